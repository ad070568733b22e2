"""Ramps in the simulators that load our worlds: MuJoCo (the box set with a
convex wedge per ramp, and the height field) and PyBullet (the URDF's
concave mesh) find each ramp's plane where `Terrain.height_at` says it is;
the box set alone holds the staircase under it (docs/schemes.md, "Ramps")."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pybullet as p
import pytest

import rse
from conftest import SCHEMES

RAMPS = SCHEMES / "mix_ramps.csv"


def worlds(out: Path, **options: object) -> tuple[rse.Terrain, Path]:
    scheme = rse.Scheme.load(RAMPS)
    rse.write_worlds(scheme, out, amount=1, **options)
    return scheme.generate(index=0), out / "world_0000"


def inside_ramps(terrain: rse.Terrain, count: int, margin: float) -> np.ndarray:
    """`count` seeded points over the ramps, `margin` metres inside their
    rectangles' edges, as (x, y) rows."""
    rng = np.random.default_rng(3)
    s = terrain.block_size
    points = []
    for i in range(count):
        x0, y0, x1, y1 = terrain.ramps[i % len(terrain.ramps)]["cells"]
        points.append(rng.uniform([x0 * s + margin, y0 * s + margin], [(x1 + 1) * s - margin, (y1 + 1) * s - margin]))
    return np.array(points)


def mujoco_ray(model: mujoco.MjModel, data: mujoco.MjData, x: float, y: float) -> float:
    geomid = np.zeros(1, dtype=np.int32)
    # Group 0 to 3: the colliders, whichever group the world hides them in.
    groups = np.array([1, 1, 1, 1, 0, 0], dtype=np.uint8)
    dist = mujoco.mj_ray(model, data, np.array([x, y, 20.0]), np.array([0.0, 0.0, -1.0]), groups, 1, -1, geomid)
    assert dist >= 0
    return 20.0 - dist


def colliders_only(model: mujoco.MjModel) -> None:
    """Takes the drawn mesh (contype 0) out of ray casts."""
    for i in range(model.ngeom):
        if model.geom_contype[i] == 0 and model.geom_conaffinity[i] == 0:
            model.geom_group[i] = 5


@pytest.mark.parametrize("mesh", ["single", "blocks"])
def test_mujoco_collides_with_each_ramps_plane(tmp_path: Path, mesh: str) -> None:
    terrain, world = worlds(tmp_path, targets="mujoco", mesh=mesh)
    assert len(terrain.ramps) == 5, "four rows, a crossing pair among them"
    model = mujoco.MjModel.from_xml_path(str(world / "mujoco" / "rse.xml"))
    colliders_only(model)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    for x, y in inside_ramps(terrain, 200, 1e-3):
        assert mujoco_ray(model, data, x, y) == pytest.approx(terrain.height_at(x, y), abs=1e-6), (x, y)


def test_mujocos_height_field_holds_the_planes(tmp_path: Path) -> None:
    terrain, world = worlds(tmp_path, targets="mujoco", mujoco_collider="hfield", oversample=4)
    model = mujoco.MjModel.from_xml_path(str(world / "mujoco" / "rse.xml"))
    colliders_only(model)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    # Half a sample (an eighth of a cell) from a ramp's edge the field is
    # the plane itself: its samples lie on it and it is linear between them.
    for x, y in inside_ramps(terrain, 200, terrain.block_size / 8 + 1e-6):
        assert mujoco_ray(model, data, x, y) == pytest.approx(terrain.height_at(x, y), abs=1e-5), (x, y)


def pybullet_ray(client: int, x: float, y: float) -> float:
    ((_, _, fraction, hit, _),) = p.rayTest([x, y, 20.0], [x, y, -1.0], physicsClientId=client)
    return hit[2]


def plane(terrain: rse.Terrain, ramp: dict, x: float, y: float) -> float:
    """`ramp`'s plane at (x, y) metres, from its dict alone."""
    x0, y0, x1, y1 = ramp["cells"]
    s = terrain.block_size
    lo, hi, at = (y0, y1 + 1, y / s) if ramp["along_y"] else (x0, x1 + 1, x / s)
    t = (at - lo if ramp["ascending"] else hi - at) / (hi - lo)
    return terrain.base + ramp["rise"] * terrain.step_height * t


def pybullet_ray(client: int, x: float, y: float) -> float:
    ((_, _, _, hit, _),) = p.rayTest([x, y, 20.0], [x, y, -1.0], physicsClientId=client)
    return hit[2]


@pytest.mark.parametrize("mesh", ["single", "blocks"])
def test_pybullet_finds_the_plane_in_the_mesh_and_the_staircase_in_the_boxes(tmp_path: Path, mesh: str) -> None:
    terrain, world = worlds(tmp_path, targets="urdf", mesh=mesh)
    client = p.connect(p.DIRECT)
    try:
        p.loadURDF(str(world / "urdf" / "rse.urdf"), useFixedBase=True, physicsClientId=client)
        for x, y in inside_ramps(terrain, 200, 1e-3):
            hit, top = pybullet_ray(client, x, y), terrain.height_at(x, y)
            if mesh == "single":
                assert hit == pytest.approx(top, abs=1e-4), (x, y)
            else:
                # The box set: the staircase under the plane, lower by at
                # most a step and the plane's climb across one cell.
                (ramp,) = [r for r in terrain.ramps if covers(terrain, r, x, y)]
                x0, y0, x1, y1 = ramp["cells"]
                run = (y1 - y0 + 1) if ramp["along_y"] else (x1 - x0 + 1)
                climb = ramp["rise"] * terrain.step_height / run
                assert top - terrain.step_height - climb - 1e-4 <= hit <= top + 1e-4, (x, y)
    finally:
        p.disconnect(client)


def covers(terrain: rse.Terrain, ramp: dict, x: float, y: float) -> bool:
    x0, y0, x1, y1 = ramp["cells"]
    s = terrain.block_size
    return x0 * s <= x <= (x1 + 1) * s and y0 * s <= y <= (y1 + 1) * s


def test_a_ramps_staircase_lies_under_its_plane_within_a_step() -> None:
    terrain = rse.Scheme.load(RAMPS).generate(index=0)
    s = terrain.block_size
    for ramp in terrain.ramps:
        x0, y0, x1, y1 = ramp["cells"]
        for y in range(y0, y1 + 1):
            for x in range(x0, x1 + 1):
                # The plane's lowest point on the cell is at one of its corners.
                low = min(plane(terrain, ramp, u * s, v * s) for u in (x, x + 1) for v in (y, y + 1))
                assert low - terrain.step_height - 1e-9 < terrain.elevation[y, x] <= low + 1e-9
                centre = ((x + 0.5) * s, (y + 0.5) * s)
                assert terrain.height_at(*centre) == pytest.approx(plane(terrain, ramp, *centre), abs=1e-12)
