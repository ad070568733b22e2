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


def rest_in_mujoco(mjcf: Path, bodies: list[gz.Drop]) -> dict:
    """`bodies` dropped into the world `mjcf` and stepped 2 s: a report as
    the gz-physics harness gives one (`bodies`: x, y, z, speed)."""
    spec = mujoco.MjSpec.from_file(str(mjcf))
    for i, drop in enumerate(bodies):
        body = spec.worldbody.add_body(name=f"drop_{i}", pos=list(drop.start))
        body.add_freejoint()
        if drop.shape == "sphere":
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[drop.half, 0, 0], mass=0.1)
        else:
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[drop.half] * 3, mass=0.1)
    model = spec.compile()
    data = mujoco.MjData(model)
    for _ in range(round(2.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    return {
        "bodies": [
            [*data.body(f"drop_{i}").xpos, float(np.linalg.norm(data.body(f"drop_{i}").cvel[3:]))]
            for i in range(len(bodies))
        ]
    }


def rest_in_pybullet(urdf: Path, bodies: list[gz.Drop]) -> dict:
    """`bodies` dropped on the world `urdf` alone (no other ground) and
    stepped 2 s at PyBullet's 240 Hz: a report as `rest_in_mujoco`'s."""
    client = p.connect(p.DIRECT)
    try:
        p.setGravity(0, 0, -9.81, physicsClientId=client)
        p.loadURDF(str(urdf), useFixedBase=True, physicsClientId=client)
        ids = []
        for drop in bodies:
            if drop.shape == "sphere":
                shape = p.createCollisionShape(p.GEOM_SPHERE, radius=drop.half, physicsClientId=client)
            else:
                shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=[drop.half] * 3, physicsClientId=client)
            ids.append(p.createMultiBody(0.1, shape, basePosition=list(drop.start), physicsClientId=client))
        for _ in range(480):
            p.stepSimulation(physicsClientId=client)
        return {
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


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_mujoco_bodies_rest_on_the_tops(scheme: Path, tmp_path: Path) -> None:
    terrain, folder = world(scheme, tmp_path, "mujoco")
    bodies = gz.drops(terrain.elevation, terrain.block_size, 20, seed=7, ramps=terrain.ramps)
    assert gz.errors(rest_in_mujoco(folder / "mujoco" / "rse.xml", bodies), bodies) == []


@pytest.mark.parametrize("mesh", ["auto", "single"])
@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_pybullet_bodies_rest_on_the_tops(scheme: Path, mesh: str, tmp_path: Path) -> None:
    """The URDF's box set (the default) and its concave mesh alike."""
    terrain, folder = world(scheme, tmp_path, "urdf", mesh)
    bodies = gz.drops(terrain.elevation, terrain.block_size, 20, seed=7, ramps=terrain.ramps)
    assert gz.errors(rest_in_pybullet(folder / "urdf" / "rse.urdf", bodies), bodies) == []


@pytest.mark.parametrize("target", ["urdf", "mujoco"])
def test_worlds_bring_their_own_ground(target: str, tmp_path: Path) -> None:
    """Loaded alone, a world holds a body dropped on an empty cell and one
    dropped 20 m past its edge at z = its radius (before the URDF had a
    ground, PyBullet let them fall to z = -22 m)."""
    terrain, folder = world(SCHEMES / "six_obstacles.csv", tmp_path, target)
    ys, xs = np.nonzero(terrain.heights == 0)
    s = terrain.block_size
    radius = 0.03
    bodies = [
        gz.Drop("sphere", radius, (x, y, 0.1), 0.1, cell, radius)
        for x, y, cell in [((xs[0] + 0.5) * s, (ys[0] + 0.5) * s, (int(xs[0]), int(ys[0]))), (-20.0, 1.0, (-200, 10))]
    ]
    if target == "urdf":
        report = rest_in_pybullet(folder / "urdf" / "rse.urdf", bodies)
    else:
        report = rest_in_mujoco(folder / "mujoco" / "rse.xml", bodies)
    rests = [z for _, _, z, _ in report["bodies"]]
    assert rests == pytest.approx([radius] * len(bodies), abs=0.002)


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
