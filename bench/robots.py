"""Robots nobody here wrote on rse terrains, in the real engines (after
the paper's §4): steps per second against a plane, contacts per step
and physics errors, for every collider rse can write beside the naive
box-per-cell baseline. Printed, not asserted.

Robots: Gymnasium's Ant and Humanoid models (MuJoCo), pybullet_data's Husky
and Laikago (PyBullet), driven by fixed seeded controls so that they move
over the blocks. Terrains: the paper's sizes 10x10, 15x60 and 50x50 (random
0..2 steps under a gaussian of 3) and a random 50x50 field of height 4, each
centred on the robot's start. Colliders: MuJoCo: rse's box set (what its
MJCF collides), a height field at k = 2 and 4, a box per cell; PyBullet:
rse's URDF with the concave single mesh (`--mesh single`), rse's URDF with
the box set (the default), a box per cell.

Physics errors per run, at the end: a state that is not finite, a body
faster than 10 m/s, a limited joint more than 0.1 rad past its limit. The
deepest contact of the run (MuJoCo: every step; PyBullet: every 100th) is
printed beside them, not counted: MuJoCo's soft contacts let these robots,
flailing at their models' time steps, sink 2-3 cm into a plane too, so depth
is read against the plane's row. Bodies at rest on the tops are judged
within 1 cm where that is meaningful: the rapier smoke test (`check
--physics`), tests/python/test_gz_physics.py (gz-physics DART and Bullet),
and the sphere tests of tests/python/test_worlds.py and test_curricula.py
(MuJoCo, PyBullet).

Run: .venv/bin/python bench/robots.py [--steps N] [--repeats R] [--engine MuJoCo|PyBullet]
"""

from __future__ import annotations

import argparse
import contextlib
import os
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

import mujoco
import numpy as np
import pybullet as p
import pybullet_data
import rse
import rse.mujoco


@dataclass
class Run:
    """One run: steps/s, contacts per step, physics errors, the terrain's
    collision shapes, the deepest contact (metres)."""

    rate: float
    contacts: float
    errors: int
    shapes: int
    deepest: float


@dataclass
class Field:
    name: str
    scheme: Optional[rse.Scheme]  # None: the plane alone

    @property
    def terrain(self) -> Optional[rse.Terrain]:
        return None if self.scheme is None else self.scheme.generate(index=0)


def fields() -> list[Field]:
    paper = [rse.Obstacle("random", height=2), rse.Obstacle("gaussian", height=3)]
    out = [Field("plane", None)]
    for nx, ny in [(10, 10), (15, 60), (50, 50)]:
        out.append(Field(f"{nx}x{ny}", rse.Scheme(paper, size=(nx, ny))))
    out.append(Field("random H4 50x50", rse.Scheme([rse.Obstacle("random", height=4)], size=(50, 50))))
    return out


def half_extent(terrain: rse.Terrain) -> tuple[float, float]:
    ny, nx = terrain.heights.shape
    return nx * terrain.block_size / 2, ny * terrain.block_size / 2


def top_under(terrain: Optional[rse.Terrain], x: float, y: float) -> float:
    """The top under a world point; the terrain is centred on the origin."""
    if terrain is None:
        return 0.0
    cx, cy = half_extent(terrain)
    i, j = int((x + cx) // terrain.block_size), int((y + cy) // terrain.block_size)
    ny, nx = terrain.heights.shape
    return float(terrain.elevation[j, i]) if 0 <= i < nx and 0 <= j < ny else 0.0


def start_height(terrain: Optional[rse.Terrain], reach: float) -> float:
    """The highest top within `reach` of the start."""
    grid = np.linspace(-reach, reach, 9)
    return max(top_under(terrain, x, y) for x in grid for y in grid)


def cell_boxes(terrain: rse.Terrain) -> list[tuple[float, ...]]:
    """A box per cell with height: centre and half sizes, grid frame."""
    s = terrain.block_size
    ny, nx = terrain.heights.shape
    return [
        ((x + 0.5) * s, (y + 0.5) * s, terrain.elevation[y, x] / 2, s / 2, s / 2, terrain.elevation[y, x] / 2)
        for y in range(ny)
        for x in range(nx)
        if terrain.elevation[y, x] > 0
    ]


# --- MuJoCo -------------------------------------------------------------------


def mujoco_model(robot: str, field: Field, collider: str) -> mujoco.MjModel:
    from gymnasium.envs.mujoco import ant_v5

    spec = mujoco.MjSpec.from_file(str(Path(ant_v5.__file__).parent / "assets" / f"{robot}.xml"))
    terrain = field.terrain
    if terrain is None:
        return spec.compile()
    cx, cy = half_extent(terrain)
    if collider.startswith("hfield"):
        k = int(collider.split("=")[1])
        rse.mujoco.add_hfield(spec, field.scheme, k, elevation=max(float(terrain.elevation.max()), 0.01))
        model = spec.compile()
        rse.mujoco.set_hfield(model, "terrain", terrain, k)
        return model
    rows = terrain.boxes() if collider == "boxes" else cell_boxes(terrain)
    for x, y, z, hx, hy, hz in rows:
        spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, pos=[x - cx, y - cy, z], size=[hx, hy, hz],
                                conaffinity=1, condim=3, group=2)  # fmt: skip
    return spec.compile()


def run_mujoco(robot: str, field: Field, collider: str, steps: int, seed: int) -> Run:
    model = mujoco_model(robot, field, collider)
    terrain = field.terrain
    data = mujoco.MjData(model)
    data.qpos[2] += start_height(terrain, 0.6)
    mujoco.mj_forward(model, data)
    controls = np.random.default_rng(seed).uniform(-1, 1, (steps, model.nu))
    ncon = 0
    deepest = 0.0
    t = time.perf_counter()
    for u in controls:
        data.ctrl[:] = u
        mujoco.mj_step(model, data)
        ncon += data.ncon
        if data.ncon:
            deepest = max(deepest, -float(data.contact.dist[: data.ncon].min()))
    rate = steps / (time.perf_counter() - t)
    errors = int(not np.all(np.isfinite(data.qpos)))
    for b in range(1, model.nbody):
        errors += int(np.linalg.norm(data.cvel[b][3:]) > 10)
    for j in range(model.njnt):
        if model.jnt_limited[j] and model.jnt_type[j] in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE):
            q, (lo, hi) = data.qpos[model.jnt_qposadr[j]], model.jnt_range[j]
            errors += int(q < lo - 0.1 or q > hi + 0.1)
    # The terrain's geoms are the ones in group 2.
    return Run(rate, ncon / steps, errors, int((model.geom_group == 2).sum()), deepest)


# --- PyBullet -----------------------------------------------------------------


@contextlib.contextmanager
def quiet_stdout():
    """PyBullet's URDF importer prints a warning per link without inertia
    (Husky has several) from C, on file descriptor 1: hide those."""
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(saved, 1)
            os.close(saved)


def pybullet_terrain(client: int, field: Field, collider: str, tmp: Path) -> int:
    """Loads the ground and the terrain; returns the terrain's collision shapes.
    rse's URDF brings its own ground: pybullet_data's plane only without it."""
    terrain = field.terrain
    if terrain is None or collider not in ("mesh", "boxes"):
        p.loadURDF("plane.urdf", physicsClientId=client)
    if terrain is None:
        return 0
    cx, cy = half_extent(terrain)
    if collider in ("mesh", "boxes"):
        out = tmp / f"{field.name}-{collider}".replace(" ", "_")
        rse.write_worlds(field.scheme, out, amount=1, targets="urdf", mesh="single" if collider == "mesh" else "blocks")
        urdf = out / "world_0000" / "urdf" / "rse.urdf"
        p.loadURDF(str(urdf), basePosition=[-cx, -cy, 0], useFixedBase=True, physicsClientId=client)
        return 1 if collider == "mesh" else len(terrain.boxes())
    rows = cell_boxes(terrain)
    for x, y, z, hx, hy, hz in rows:
        shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=[hx, hy, hz], physicsClientId=client)
        p.createMultiBody(0, shape, basePosition=[x - cx, y - cy, z], physicsClientId=client)
    return len(rows)


def run_pybullet(robot: str, field: Field, collider: str, steps: int, seed: int, tmp: Path) -> Run:
    client = p.connect(p.DIRECT)
    try:
        p.setAdditionalSearchPath(pybullet_data.getDataPath(), physicsClientId=client)
        p.setGravity(0, 0, -9.81, physicsClientId=client)
        terrain = field.terrain
        with quiet_stdout():
            shapes = pybullet_terrain(client, field, collider, tmp)
            if robot == "husky":
                body = p.loadURDF("husky/husky.urdf", [0, 0, start_height(terrain, 0.5) + 0.2], physicsClientId=client)
            else:
                body = p.loadURDF("laikago/laikago_toes_zup.urdf", [0, 0, start_height(terrain, 0.4) + 0.5],
                                  physicsClientId=client)  # fmt: skip
        joints = [j for j in range(p.getNumJoints(body, physicsClientId=client))
                  if p.getJointInfo(body, j, physicsClientId=client)[2] == p.JOINT_REVOLUTE]  # fmt: skip
        phases = np.random.default_rng(seed).uniform(0, 2 * np.pi, len(joints))
        ncon = 0
        deepest = 0.0
        t = time.perf_counter()
        for i in range(steps):
            if robot == "husky":
                p.setJointMotorControlArray(body, joints, p.VELOCITY_CONTROL, targetVelocities=[6.0] * len(joints),
                                            forces=[60.0] * len(joints), physicsClientId=client)  # fmt: skip
            else:
                targets = 0.4 * np.sin(2 * np.pi * 1.5 * i / 240 + phases)
                p.setJointMotorControlArray(body, joints, p.POSITION_CONTROL, targetPositions=targets,
                                            physicsClientId=client)  # fmt: skip
            p.stepSimulation(physicsClientId=client)
            if i % 100 == 0:
                contacts = p.getContactPoints(physicsClientId=client)
                ncon += len(contacts) * 100
                # Field 8: the contact distance, negative when overlapping.
                deepest = max([deepest] + [-c[8] for c in contacts])
        rate = steps / (time.perf_counter() - t)
        errors = 0
        for link in range(-1, p.getNumJoints(body, physicsClientId=client)):
            if link < 0:
                v, _ = p.getBaseVelocity(body, physicsClientId=client)
            else:
                v = p.getLinkState(body, link, computeLinkVelocity=1, physicsClientId=client)[6]
            errors += int(not np.all(np.isfinite(v)) or np.linalg.norm(v) > 10)
        for j in joints:
            info = p.getJointInfo(body, j, physicsClientId=client)
            lo, hi = info[8], info[9]
            q = p.getJointState(body, j, physicsClientId=client)[0]
            if lo < hi:
                errors += int(q < lo - 0.1 or q > hi + 0.1)
        return Run(rate, ncon / steps, errors, shapes, deepest)
    finally:
        p.disconnect(client)


# --- the table ----------------------------------------------------------------

ENGINES = {
    "MuJoCo": (["ant", "humanoid"], ["boxes", "hfield k=2", "hfield k=4", "box per cell"]),
    "PyBullet": (["husky", "laikago"], ["mesh", "boxes", "box per cell"]),
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--engine", choices=sorted(ENGINES), help="one engine's rows only [default: both]")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for engine, (robots, colliders) in ENGINES.items():
            if args.engine not in (None, engine):
                continue
            for robot in robots:
                print(f"\n{engine} {robot}: steps/s median [min-max] of {args.repeats}, x plane, contacts/step, "
                      f"physics errors, terrain shapes, deepest contact mm")  # fmt: skip
                plane_rate = None
                for field in fields():
                    for collider in ["plane"] if field.scheme is None else colliders:
                        runs = [
                            run_mujoco(robot, field, collider, args.steps, r)
                            if engine == "MuJoCo"
                            else run_pybullet(robot, field, collider, args.steps, r, Path(tmp))
                            for r in range(args.repeats)
                        ]
                        rates = [run.rate for run in runs]
                        med = statistics.median(rates)
                        plane_rate = plane_rate or med
                        print(f"  {field.name:<16} {collider:<13} {med:>8,.0f} [{min(rates):,.0f}-{max(rates):,.0f}]"
                              f"  {med / plane_rate:4.2f}x  {statistics.median(r.contacts for r in runs):5.1f}"
                              f"  {sum(r.errors for r in runs):3d}  {runs[0].shapes:5d}"
                              f"  {max(r.deepest for r in runs) * 1e3:5.1f}")  # fmt: skip


if __name__ == "__main__":
    main()
