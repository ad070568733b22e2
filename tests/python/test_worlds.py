"""Worlds of `rse-gen batch` loaded by the simulators' own parsers: libsdformat (`ign sdf -k` and a
strict checker linked against it), MuJoCo, PyBullet and usd-core; Webots,
which has no installable checker, parsed structurally."""

import hashlib
import json
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import mujoco
import numpy as np
import pybullet as p
import pytest
import rse
from conftest import REPO, SCHEMES, heights, run, units
from pxr import Usd, UsdGeom, UsdPhysics

ALL_TARGETS = ",".join(rse.TARGETS)
MODES = ["single", "blocks"]
WORLD_SCHEMES = ["six_obstacles", "wall", "paper_pallets", "gaussian", "nist_diagonal_hill", "mix_ramps"]
AMOUNT = 2


@pytest.fixture(scope="session")
def batches(tmp_path_factory: pytest.TempPathFactory) -> dict[tuple[str, str], Path]:
    """Two worlds of each scheme in each mesh mode, every target; plus an
    empty terrain (no obstacles) and an atlas."""
    root = tmp_path_factory.mktemp("batches")
    empty = root / "empty.csv"
    empty.write_text("# size: 6x4\ntype,height\n")
    found = {}
    for scheme in [*(SCHEMES / f"{s}.csv" for s in WORLD_SCHEMES), empty]:
        for mode in MODES:
            out = root / f"{scheme.stem}-{mode}"
            run("batch", str(scheme), "-o", str(out), "--amount", str(AMOUNT), "--target", ALL_TARGETS, "--mesh", mode)
            found[(scheme.stem, mode)] = out
    # An atlas is a world like any other: every check below applies to it.
    for mode in MODES:
        out = root / f"atlas-{mode}"
        run(
            "atlas", str(SCHEMES / "six_obstacles.csv"), str(SCHEMES / "curriculum.csv"), "--size", "50x50", "--step-height", "0.1",
            "--rows", "2", "--cols", "2", "--border", "2", "--flat-patches", "2",
            "-o", str(out / "world_atlas"), "--target", ALL_TARGETS, "--mesh", mode,
        )  # fmt: skip
        found[("atlas", mode)] = out
    return found


def worlds(batches: dict[tuple[str, str], Path], mode: str | None = None) -> list[Path]:
    """Every world of the batches, or of those in one mesh mode."""
    return sorted(w for (_, m), out in batches.items() if mode in (None, m) for w in out.glob("world_*"))



def manifest(world: Path) -> dict:
    return json.loads((world / "rse.json").read_text())


def ramp_tops(world: Path) -> list[float]:
    """The top of each ramp of a world of full difficulty, from its
    manifest (crossing ramps are two, of one height), metres."""
    m = manifest(world)
    base, step = m["globals"]["base"], m["globals"]["step_height"]
    tops = []
    for d in m["drawn"]:
        if d["kind"] in ("ramp", "crossing_ramps") and d["height"] > 0:
            (x1, y1), (x2, y2) = d["p1"], d["p2"]
            along_y = abs(y2 - y1) > abs(x2 - x1)
            pair = d["kind"] == "crossing_ramps" and (x1 != x2 if along_y else y1 != y2)
            tops += [base + d["height"] * step] * (2 if pair else 1)
    return tops


GAZEBOS = {"gazebo": 1.9, "gazebo-classic": 1.7}


def sdf_files(world: Path, gazebos=GAZEBOS) -> list[Path]:
    """Each Gazebo target's world and model SDF."""
    return [world / g / f for g in gazebos for f in ("rse.world", "rse_terrain/model.sdf")]


# --- the folder itself -------------------------------------------------------


def test_every_file_is_in_the_manifest_with_its_hash(batches) -> None:
    for world in worlds(batches):
        files = {str(f.relative_to(world)) for f in world.rglob("*") if f.is_file()}
        listed = manifest(world)["files"]
        assert files == set(listed) | {"rse.json"}, world
        for path, digest in listed.items():
            assert hashlib.sha256((world / path).read_bytes()).hexdigest() == digest, f"{world}/{path}"


def test_no_file_holds_an_absolute_path(batches) -> None:
    for world in worlds(batches):
        for f in world.rglob("*"):
            if f.is_file() and f.suffix != ".png":
                text = f.read_text()
                assert str(world.parent) not in text and str(REPO) not in text, f
                assert not re.search(r'(uri>|url \[\s*"|filename="|file=")/', text), f


def test_heightmap_is_the_one_rse_gen_heightmap_prints(batches) -> None:
    for stem in WORLD_SCHEMES:
        for world in sorted(batches[(stem, "single")].glob("world_*")):
            m = manifest(world)
            expected = run("heightmap", str(SCHEMES / f"{stem}.csv"), "--seed", str(m["seed"]), "--index", str(m["index"]))
            assert (world / "heightmap.csv").read_text() == expected


# --- Gazebo: libsdformat ------------------------------------------------------


@pytest.mark.thirdparty
def test_every_sdf_passes_ign_sdf_check(batches) -> None:
    ign = shutil.which("ign")
    assert ign, "ign (Debian ignition-tools) is installed by the test command"
    for world in worlds(batches):
        for f in sdf_files(world):
            done = subprocess.run([ign, "sdf", "-k", str(f)], capture_output=True, text=True, cwd=f.parent)
            assert done.returncode == 0 and "Valid" in done.stdout, f"{f}: {done.stdout}{done.stderr}"


@pytest.fixture(scope="session")
def sdf_check() -> Path:
    """tests/sdf_check: libsdformat with unknown elements and warnings as errors."""
    source = REPO / "tests/sdf_check/sdf_check.cc"
    binary = REPO / "target/sdf_check"
    if not binary.exists() or binary.stat().st_mtime < source.stat().st_mtime:
        flags = subprocess.run(
            ["pkg-config", "--cflags", "--libs", "sdformat12"], capture_output=True, text=True, check=True
        ).stdout.split()
        subprocess.run(["g++", "-O1", str(source), *flags, "-o", str(binary)], check=True)
    return binary


@pytest.mark.thirdparty
def test_every_sdf_passes_the_strict_libsdformat_check(batches, sdf_check: Path) -> None:
    files = [str(f) for world in worlds(batches) for f in sdf_files(world)]
    done = subprocess.run([str(sdf_check), *files], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


@pytest.mark.thirdparty
def test_the_strict_check_fails_on_what_ign_lets_pass(batches, sdf_check: Path, tmp_path: Path) -> None:
    world = next(iter(sorted(batches[("wall", "single")].glob("world_*"))))
    copy = tmp_path / "gazebo"
    shutil.copytree(world / "gazebo", copy)
    model = copy / "rse_terrain/model.sdf"
    model.write_text(model.read_text().replace("<static>true</static>", "<statik>true</statik>"))
    assert subprocess.run([str(sdf_check), str(model)], capture_output=True).returncode == 1
    (copy / "rse_terrain/meshes/terrain.obj").unlink()
    done = subprocess.run([str(sdf_check), str(copy / "rse.world")], capture_output=True, text=True)
    assert done.returncode == 1 and "not found" in done.stderr


def test_sdf_versions_are_what_each_gazebo_reads(batches) -> None:
    """Gazebo Sim's files are SDF 1.9; Gazebo classic 11's (libsdformat 9)
    1.7 at most in every file, `model.config`'s `<sdf version>` included:
    Gazebo 11 refuses to convert anything newer."""
    for world in worlds(batches):
        for gazebo, highest in GAZEBOS.items():
            for f in sdf_files(world, [gazebo]):
                version = ET.parse(f).getroot().get("version")
                assert version and float(version) <= highest, f
            config = ET.parse(world / gazebo / "rse_terrain/model.config").getroot().find("sdf")
            assert config is not None and float(config.get("version") or "inf") <= highest, world / gazebo
            assert config.text == "model.sdf"


def tree(folder: Path) -> dict[str, bytes]:
    return {str(f.relative_to(folder)): f.read_bytes() for f in sorted(folder.rglob("*")) if f.is_file()}


def test_gazebo_classic_from_python_and_the_cli_is_the_same_bytes_every_run_and_checks_good(tmp_path: Path) -> None:
    """`targets="gazebo-classic"` in Python and `--target gazebo-classic` on
    the command line: the same files, byte for byte, run after run; `check`
    passes them; by default the box set collides and the mesh is drawn."""
    scheme = SCHEMES / "six_obstacles.csv"
    runs = []
    for i in range(2):
        rse.write_worlds(rse.Scheme.load(scheme), tmp_path / f"py{i}", amount=2, targets="gazebo-classic")
        runs.append(tree(tmp_path / f"py{i}"))
    run("batch", str(scheme), "-o", str(tmp_path / "cli"), "--amount", "2", "--target", "gazebo-classic")
    runs.append(tree(tmp_path / "cli"))
    assert runs[0] == runs[1] == runs[2]
    assert {p.split("/", 1)[1] for p in runs[0]} == {
        "rse.json",
        "heightmap.csv",
        "preview.png",
        "gazebo-classic/rse.world",
        "gazebo-classic/rse_terrain/model.config",
        "gazebo-classic/rse_terrain/model.sdf",
        "gazebo-classic/rse_terrain/meshes/terrain.obj",
        "gazebo-classic/rse_terrain/meshes/terrain.mtl",
    }
    report = rse.check(tmp_path / "py0")
    assert report.ok and report.checked == 2
    model = ET.parse(tmp_path / "py0/world_0000/gazebo-classic/rse_terrain/model.sdf").getroot()
    link = model.find("model/link")
    assert link is not None
    collisions, visuals = link.findall("collision"), link.findall("visual")
    assert len(collisions) > 1 and all(c.find("geometry/box") is not None for c in collisions)
    assert [v.findtext("geometry/mesh/uri") for v in visuals] == ["model://rse_terrain/meshes/terrain.obj"]


# --- dropping bodies on chosen cells ----------------------------------------


def drop_cells(h: np.ndarray) -> list[tuple[int, int]]:
    """Cells in the middle of flat 3x3 patches, so a body cannot slide off:
    the highest, the lowest, and some between."""
    flat = [
        (x, y)
        for y in range(1, h.shape[0] - 1)
        for x in range(1, h.shape[1] - 1)
        if (h[y - 1 : y + 2, x - 1 : x + 2] == h[y, x]).all()
    ]
    flat.sort(key=lambda c: (h[c[1], c[0]], c))
    assert len(flat) >= 3
    return sorted({flat[0], flat[-1], *flat[:: max(1, len(flat) // 4)]})


RADIUS, HALF_BOX = 0.02, 0.015


@pytest.mark.parametrize("mode", MODES)
def test_mujoco_bodies_rest_at_their_cells_height(batches, mode: str) -> None:
    scheme = SCHEMES / "six_obstacles.csv"
    u = units(scheme)
    for world in sorted(batches[("six_obstacles", mode)].glob("world_*")):
        h = heights(scheme, index=manifest(world)["index"])
        spec = mujoco.MjSpec.from_file(str(world / "mujoco/rse.xml"))
        dropped = []
        for i, (x, y) in enumerate(drop_cells(h)):
            top = h[y, x] * u["step_height"]
            centre = [(x + 0.5) * u["block_size"], (y + 0.5) * u["block_size"]]
            body = spec.worldbody.add_body(pos=[*centre, top + 0.05])
            body.add_freejoint()
            if i % 2:
                body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[HALF_BOX] * 3, mass=0.1)
                dropped.append((body.name, top + HALF_BOX))
            else:
                body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[RADIUS, 0, 0], mass=0.1)
                dropped.append((body.name, top + RADIUS))
            body.name = f"drop_{i}"
            dropped[-1] = (body.name, dropped[-1][1])
        model = spec.compile()
        data = mujoco.MjData(model)
        for _ in range(1000):
            mujoco.mj_step(model, data)
        for name, rest in dropped:
            z = data.body(name).xpos[2]
            assert z == pytest.approx(rest, abs=0.002), f"{world.name} {mode} {name}"


@pytest.mark.parametrize("mode", MODES)
def test_mujoco_loads_every_world_with_one_box_geom_per_box(batches, mode: str) -> None:
    for world in worlds(batches, mode):
        model = mujoco.MjModel.from_xml_path(str(world / "mujoco/rse.xml"))
        boxes = sum(model.geom(i).type[0] == mujoco.mjtGeom.mjGEOM_BOX for i in range(model.ngeom))
        expected = len(re.findall(r'type="box"', (world / "mujoco/rse.xml").read_text()))
        assert boxes == expected
        solid = (np.loadtxt(world / "heightmap.csv", delimiter=",", ndmin=2) > 0).any()
        assert (boxes > 0) == solid
        # A convex mesh geom for each ramp's wedge, beside the drawn mesh.
        ramps = [i for i in range(model.ngeom) if model.geom(i).name.startswith("rse_ramp_")]
        assert all(model.geom(i).type[0] == mujoco.mjtGeom.mjGEOM_MESH for i in ramps)
        assert len(ramps) == len(ramp_tops(world))
        assert model.nmesh == (1 if mode == "single" and solid else 0) + len(ramps)


@pytest.mark.parametrize("mode", MODES)
def test_pybullet_urdf_bodies_rest_at_their_cells_height(batches, mode: str) -> None:
    scheme = SCHEMES / "six_obstacles.csv"
    u = units(scheme)
    world = sorted(batches[("six_obstacles", mode)].glob("world_*"))[0]
    h = heights(scheme, index=manifest(world)["index"])
    client = p.connect(p.DIRECT)
    try:
        p.setGravity(0, 0, -9.81, physicsClientId=client)
        terrain = p.loadURDF(str(world / "urdf/rse.urdf"), useFixedBase=True, physicsClientId=client)
        assert terrain >= 0
        bodies = []
        for x, y in drop_cells(h):
            top = h[y, x] * u["step_height"]
            shape = p.createCollisionShape(p.GEOM_SPHERE, radius=RADIUS, physicsClientId=client)
            body = p.createMultiBody(
                0.1,
                shape,
                basePosition=[(x + 0.5) * u["block_size"], (y + 0.5) * u["block_size"], top + 0.05],
                physicsClientId=client,
            )
            bodies.append((body, top + RADIUS))
        for _ in range(1000):
            p.stepSimulation(physicsClientId=client)
        for body, rest in bodies:
            z = p.getBasePositionAndOrientation(body, physicsClientId=client)[0][2]
            assert z == pytest.approx(rest, abs=0.002), mode
    finally:
        p.disconnect(client)


def test_urdf_collision_is_a_concave_mesh_in_single_mode(batches) -> None:
    for world in sorted(batches[("wall", "single")].glob("world_*")):
        collisions = ET.parse(world / "urdf/rse.urdf").getroot().findall("link[@name='terrain']/collision")
        assert len(collisions) == 1 and collisions[0].get("concave") == "yes"
        mesh = collisions[0].find("geometry/mesh").get("filename")
        assert (world / "urdf" / mesh).resolve().is_file()


# --- USD: usd-core -------------------------------------------------------------


@pytest.mark.parametrize("mode", MODES)
def test_usd_stage_opens_with_valid_meshes_and_collision(batches, mode: str) -> None:
    for world in worlds(batches, mode):
        stage = Usd.Stage.Open(str(world / "usd/rse.usda"))
        assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.z
        assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
        colliders = [prim for prim in stage.Traverse() if prim.HasAPI(UsdPhysics.CollisionAPI)]
        # The ground: a slab whose top is z = 0, under the whole terrain and 50 m past it.
        ground = stage.GetPrimAtPath("/World/ground")
        assert ground in colliders and ground.IsA(UsdGeom.Cube)
        colliders.remove(ground)
        box = UsdGeom.Cube(ground).ComputeWorldBound(Usd.TimeCode.Default(), "default").ComputeAlignedRange()
        h = np.loadtxt(world / "heightmap.csv", delimiter=",", ndmin=2)
        size = np.array(h.shape[::-1]) * manifest(world)["globals"]["block_size"]
        assert box.GetMax()[2] == pytest.approx(0, abs=1e-9)
        # float3 scale: float32 precision.
        assert np.all(np.array(box.GetMin())[:2] <= -50 + 1e-4) and np.all(np.array(box.GetMax())[:2] >= size + 50 - 1e-4)
        if not (h > 0).any():
            assert colliders == []
            continue
        if mode == "blocks":
            cubes = [prim for prim in colliders if prim.IsA(UsdGeom.Cube)]
            assert len(cubes) == len(colliders) == len(re.findall('type="box"', (world / "mujoco/rse.xml").read_text()))
            continue
        (terrain,) = colliders
        assert terrain.IsA(UsdGeom.Mesh) and terrain.HasAPI(UsdPhysics.MeshCollisionAPI)
        mesh = UsdGeom.Mesh(terrain)
        points = np.array(mesh.GetPointsAttr().Get())
        ok, why = UsdGeom.Mesh.ValidateTopology(
            mesh.GetFaceVertexIndicesAttr().Get(), mesh.GetFaceVertexCountsAttr().Get(), len(points)
        )
        assert ok, why
        step = manifest(world)["globals"]["step_height"]
        assert points[:, 2].max() == pytest.approx(max([h.max() * step, *ramp_tops(world)]), abs=1e-6)
        assert UsdPhysics.MeshCollisionAPI(terrain).GetApproximationAttr().Get() == "none"


def test_usd_terrain_asset_is_a_collider_alone(batches) -> None:
    """usd/terrain.usda opened alone (as Isaac Lab's terrain_type="usd" and
    Isaac Sim's drag-and-drop do): its default prim is the mesh, a static
    collider with the exact triangles."""
    checked = 0
    for world in worlds(batches, "single"):
        asset = world / "usd/terrain.usda"
        if not asset.exists():
            continue
        stage = Usd.Stage.Open(str(asset))
        assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.z
        assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
        terrain = stage.GetDefaultPrim()
        assert terrain.IsA(UsdGeom.Mesh)
        assert terrain.HasAPI(UsdPhysics.CollisionAPI) and terrain.HasAPI(UsdPhysics.MeshCollisionAPI)
        assert UsdPhysics.MeshCollisionAPI(terrain).GetApproximationAttr().Get() == "none"
        assert not terrain.HasAPI(UsdPhysics.RigidBodyAPI)  # static
        checked += 1
    assert checked > 0


# --- Webots: structure --------------------------------------------------------

TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|#[^\n]*|[{}\[\]]|[^\s{}\[\]"]+')


def parse_wbt(text: str) -> list[str]:
    """Tokens of a .wbt (VRML-like) world, braces and brackets checked balanced."""
    tokens = [t for t in TOKEN.findall(text) if not t.startswith("#")]
    stack = []
    for t in tokens:
        if t in "{[":
            stack.append(t)
        elif t in "}]":
            assert stack and stack.pop() == {"}": "{", "]": "["}[t], "unbalanced"
    assert not stack, "unclosed node"
    return tokens


@pytest.mark.parametrize("mode", MODES)
def test_webots_world_is_well_formed_and_its_meshes_exist(batches, mode: str) -> None:
    for world in worlds(batches, mode):
        wbt = world / "webots/rse.wbt"
        text = wbt.read_text()
        assert text.startswith("#VRML_SIM R2023b utf8\n")
        tokens = parse_wbt(text)
        nodes = [tokens[i - 1] for i, t in enumerate(tokens) if t == "{"]
        for node in ["WorldInfo", "Viewpoint", "Solid"]:
            assert node in nodes
        urls = [tokens[i + 2].strip('"') for i, t in enumerate(tokens) if t == "url"]
        for url in urls:
            assert (wbt.parent / url).resolve().is_file(), url
        solid = (np.loadtxt(world / "heightmap.csv", delimiter=",", ndmin=2) > 0).any()
        boxes = nodes.count("Box")
        if mode == "single":
            assert len(urls) == (1 if solid else 0) and boxes == 0
        else:
            assert urls == [] and boxes == len(re.findall('type="box"', (world / "mujoco/rse.xml").read_text()))


def test_the_webots_parser_catches_unbalanced_nodes() -> None:
    with pytest.raises(AssertionError):
        parse_wbt("#VRML_SIM R2023b utf8\nSolid {\n children [\n Shape {\n }\n}\n")
