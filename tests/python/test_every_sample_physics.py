"""World 0 of every sample, as its files are written by default (`--mesh
auto`), in MuJoCo and PyBullet: 20 seeded spheres and boxes dropped on cell
centres rest on their cell's top within 1 cm (the judge of the gz-physics
test, tests/gz_physics/gz.py), and robots nobody here wrote (Gymnasium's
Ant in MuJoCo; pybullet_data's Husky and Laikago in PyBullet, through
bench/robots.py) run 500 steps of seeded controls with no physics error (a
state not finite, a body faster than 10 m/s, a joint 0.1 rad past its
limit)."""

from __future__ import annotations

import sys
from pathlib import Path

import mujoco
import numpy as np
import pybullet as p
import pytest

import rse
from conftest import REPO, SCHEMES

sys.path.insert(0, str(REPO / "tests" / "gz_physics"))
sys.path.insert(0, str(REPO / "bench"))
import gz  # noqa: E402
import robots  # noqa: E402

SAMPLES = sorted(SCHEMES.glob("*.csv"))


def world(scheme: Path, out: Path, targets: str, mesh: str = "auto") -> tuple[rse.Terrain, Path]:
    loaded = rse.Scheme.load(scheme)
    rse.write_worlds(loaded, out, amount=1, targets=targets, mesh=mesh)
    return loaded.generate(index=0), out / "world_0000"


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_mujoco_bodies_rest_on_the_tops(scheme: Path, tmp_path: Path) -> None:
    terrain, folder = world(scheme, tmp_path, "mujoco")
    bodies = gz.drops(terrain.elevation, terrain.block_size, 20, seed=7)
    spec = mujoco.MjSpec.from_file(str(folder / "mujoco" / "rse.xml"))
    for i, drop in enumerate(bodies):
        words = drop.line.split()
        x, y, z = map(float, words[-4:-1])
        body = spec.worldbody.add_body(name=f"drop_{i}", pos=[x, y, z])
        body.add_freejoint()
        if words[0] == "sphere":
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[gz.SPHERE_RADIUS, 0, 0], mass=0.1)
        else:
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[gz.BOX_HALF] * 3, mass=0.1)
    model = spec.compile()
    data = mujoco.MjData(model)
    for _ in range(round(2.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    report = {
        "bodies": [
            [*data.body(f"drop_{i}").xpos, float(np.linalg.norm(data.body(f"drop_{i}").cvel[3:]))]
            for i in range(len(bodies))
        ]
    }
    assert gz.errors(report, bodies) == []


@pytest.mark.parametrize("mesh", ["auto", "single"])
@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_pybullet_bodies_rest_on_the_tops(scheme: Path, mesh: str, tmp_path: Path) -> None:
    """The URDF's box set (the default) and its concave mesh alike."""
    terrain, folder = world(scheme, tmp_path, "urdf", mesh)
    bodies = gz.drops(terrain.elevation, terrain.block_size, 20, seed=7)
    client = p.connect(p.DIRECT)
    try:
        p.setGravity(0, 0, -9.81, physicsClientId=client)
        p.loadURDF(str(folder / "urdf" / "rse.urdf"), useFixedBase=True, physicsClientId=client)
        ids = []
        for drop in bodies:
            words = drop.line.split()
            if words[0] == "sphere":
                shape = p.createCollisionShape(p.GEOM_SPHERE, radius=gz.SPHERE_RADIUS, physicsClientId=client)
            else:
                shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=[gz.BOX_HALF] * 3, physicsClientId=client)
            position = [float(v) for v in words[-4:-1]]
            ids.append(p.createMultiBody(0.1, shape, basePosition=position, physicsClientId=client))
        for _ in range(480):  # 2 s at PyBullet's 240 Hz
            p.stepSimulation(physicsClientId=client)
        report = {
            "bodies": [
                [
                    *p.getBasePositionAndOrientation(i, physicsClientId=client)[0],
                    float(np.linalg.norm(p.getBaseVelocity(i, physicsClientId=client)[0])),
                ]
                for i in ids
            ]
        }
    finally:
        p.disconnect(client)
    assert gz.errors(report, bodies) == []


@pytest.mark.parametrize("target", ["urdf", "mujoco"])
def test_worlds_bring_their_own_ground(target: str, tmp_path: Path) -> None:
    """Loaded alone, a world holds a body dropped on an empty cell and one
    dropped 20 m past its edge at z = its radius (before the URDF had a
    ground, PyBullet let them fall to z = -22 m)."""
    terrain, folder = world(SCHEMES / "six_obstacles.csv", tmp_path, target)
    ys, xs = np.nonzero(terrain.heights == 0)
    s = terrain.block_size
    points = [((xs[0] + 0.5) * s, (ys[0] + 0.5) * s), (-20.0, 1.0)]
    radius = 0.03
    if target == "urdf":
        client = p.connect(p.DIRECT)
        try:
            p.setGravity(0, 0, -9.81, physicsClientId=client)
            p.loadURDF(str(folder / "urdf" / "rse.urdf"), useFixedBase=True, physicsClientId=client)
            shape = p.createCollisionShape(p.GEOM_SPHERE, radius=radius, physicsClientId=client)
            ids = [p.createMultiBody(0.1, shape, basePosition=[x, y, 0.1], physicsClientId=client) for x, y in points]
            for _ in range(480):
                p.stepSimulation(physicsClientId=client)
            rests = [p.getBasePositionAndOrientation(i, physicsClientId=client)[0][2] for i in ids]
        finally:
            p.disconnect(client)
    else:
        spec = mujoco.MjSpec.from_file(str(folder / "mujoco" / "rse.xml"))
        for i, (x, y) in enumerate(points):
            body = spec.worldbody.add_body(name=f"drop_{i}", pos=[x, y, 0.1])
            body.add_freejoint()
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[radius, 0, 0], mass=0.1)
        model = spec.compile()
        data = mujoco.MjData(model)
        for _ in range(round(2.0 / model.opt.timestep)):
            mujoco.mj_step(model, data)
        rests = [data.body(f"drop_{i}").xpos[2] for i in range(len(points))]
    assert rests == pytest.approx([radius] * len(points), abs=0.002)


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_robots_run_without_physics_errors(scheme: Path, tmp_path: Path) -> None:
    field = robots.Field(scheme.stem, rse.Scheme.load(scheme))
    runs = {
        "ant": robots.run_mujoco("ant", field, "boxes", steps=500, seed=0),
        "husky": robots.run_pybullet("husky", field, "boxes", steps=500, seed=0, tmp=tmp_path),
        "laikago": robots.run_pybullet("laikago", field, "boxes", steps=500, seed=0, tmp=tmp_path),
    }
    assert {name: run.errors for name, run in runs.items()} == {name: 0 for name in runs}
    assert all(run.contacts > 0 for run in runs.values()), runs
