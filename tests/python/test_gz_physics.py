"""Gazebo's own physics on our Gazebo worlds: gz-physics 5 from Debian
(tests/gz_physics/harness.cc builds the terrain model as gz-sim's Physics
system does), 20 seeded bodies dropped on cell centres, 5 s at 1 kHz: every
body must rest on the top of its cell within 1 cm, in DART with the mesh and
with the box set, and in Bullet with the box set (Bullet's 1 cm collision
margin holds bodies about 1 cm above a mesh, so its mesh is not judged)."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

import rse
from conftest import REPO, SCHEMES

sys.path.insert(0, str(REPO / "tests" / "gz_physics"))
import gz  # noqa: E402

# Needs what only `make test` installs (Debian packages, a browser, or
# the wheels' build): not in `make test-quick`.
pytestmark = pytest.mark.thirdparty

SAMPLES = sorted(SCHEMES.glob("*.csv"))
CASES = [("dartsim", "single"), ("dartsim", "blocks"), ("bullet", "blocks")]


@pytest.fixture(scope="module")
def harness(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return gz.build(tmp_path_factory.mktemp("gz"))


def world(scheme: Path, out: Path, mesh: str) -> tuple[rse.Terrain, Path]:
    loaded = rse.Scheme.load(scheme)
    rse.write_worlds(loaded, out, amount=1, targets="gazebo", mesh=mesh)
    return loaded.generate(index=0), out / "world_0000" / "gazebo" / "rse_terrain" / "model.sdf"


@pytest.mark.parametrize("engine, mesh", CASES, ids=[f"{e}-{m}" for e, m in CASES])
@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_bodies_rest_on_the_tops(harness: Path, scheme: Path, engine: str, mesh: str, tmp_path: Path) -> None:
    terrain, model = world(scheme, tmp_path, mesh)
    bodies = gz.drops(terrain.elevation, terrain.block_size, 20, seed=7, ramps=terrain.ramps)
    report = gz.run(harness, engine, model, bodies, seconds=5.0)
    assert len(report["bodies"]) == len(bodies)
    assert gz.errors(report, bodies) == []


def test_a_terrain_without_tops_is_caught(harness: Path, tmp_path: Path) -> None:
    """The negative control: the mesh with every upward face taken off lets
    the bodies through, and the judge says so."""
    terrain, model = world(SCHEMES / "six_obstacles.csv", tmp_path, "single")
    obj = model.parent / "meshes" / "terrain.obj"
    text = obj.read_text()
    up = next(i + 1 for i, line in enumerate(l for l in text.splitlines() if l.startswith("vn ")) if line == "vn 0 0 1")
    holed = "".join(l for l in text.splitlines(keepends=True) if not re.match(rf"f .*//{up}\b", l))
    assert len(holed) < len(text)
    obj.write_text(holed)
    bodies = gz.drops(terrain.elevation, terrain.block_size, 20, seed=7)
    found = gz.errors(gz.run(harness, "dartsim", model, bodies, seconds=5.0), bodies)
    on_solid = sum(terrain.elevation[d.cell[1], d.cell[0]] > 0 for d in bodies)
    assert on_solid > 0 and len(found) >= on_solid, found
