"""The Python package `rse`: the same terrains
as the CLI and the batch, mesh arrays that are closed volumes in trimesh,
MJCF that MuJoCo loads and that bodies rest on, hypothesis round trips and
bad inputs, and stubs that match the module."""

import ast
import inspect
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest
import rse
import rse._rse as _rse
import trimesh
from conftest import REPO, SCHEMES, heights, run, wedges_volume
from hypothesis import given, settings
from hypothesis import strategies as st

SAMPLES = sorted(SCHEMES.glob("*.csv"))


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_heights_match_rse_gen_heightmap(scheme: Path) -> None:
    loaded = rse.Scheme.load(scheme)
    for seed, index in [(0, 0), (12345, 7)]:
        terrain = loaded.generate(seed=seed, index=index)
        assert terrain.heights.shape == (loaded.grid[1], loaded.grid[0])
        np.testing.assert_array_equal(terrain.heights, heights(scheme, seed, index))


def test_heights_match_the_batch_heightmaps_from_both_front_ends(tmp_path: Path) -> None:
    scheme_path = SCHEMES / "nist_hill.csv"
    scheme = rse.Scheme.load(scheme_path)
    run("batch", str(scheme_path), "-o", str(tmp_path / "cli"), "--amount", "3", "--seed", "4", "--target", "mujoco")
    counts = rse.write_worlds(scheme, tmp_path / "py", amount=3, seed=4, targets="mujoco", jobs=2)
    assert counts["written"] == 3 and counts["skipped"] == 0 and counts["bytes"] > 0
    for i in range(3):
        world = f"world_{i:04d}"
        expected = scheme.generate(seed=4, index=i).heights
        for front in ["cli", "py"]:
            on_disk = np.loadtxt(tmp_path / front / world / "heightmap.csv", delimiter=",", dtype=np.uint16, ndmin=2)
            np.testing.assert_array_equal(on_disk, expected)
        for f in (tmp_path / "cli" / world).rglob("*"):
            if f.is_file():
                assert f.read_bytes() == (tmp_path / "py" / world / f.relative_to(tmp_path / "cli" / world)).read_bytes()
    again = rse.write_worlds(scheme, tmp_path / "py", amount=3, seed=4, targets="mujoco")
    assert again["skipped"] == 3


def test_arrays_are_read_only_and_typed() -> None:
    terrain = rse.Scheme.load(SCHEMES / "six_obstacles.csv").generate(index=2)
    assert terrain.heights.dtype == np.uint16 and terrain.elevation.dtype == np.float64
    with pytest.raises(ValueError):
        terrain.heights[0, 0] = 9
    np.testing.assert_allclose(
        terrain.elevation, np.where(terrain.heights > 0, terrain.base + terrain.heights * terrain.step_height, 0.0)
    )
    vertices, faces = terrain.mesh()
    assert vertices.dtype == np.float32 and vertices.shape[1] == 3
    assert faces.dtype == np.uint32 and faces.shape[1] == 3
    boxes = terrain.boxes()
    assert boxes.dtype == np.float64 and boxes.shape[1] == 6
    # The boxes' union is the solid (they may overlap inside it): each stands
    # on z = 0, none rises above a cell under it, and over every cell the
    # highest box reaches the cell's top.
    assert len(boxes) < np.count_nonzero(terrain.heights)
    np.testing.assert_allclose(boxes[:, 2], boxes[:, 5])
    highest = np.zeros_like(terrain.elevation)
    s = terrain.block_size
    for cx, cy, _, hx, hy, hz in boxes:
        x0, x1, y0, y1 = (round(v / s) for v in (cx - hx, cx + hx, cy - hy, cy + hy))
        under = terrain.elevation[y0:y1, x0:x1]
        assert under.size == (x1 - x0) * (y1 - y0) and np.all(2 * hz <= under + 1e-9)
        highest[y0:y1, x0:x1] = np.maximum(highest[y0:y1, x0:x1], 2 * hz)
    np.testing.assert_allclose(highest, terrain.elevation, atol=1e-9)


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_mesh_arrays_are_a_closed_volume_in_trimesh(scheme: Path) -> None:
    terrain = rse.Scheme.load(scheme).generate(index=1)
    vertices, faces = terrain.mesh()
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.is_volume
    cells = np.sum(terrain.elevation) * terrain.block_size**2
    assert mesh.volume == pytest.approx(cells + wedges_volume(terrain), rel=1e-5)


def test_save_writes_each_format(tmp_path: Path) -> None:
    terrain = rse.Scheme.load(SCHEMES / "wall.csv").generate()
    for suffix in ["obj", "stl", "glb"]:
        terrain.save(tmp_path / f"t.{suffix}")
    assert (tmp_path / "t.mtl").is_file()
    loaded = trimesh.load(tmp_path / "t.stl", force="mesh")
    assert loaded.volume == pytest.approx(np.sum(terrain.elevation) * terrain.block_size**2, rel=1e-5)
    with pytest.raises(ValueError, match="unknown mesh format"):
        terrain.save(tmp_path / "t.ply")
    with pytest.raises(OSError):
        terrain.save(tmp_path / "no" / "such" / "dir" / "t.obj")


def test_mjcf_loads_in_mujoco_and_bodies_rest_on_their_cells() -> None:
    terrain = rse.Scheme.load(SCHEMES / "nist_hill.csv").generate(index=3)
    h, s, step = terrain.heights, terrain.block_size, terrain.step_height
    spec = mujoco.MjSpec.from_string(terrain.mjcf())
    cells = [
        (x, y)
        for y in range(1, h.shape[0] - 1)
        for x in range(1, h.shape[1] - 1)
        if (h[y - 1 : y + 2, x - 1 : x + 2] == h[y, x]).all()
    ][::7]
    assert len(cells) >= 3
    for i, (x, y) in enumerate(cells):
        body = spec.worldbody.add_body(name=f"drop_{i}", pos=[(x + 0.5) * s, (y + 0.5) * s, h[y, x] * step + 0.05])
        body.add_freejoint()
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.02, 0, 0], mass=0.1)
    model = spec.compile()
    data = mujoco.MjData(model)
    for _ in range(1000):
        mujoco.mj_step(model, data)
    for i, (x, y) in enumerate(cells):
        assert data.body(f"drop_{i}").xpos[2] - 0.02 == pytest.approx(h[y, x] * step, abs=0.002)


def test_generate_batch_is_the_per_index_generator_on_any_jobs() -> None:
    scheme = rse.Scheme.load(SCHEMES / "six_obstacles.csv")
    one = rse.generate_batch(scheme, 12, seed=3, jobs=1)
    two = rse.generate_batch(scheme, 12, seed=3, jobs=2)
    assert [t.index for t in one] == list(range(12))
    for i, (a, b) in enumerate(zip(one, two)):
        np.testing.assert_array_equal(a.heights, b.heights)
        np.testing.assert_array_equal(a.heights, scheme.generate(seed=3, index=i).heights)
    with pytest.raises(ValueError):
        rse.generate_batch(scheme, 2, jobs=0)


def test_scheme_errors_carry_file_line_column_and_field(tmp_path: Path) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text("# size: 10x10\ntype,height,angle,x1,y1\npeak,2,45,12,3\n")
    with pytest.raises(rse.SchemeError) as caught:
        rse.Scheme.load(bad)
    e = caught.value
    assert isinstance(e, ValueError)
    assert (e.file, e.line, e.column, e.field) == (str(bad), 3, 4, "x1")
    with pytest.raises(OSError):
        rse.Scheme.load(tmp_path / "missing.csv")
    with pytest.raises(rse.SchemeError) as caught:
        rse.Scheme([rse.Obstacle("peak", height=2, angle=45, x1=3, y1=30)], size=(10, 10))
    assert caught.value.field == "y1"
    with pytest.raises(rse.SchemeError):
        rse.Obstacle("wall", height=2)  # a wall needs its angle and both points
    with pytest.raises(rse.SchemeError, match="volcano"):
        rse.Obstacle("volcano", height=2)
    with pytest.raises(rse.SchemeError) as caught:
        rse.Obstacle("random", height=-1)
    assert caught.value.field == "height"
    # Ints of any size: one past 64 bits is a scheme error too, not an OverflowError.
    with pytest.raises(rse.SchemeError) as caught:
        rse.Obstacle("peak", height=2, angle=45, x1=(0, 2**70), y1=3)
    assert caught.value.field == "x1" and str(2**70) in str(caught.value)


def test_obstacles_read_back_their_fields() -> None:
    o = rse.Obstacle("peak", height=(2, 5), angle=30.0, x1=4, y1=(1, 8))
    assert (o.type, o.height, o.angle, o.x1, o.y1, o.x2) == ("peak", (2, 5), 30.0, 4, (1, 8), None)
    scheme = rse.Scheme([o], size=(10, 10), step_height=0.05, seed=9)
    assert scheme.obstacles == [o] and scheme.grid == (10, 10) and scheme.step_height == 0.05 and scheme.seed == 9


# --- hypothesis: round trips and bad input ------------------------------------

SIZE = 12


@st.composite
def obstacles(draw: st.DrawFn) -> rse.Obstacle:
    def coordinate() -> st.SearchStrategy:
        value = st.integers(0, SIZE - 1)
        return st.one_of(value, st.tuples(value, value).map(sorted).map(tuple))

    kind = draw(st.sampled_from(["random", "gaussian", "peak", "pit", "wall", "long_pit"]))
    height = draw(st.one_of(st.integers(1, 6), st.tuples(st.integers(1, 3), st.integers(3, 6))))
    if kind in ("random", "gaussian"):
        sigma = draw(st.none() | st.floats(0.1, 3.0)) if kind == "gaussian" else None
        return rse.Obstacle(kind, height=height, sigma=sigma)
    angle = draw(st.floats(1.0, 90.0))
    if kind in ("peak", "pit"):
        return rse.Obstacle(kind, height=height, angle=angle, x1=draw(coordinate()), y1=draw(coordinate()))
    return rse.Obstacle(
        kind,
        height=height,
        angle=angle,
        x1=draw(coordinate()),
        y1=draw(coordinate()),
        x2=draw(coordinate()),
        y2=draw(coordinate()),
    )


@settings(max_examples=60, deadline=None)
@given(st.lists(obstacles(), max_size=5), st.integers(0, 2**64 - 1), st.integers(0, 1000))
def test_schemes_round_trip_through_csv_with_the_same_worlds(table, seed, index) -> None:
    scheme = rse.Scheme(table, size=(SIZE, SIZE))
    again = rse.Scheme.from_csv(scheme.to_csv())
    assert again.to_csv() == scheme.to_csv()
    np.testing.assert_array_equal(again.generate(seed, index).heights, scheme.generate(seed, index).heights)


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=300))
def test_any_text_is_a_scheme_or_a_scheme_error(text: str) -> None:
    try:
        rse.Scheme.from_csv(text)
    except rse.SchemeError as e:
        assert str(e)


@settings(max_examples=100, deadline=None)
@given(
    st.sampled_from(["peak", "pit", "wall", "long_pit", "random", "gaussian"]),
    st.one_of(st.none(), st.integers(-5, 70000)),
    st.one_of(st.none(), st.floats(allow_nan=True, allow_infinity=True)),
    st.one_of(st.none(), st.integers(-3, 40)),
)
def test_bad_obstacle_values_raise_value_errors_never_crash(kind, height, angle, x1) -> None:
    try:
        rse.Scheme([rse.Obstacle(kind, height=height, angle=angle, x1=x1, y1=x1)], size=(10, 10))
    except rse.SchemeError as e:
        assert str(e) and (e.field is not None or e.line is not None)


def test_stubs_match_the_module() -> None:
    done = subprocess.run([sys.executable, "-m", "mypy.stubtest", "rse._rse"], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr


def _stub_defaults() -> list[tuple[str, object, str, object]]:
    """(qualified name, runtime callable, parameter, default) of every
    literal default `_rse.pyi` writes, for the functions and methods the
    extension has."""
    tree = ast.parse((REPO / "crates/rse-py/python/rse/_rse.pyi").read_text())
    found = []

    def defaults(qual: str, fn: ast.FunctionDef, runtime: object) -> None:
        args = fn.args
        positional = args.posonlyargs + args.args
        given = dict(zip([a.arg for a in positional][len(positional) - len(args.defaults) :], args.defaults))
        given.update({a.arg: d for a, d in zip(args.kwonlyargs, args.kw_defaults) if d is not None})
        for name, node in given.items():
            try:
                found.append((qual, runtime, name, ast.literal_eval(node)))
            except ValueError:
                pass  # not a literal (a name, `...`)

    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and hasattr(_rse, node.name):
            defaults(node.name, node, getattr(_rse, node.name))
        if isinstance(node, ast.ClassDef) and hasattr(_rse, node.name):
            cls = getattr(_rse, node.name)
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and callable(getattr(cls, item.name, None)):
                    runtime = cls if item.name in ("__new__", "__init__") else getattr(cls, item.name)
                    defaults(f"{node.name}.{item.name}", item, runtime)
    return found


def test_the_stubs_defaults_are_the_extensions() -> None:
    """`_rse.pyi` restates defaults by hand: each literal one must be the
    extension's own (its pyo3 signature, from Rust), and the scheme's
    globals those of a default `Scheme` (rse-core's `Globals::default`)."""
    stub = _stub_defaults()
    assert len(stub) > 40, len(stub)
    differ = []
    for qual, runtime, name, want in stub:
        got = inspect.signature(runtime).parameters[name].default  # type: ignore[arg-type]
        if got != want and not (isinstance(want, tuple) and list(want) == got):
            differ.append(f"{qual}({name}=): stub {want!r}, extension {got!r}")
    assert not differ, differ
    fields = rse.Scheme().fields()
    scheme_defaults = {name: want for qual, _, name, want in stub if qual == "Scheme.__new__"}
    assert set(scheme_defaults) >= {"size", "block_size", "step_height", "base", "amount", "seed"}, scheme_defaults
    for name, want in scheme_defaults.items():
        assert fields[name] == want, f"Scheme({name}=): stub {want!r}, Rust's default {fields[name]!r}"


def test_a_terrain_from_forged_state_is_refused_not_a_later_panic() -> None:
    """`rse.Terrain(state, cells)` is pickle's constructor: a state no scheme
    could give (a 0x0 grid, a block of no size, frames every 0 cells) is
    refused there, instead of a panic in `spawn_origin()` later."""
    import json

    terrain = rse.Scheme.from_csv("# size: 4x3\ntype,height\nrandom,2\n").generate()
    constructor, (state, cells, scheme) = terrain.__reduce__()
    assert constructor(state, cells, scheme).heights.tolist() == terrain.heights.tolist()
    fields = json.loads(state)
    forgeries = {
        "0x0 grid": ({**fields, "grid": {**fields["grid"], "nx": 0, "ny": 0}}, b""),
        "no block": ({**fields, "globals": {**fields["globals"], "block_size": 0.0}}, cells),
        "negative step": ({**fields, "globals": {**fields["globals"], "step_height": -0.1}}, cells),
        "frames every 0 cells": ({**fields, "grid": {**fields["grid"], "frame_period": 0}}, cells),
        # Hostile worlds VI: units or heights the recipe cannot give.
        "a step of 1e300 m": ({**fields, "globals": {**fields["globals"], "step_height": 1e300}}, cells),
        "heights of 65535": (fields, b"\xff\xff" * 12),
    }
    for name, (forged, forged_cells) in forgeries.items():
        with pytest.raises(ValueError, match="not the state of a pickled rse.Terrain"):
            rse.Terrain(json.dumps(forged), forged_cells, scheme)
        if name == "a step of 1e300 m":
            # Refused with no scheme to regenerate from, too.
            with pytest.raises(ValueError, match="not the state of a pickled rse.Terrain"):
                rse.Terrain(json.dumps(forged), forged_cells)
    # A terrain of a pool (at its difficulty, in its episode) restores.
    envs = rse.EnvTerrains(rse.Scheme.from_csv("# size: 4x3\ntype,height\nrandom,2\n"), 3, difficulty=0.4)
    envs.reset([1])
    for e in range(3):
        t = envs.terrain(e)
        constructor, args = t.__reduce__()
        assert constructor(*args).heights.tolist() == t.heights.tolist()


def under_3_gb(script: str) -> subprocess.CompletedProcess[str]:
    """``script`` (``rse`` imported) run by this Python in a process of its
    own under a 3 GB address-space limit, as the hostile reports ran theirs;
    it must exit 0."""
    limit = "import resource, rse\nresource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))\n"
    done = subprocess.run([sys.executable, "-c", limit + script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done


def test_flat_patches_never_pad_past_what_a_terrain_holds() -> None:
    """A caller's n sizes no allocation past one patch a cell: 10**8 asked
    for 9.6 GB and aborted the interpreter under an address-space limit."""
    terrain = rse.Scheme.from_csv("# size: 6x5\ntype,height\nrandom,0\n").generate()
    patches = terrain.flat_patches(10**8, radius=0.05)
    assert patches.shape == (30, 3) and not np.isnan(patches).any()
    atlas = rse.Atlas([rse.Scheme.from_csv("# size: 4x4\ntype,height\nrandom,0\n")], rows=2, cols=3)
    tiled = atlas.flat_patches(2**32 - 1, radius=0.05)
    assert tiled.shape[:2] == (2, 3) and 16 <= tiled.shape[2] <= 64, tiled.shape
    # As the report had it: under a 3 GB address-space limit, in a process of its own.
    done = under_3_gb(
        "s = rse.Scheme.from_csv('# size: 50x50\\ntype,height\\nrandom,1\\n')\n"
        "print(rse.Atlas([s], rows=4, cols=4).flat_patches(10**8, radius=0.05).shape)\n"
    )
    assert done.stdout.startswith("(4, 4, "), done.stdout


def test_a_pool_past_an_address_space_limit_is_a_memory_error_naming_num_envs() -> None:
    """Hostile worlds VI: under a 3 GB address-space limit a pool of 1000
    envs of 300×300 cells at oversample 4 (5.8 GB of samples) raised
    ``PanicException: PyObject pointer is null``. The limit's room counts
    as the memory available: a ``MemoryError`` naming ``num_envs``."""
    done = under_3_gb(
        "s = rse.Scheme.from_csv('# size: 300x300\\ntype,height\\nrandom,3\\n')\n"
        "try:\n"
        "    rse.EnvTerrains(s, 1000, oversample=4)\n"
        "except MemoryError as e:\n"
        "    print('MemoryError', e)\n"
    )
    assert done.stdout.startswith("MemoryError num_envs: "), done.stdout


def test_the_schemes_stub_is_the_table_of_global_keys() -> None:
    """`Scheme.__new__` in `_rse.pyi` is written by scripts/python_stubs.py
    from the extension's signature, which rse-py builds from rse-core's
    table of global keys: a key added there without rerunning the script
    fails here, by the script's words."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("python_stubs", REPO / "scripts" / "python_stubs.py")
    assert spec is not None and spec.loader is not None
    stubs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(stubs)
    text = stubs.STUB.read_text()
    assert stubs.updated(text) == text, "run .venv/bin/python scripts/python_stubs.py"
    # A key the stub lacks is put back by the script.
    without_seed = text.replace("        seed: _Int = 0,\n", "", 1)
    assert without_seed != text and stubs.updated(without_seed) == text
    # So is a world option one of the writers' stubs lacks.
    without_mesh = text.replace("    mesh: Optional[_MeshMode] = None,\n", "", 1)
    assert without_mesh != text and stubs.updated(without_mesh) == text
    assert list(inspect.signature(rse.Scheme).parameters) == list(rse.Scheme().fields())


def test_every_keyword_group_is_the_signature_it_shows(tmp_path: Path) -> None:
    """Calls that read `**options` into typed keyword groups show their
    keywords in `inspect.signature` (for functions and methods, the
    signature heading the docstring, its world options from rse-world's
    table; for classes, `__signature__` built from the groups): an
    unknown keyword's `TypeError` lists the groups' keywords, which must be
    the signature's, and each of them is taken."""
    scheme = rse.Scheme(size=(4, 4))
    atlas = rse.Atlas([scheme], 1, 1)
    calls = {
        "write_worlds": (rse.write_worlds, lambda **kw: rse.write_worlds(scheme, tmp_path / "batch", **kw)),
        "write_world": (rse.write_world, lambda **kw: rse.write_world(scheme.generate(), tmp_path / "world", **kw)),
        "write": (rse.Atlas.write, lambda **kw: atlas.write(tmp_path / "atlas", **kw)),
        "Atlas": (rse.Atlas, lambda **kw: rse.Atlas([scheme], 1, 1, **kw)),
        "EnvTerrains": (rse.EnvTerrains, lambda **kw: rse.EnvTerrains(scheme, 1, **kw)),
        "contact_sheet": (rse.EnvTerrains.contact_sheet, lambda **kw: rse.EnvTerrains(scheme, 1).contact_sheet(**kw)),
        "Obstacle": (rse.Obstacle, lambda **kw: rse.Obstacle("random", **kw)),
    }
    for name, (shown, call) in calls.items():
        keywords = [p.name for p in inspect.signature(shown).parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY]
        with pytest.raises(TypeError, match=f"{name}\\(\\) got an unexpected keyword argument 'nope'") as refused:
            call(nope=1)
        listed = str(refused.value).split("the keywords are ", 1)[1].split(", ")
        assert listed == keywords, name
        for keyword in keywords:
            try:
                call(**{keyword: None})
            except TypeError as e:
                assert "unexpected keyword" not in str(e), (name, keyword, e)
            except (ValueError, OSError):
                pass  # refused for what it is, not for its name
