"""Gazebo classic 11 itself (gzserver 11.1 from Debian bullseye, in a chroot
made by gz11.py) loads `gazebo-classic` worlds with no SDF error or warning,
and bodies rest on the target's default collider. Run by `make
test-gazebo-classic` (needs root; not in `make test`)."""

from __future__ import annotations

import shutil
import subprocess
import time
from pathlib import Path

import drops
import gz11
import pytest

RSE_GEN = gz11.REPO / "target" / "release" / "rse-gen"
SCHEMES = gz11.REPO / "schemes"
EMPTY = "# size: 6x4\ntype,height\n"
# Long enough for the largest sample (2500 boxes) to load here: a world cut
# short loads no terrain, and the state log says so.
LOAD_SECONDS = 12
# (scheme, --mesh): the default collider (auto: the box set), the single
# mesh, framed pallets, and an empty terrain (a model with no collider).
CASES = [
    ("six_obstacles", "auto"),
    ("six_obstacles", "single"),
    ("nist_hill", "auto"),
    ("paper_pallets", "single"),
    ("empty", "auto"),
]


@pytest.fixture(scope="session")
def root() -> Path:
    return gz11.ensure_root()


def batch(tmp: Path, scheme: str, mesh: str, targets: str = "gazebo-classic") -> Path:
    """`rse-gen batch` of a sample scheme (or the empty one) into `tmp`; its first world."""
    source = tmp / "empty.csv" if scheme == "empty" else SCHEMES / f"{scheme}.csv"
    if scheme == "empty":
        source.write_text(EMPTY)
    out = tmp / f"{scheme}-{mesh}"
    subprocess.run(
        [str(RSE_GEN), "batch", str(source), "-o", str(out), "--amount", "1", "--target", targets, "--mesh", mesh],
        check=True,
        capture_output=True,
    )
    return out / "world_0000"


def load(root: Path, folder: Path, world_file: str = "rse.world", model_path: bool = True) -> tuple[str, str]:
    """Runs `folder/world_file` in gzserver --verbose for LOAD_SECONDS (no
    `gz` tool connects: its own transport warnings are not the world's),
    then stops it; its log, and the world as Gazebo loaded it (the state
    log's copy)."""
    with gz11.staged(root, folder) as inside:
        # Without the model path, run from elsewhere: Gazebo also looks in
        # the folder it runs in.
        elsewhere = {} if model_path else {"model_path": "/nowhere", "cwd": "/"}
        world = world_file if model_path else f"{inside}/{world_file}"
        with gz11.Gzserver(root, inside, world, record=True, **elsewhere) as server:
            time.sleep(LOAD_SECONDS)
        return server.log, server.recorded()


@pytest.mark.parametrize("scheme, mesh", CASES, ids=[f"{s}-{m}" for s, m in CASES])
def test_gzserver_loads_a_classic_world_with_no_error_or_warning(root: Path, tmp_path: Path, scheme: str, mesh: str) -> None:
    world = batch(tmp_path, scheme, mesh)
    log, loaded = load(root, world / "gazebo-classic")
    assert "Connected to gazebo master" in log, log
    assert gz11.problems(log) == [], log
    # What Gazebo made of it: the terrain model with every collider our SDF
    # has, and the mesh drawn once.
    ours = (world / "gazebo-classic/rse_terrain/model.sdf").read_text()
    assert "<model name='rse_terrain'>" in loaded, loaded[:2000]
    terrain = loaded.split("<model name='rse_terrain'>", 1)[1].split("</model>", 1)[0]
    assert terrain.count("<collision name='box_") == ours.count('<collision name="box_')
    assert terrain.count("<collision name='collision'>") == ours.count('<collision name="collision">')
    assert terrain.count("<visual name='visual'>") == ours.count('<visual name="visual">') == (scheme != "empty")
    assert terrain.count("model://rse_terrain/meshes/terrain.obj") == ours.count("model://rse_terrain/meshes/terrain.obj")
    assert "<sdf version ='1.7'>" in loaded


def test_the_judge_sees_what_gazebo_11_says_of_a_gazebo_sim_world(root: Path, tmp_path: Path) -> None:
    """The negative control: our SDF 1.9 `gazebo` world gives Gazebo 11's
    conversion errors, and a classic world whose model is not on the model
    path its missing include; the judge reports both."""
    world = batch(tmp_path, "wall", "auto", targets="gazebo,gazebo-classic")
    said = gz11.problems(load(root, world / "gazebo")[0])
    assert any("Unable to convert from SDF version 1.9 to 1.7" in line for line in said), said
    said = gz11.problems(load(root, world / "gazebo-classic", model_path=False)[0])
    assert any("model://rse_terrain" in line for line in said), said


def sphere_moves(root: Path, tmp_path: Path, mesh: str) -> list[float]:
    """How far 20 spheres placed on six_obstacles' mesh diagonals move in
    5 s on the `mesh` collider of the same world."""
    meshed = batch(tmp_path / "meshed", "six_obstacles", "single")
    points = drops.places(meshed, 20, seed=0)
    assert len(points) == 20
    world = meshed if mesh == "single" else batch(tmp_path / "default", "six_obstacles", mesh)
    spheres = [drops.Sphere(x, y, top, 0.0) for x, y, top, _, _ in points]
    moved, _ = drops.run(root, world, spheres)
    return moved


def test_bodies_on_interior_edges_stay_put_on_the_default_collider(root: Path, tmp_path: Path) -> None:
    """The classic target's default (`auto`: the box set) holds spheres
    resting exactly where the mesh has an interior edge."""
    moved = sphere_moves(root, tmp_path, "auto")
    assert max(moved) <= drops.SLID, moved


def test_odes_mesh_rolls_bodies_off_interior_edges(root: Path, tmp_path: Path) -> None:
    """Why the default is the box set: on the single mesh, ODE rolls some of
    the same spheres away (its contacts on an edge shared by two coplanar
    triangles push sideways). Should a Gazebo release stop doing so, this
    fails, and the default is worth measuring again
    (bench/gazebo_classic_contacts.py)."""
    moved = sphere_moves(root, tmp_path, "single")
    assert sum(m > drops.SLID for m in moved) >= 1, moved


def test_the_chroot_is_gazebo_11(root: Path) -> None:
    assert gz11.gazebo_version(root).startswith("11."), gz11.gazebo_version(root)
    assert shutil.which("chroot")
