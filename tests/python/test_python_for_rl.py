"""The Python package as reinforcement-learning code calls it: numpy numbers anywhere, pickling into worker processes, reprs that
read back, heights under points, curricula by `replace`, MJCF fragments
attached to a robot with `mujoco.MjSpec`, one terrain written as a world,
the same validation and messages as the command line in Python's words."""

import copy
import inspect
import json
import multiprocessing
import pickle
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import mujoco
import numpy as np
import pytest
import rse
from conftest import SCHEMES, rse_gen_path

SIX = SCHEMES / "six_obstacles.csv"


def wall(**kwargs: object) -> rse.Obstacle:
    fields = dict(height=(1, 3), angle=45.0, x1=(1, 2), y1=1, x2=6, y2=5)
    fields.update(kwargs)
    return rse.Obstacle("wall", **fields)


# --- numpy numbers -------------------------------------------------------


def test_numpy_scalars_and_arrays_are_taken_wherever_numbers_are() -> None:
    plain = rse.Scheme(
        [rse.Obstacle("random", height=2), wall(), rse.Obstacle("gaussian", height=3, sigma=(0.5, 1.5))],
        size=(12, 10),
        step_height=0.05,
        base=0.02,
        amount=4,
        seed=7,
    )
    numpy = rse.Scheme(
        [
            rse.Obstacle("random", height=np.int64(2)),
            wall(height=np.array([1, 3]), angle=np.float64(45), x1=[np.uint8(1), 2], y1=np.int32(1), x2=np.array(6)),
            rse.Obstacle("gaussian", height=np.uint16(3), sigma=np.array([0.5, 1.5])),
        ],
        size=np.array([12, 10]),
        step_height=np.float64(0.05),
        base=np.float64(0.02),
        amount=np.int64(4),
        seed=np.uint64(7),
    )
    assert numpy == plain and numpy.to_csv() == plain.to_csv()
    pallets = rse.Scheme(pallets=np.array([2, 3]), pallet_size=np.int8(3))
    assert pallets.grid == (9, 13)


def test_numpy_numbers_reach_every_call_rl_code_makes() -> None:
    scheme = rse.Scheme.load(SIX)
    plain = scheme.generate(seed=3, index=2, difficulty=0.5)
    terrain = scheme.generate(seed=np.uint64(3), index=np.int64(2), difficulty=np.float32(0.5))
    np.testing.assert_array_equal(terrain.heights, plain.heights)
    assert len(rse.generate_batch(scheme, np.int64(3), seed=np.int32(3), jobs=np.int64(2))) == 3
    np.testing.assert_array_equal(terrain.spawn_origin(np.float32(0.25)), plain.spawn_origin(0.25))
    assert terrain.flat_patches(np.int64(2), np.float64(0.3), np.int8(0)).shape == (2, 3)
    assert terrain.hfield_shape(np.uint8(2)) == plain.hfield_shape(2)
    assert terrain.preview(np.int64(2)) == plain.preview(2)
    assert terrain.mjcf(offset=np.array([1.0, 2.0, 3.0]), friction=np.float32(0.5)) == plain.mjcf(
        offset=(1, 2, 3), friction=0.5
    )
    atlas = rse.Atlas([scheme], np.int64(2), np.int64(2), seed=np.uint64(1), difficulty=np.array([0.2, 0.8]))
    assert atlas.to_json() == rse.Atlas([scheme], 2, 2, seed=1, difficulty=(0.2, 0.8)).to_json()
    with pytest.raises(TypeError, match="offset: expected 3 numbers"):
        terrain.mjcf(offset=(1.0, 2.0))
    with pytest.raises(TypeError, match="difficulty: expected 2 numbers"):
        rse.Atlas([scheme], 1, 1, difficulty="easy")


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        (dict(height="3"), "height"),
        (dict(height=True), "height"),
        (dict(height=(1, 2, 3)), "height"),
        (dict(x1=1.5), "x1"),
        (dict(angle="steep"), "angle"),
        (dict(angle=(10, "x")), "angle"),
    ],
)
def test_a_wrong_type_is_a_type_error_naming_the_field(kwargs: dict, field: str) -> None:
    with pytest.raises(TypeError, match=f"^{field}: expected "):
        wall(**kwargs)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        (dict(size=(-1, 10)), "size"),
        (dict(size=(10, 2**40)), "size"),
        (dict(seed=-1), "seed"),
        (dict(amount=np.int64(-3)), "amount"),
        (dict(pallet_size=3), "pallet_size"),
        (dict(pallet_boundary=True), "pallet_boundary"),
        (dict(size=(0, 10)), "size"),
        (dict(amount=0), "amount"),
    ],
)
def test_a_value_out_of_range_is_a_scheme_error_naming_the_field(kwargs: dict, field: str) -> None:
    with pytest.raises(rse.SchemeError) as caught:
        rse.Scheme(**kwargs)
    assert caught.value.field == field and str(caught.value).find(f"{field}: ") >= 0
    assert "--" not in str(caught.value), "Python messages name keywords, not flags"


def test_pallet_settings_without_pallets_are_refused_in_both_front_ends(tmp_path: Path) -> None:
    """The same rule, and the same field, as a scheme file on the command line."""
    import subprocess

    path = tmp_path / "p.csv"
    path.write_text("# pallet_size: 3\ntype,height\nrandom,2\n")
    done = subprocess.run([str(rse_gen_path()), "heightmap", str(path)], capture_output=True, text=True)
    assert done.returncode == 2
    assert f"{path}:1: pallet_size: is set but pallets are off" in done.stderr
    with pytest.raises(rse.SchemeError, match="pallet_size: is set but pallets are off") as caught:
        rse.Scheme([rse.Obstacle("random", height=2)], pallet_size=3)
    assert "pallets=(2, 3)" in str(caught.value)
    with pytest.raises(rse.SchemeError) as from_file:
        rse.Scheme.load(path)
    assert from_file.value.field == "pallet_size" and from_file.value.line == 1


def test_a_pallet_setting_that_changes_nothing_is_accepted_everywhere(tmp_path: Path) -> None:
    """No pallets, no frame: saying `pallet_boundary` false is not a mistake
    (one rule in rse-core, the same answer from Python, a file and a flag)."""
    import subprocess

    plain = rse.Scheme([rse.Obstacle("random", height=2)])
    assert rse.Scheme([rse.Obstacle("random", height=2)], pallet_boundary=False) == plain
    assert rse.Scheme([rse.Obstacle("random", height=2)], pallet_boundary=np.bool_(False)) == plain
    assert plain.replace(pallet_boundary=False) == plain
    path = tmp_path / "p.csv"
    path.write_text("# pallet_boundary: false\ntype,height\nrandom,2\n")
    assert rse.Scheme.load(path).to_csv() == plain.to_csv()
    flag = subprocess.run(
        [str(rse_gen_path()), "heightmap", str(SCHEMES / "random.csv"), "--pallet-boundary", "false"],
        capture_output=True, text=True,
    )
    assert flag.returncode == 0, flag.stderr
    refused = subprocess.run(
        [str(rse_gen_path()), "heightmap", str(SCHEMES / "random.csv"), "--pallet-boundary", "true"],
        capture_output=True, text=True,
    )
    assert refused.returncode == 2 and "--pallet-boundary needs pallets" in refused.stderr


# --- pickle, copy, repr ---------------------------------------------------


def test_schemes_obstacles_and_terrains_pickle_and_deep_copy() -> None:
    scheme = rse.Scheme.load(SIX).replace(seed=11)
    terrain = scheme.generate(index=5, difficulty=0.5)
    atlas_map = rse.Atlas([SIX], 2, 2).terrain
    for thing in [scheme, wall(), *scheme.obstacles]:
        for again in [pickle.loads(pickle.dumps(thing)), copy.deepcopy(thing), copy.copy(thing)]:
            assert type(again) is type(thing) and again == thing
    for t in [terrain, atlas_map]:
        for again in [pickle.loads(pickle.dumps(t)), copy.deepcopy(t)]:
            np.testing.assert_array_equal(again.heights, t.heights)
            assert (again.seed, again.index, again.difficulty, again.drawn) == (t.seed, t.index, t.difficulty, t.drawn)
            assert (again.block_size, again.step_height, again.base) == (t.block_size, t.step_height, t.base)
            np.testing.assert_array_equal(again.boxes(), t.boxes())
    assert pickle.loads(pickle.dumps(scheme)).to_csv() == scheme.to_csv(), "notes and all"
    with pytest.raises(ValueError, match="make terrains with Scheme.generate"):
        rse.Terrain("{}", b"")


def _heights_sum(terrain: rse.Terrain) -> int:
    return int(terrain.heights.sum())


def test_terrains_reach_spawned_worker_processes() -> None:
    """What vectorised environments do: ship terrains to subprocesses."""
    terrains = rse.generate_batch(rse.Scheme.load(SIX), 4)
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        sums = list(pool.map(_heights_sum, terrains))
    assert sums == [_heights_sum(t) for t in terrains]


def test_reprs_are_the_calls_that_make_them() -> None:
    obstacle = wall(sigma=None)
    assert repr(obstacle) == "rse.Obstacle('wall', height=(1, 3), angle=45.0, x1=(1, 2), y1=1, x2=6, y2=5)"
    scheme = rse.Scheme([obstacle], size=(12, 10), step_height=0.05)
    assert repr(scheme) == f"rse.Scheme([{obstacle!r}], size=(12, 10), step_height=0.05)"
    for thing in [obstacle, scheme, rse.Scheme.load(SIX), rse.Scheme(pallets=(2, 3), pallet_boundary=False)]:
        assert eval(repr(thing), {"rse": rse}) == thing or thing.to_csv().startswith("#")
    assert "ObstacleFields" not in repr(rse.Scheme.load(SIX)) and "Some(" not in repr(rse.Scheme.load(SIX))


def test_help_shows_real_defaults() -> None:
    """No `...` (Ellipsis) where a default is, in any public callable."""
    for name in rse.__all__:
        thing = getattr(rse, name)
        members = [thing] + [m for n, m in vars(thing).items() if not n.startswith("_")] if inspect.isclass(thing) else [thing]
        for member in members:
            if not callable(member):
                continue
            try:
                signature = inspect.signature(member)
            except (TypeError, ValueError):
                continue
            for p in signature.parameters.values():
                assert p.default is not Ellipsis, f"rse.{name}: {member} shows {p.name}=..."
    assert "size=(10, 10)" in str(inspect.signature(rse.Scheme))


# --- height_at, replace ---------------------------------------------------


def test_height_at_reads_the_top_under_points_and_is_vectorised() -> None:
    terrain = rse.Scheme.load(SIX).generate(index=3)
    s = terrain.block_size
    ny, nx = terrain.heights.shape
    ys, xs = np.mgrid[0:ny, 0:nx]
    centres = terrain.height_at((xs + 0.5) * s, (ys + 0.5) * s)
    assert centres.shape == (ny, nx) and centres.dtype == np.float64
    np.testing.assert_allclose(centres, terrain.base + terrain.heights * terrain.step_height)
    assert isinstance(terrain.height_at(0.05, 0.05), float)
    # On the line between two cells: the higher of them.
    x, y = 7, 9
    edge = terrain.height_at((x + 1) * s, (y + 0.5) * s)
    assert edge == pytest.approx(max(centres[y, x], centres[y, x + 1]))
    # A scanner's rays broadcast against one row of points.
    rows = terrain.height_at(np.linspace(0, nx * s, 7)[None, :], np.array([[0.2], [0.4]]))
    assert rows.shape == (2, 7)
    assert terrain.height_at(-0.1, 1.0) == 0.0, "off the terrain: the ground"
    assert np.isnan(terrain.height_at(nx * s + 0.01, 1.0, outside=np.nan))


def test_replace_makes_curricula() -> None:
    scheme = rse.Scheme.load(SIX)
    bigger = scheme.replace(size=(60, 60), step_height=0.05, seed=3)
    assert bigger.grid == (60, 60) and bigger.step_height == 0.05 and bigger.seed == 3
    assert bigger.obstacles == scheme.obstacles and bigger.block_size == scheme.block_size
    assert scheme.grid == (50, 50), "the original is unchanged"
    fewer = scheme.replace(obstacles=scheme.obstacles[:2])
    assert len(fewer.obstacles) == 2
    pallets = rse.Scheme(pallets=(2, 3), pallet_size=4)
    assert pallets.replace(pallets=None).grid == (10, 10), "pallets off takes their size along"
    with pytest.raises(TypeError, match="unexpected keyword argument 'heigth'"):
        scheme.replace(heigth=3)
    with pytest.raises(rse.SchemeError) as caught:
        scheme.replace(block_size=-1.0)
    assert caught.value.field == "block_size"


# --- MJCF into a robot's model ---------------------------------------------

ROBOT = """<mujoco model="robot"><worldbody><geom name="floor" type="plane" size="0 0 1"/>
<body name="ball" pos="{x} {y} 1"><freejoint/><geom name="ball" type="sphere" size="0.04"/></body>
</worldbody></mujoco>"""


def test_an_mjcf_fragment_attaches_to_a_robot_and_holds_it() -> None:
    terrain = rse.Scheme.load(SIX).generate(index=1)
    offset = (-2.5, -2.5, 0.0)
    x, y = 0.35, -0.15  # world frame: terrain point (2.85, 2.35)
    top = terrain.height_at(x - offset[0], y - offset[1])
    robot = mujoco.MjSpec.from_string(ROBOT.format(x=x, y=y))
    fragment = terrain.mjcf(fragment=True, friction=(0.9, 0.01, 0.001))
    assert "<compiler" not in fragment and "<option" not in fragment and 'name="floor"' not in fragment
    robot.attach(mujoco.MjSpec.from_string(fragment), prefix="terrain/", frame=robot.worldbody.add_frame(pos=offset))
    model = robot.compile()
    data = mujoco.MjData(model)
    boxes = [i for i in range(model.ngeom) if model.geom(i).name.startswith("terrain/rse_box_")]
    assert len(boxes) == len(terrain.boxes())
    np.testing.assert_allclose(model.geom_friction[boxes[0]], [0.9, 0.01, 0.001])
    mujoco.mj_step(model, data, nstep=1500)
    ball = model.body("ball").id
    assert data.xpos[ball][2] == pytest.approx(top + 0.04, abs=0.01), "the ball rests on the top under it"


def test_mjcf_prefix_and_offset_move_and_rename_everything() -> None:
    terrain = rse.Scheme.load(SCHEMES / "wall.csv").generate()
    plain = mujoco.MjModel.from_xml_string(terrain.mjcf())
    moved = mujoco.MjModel.from_xml_string(terrain.mjcf(prefix="t0_", offset=(1.0, -2.0, 0.5), friction=0.7))
    assert moved.ngeom == plain.ngeom
    names = [moved.geom(i).name for i in range(moved.ngeom)]
    assert all(n.startswith("t0_") for n in names), names[:3]
    mujoco.mj_forward(plain, pd := mujoco.MjData(plain))
    mujoco.mj_forward(moved, md := mujoco.MjData(moved))
    box = plain.geom("rse_box_0").id
    np.testing.assert_allclose(md.geom_xpos[moved.geom("t0_rse_box_0").id], pd.geom_xpos[box] + [1.0, -2.0, 0.5])
    assert moved.geom_friction[moved.geom("t0_rse_box_0").id][0] == pytest.approx(0.7)
    assert terrain.mjcf() == terrain.mjcf(fragment=False, prefix="", offset=(0, 0, 0)), "defaults: the template's bytes"
    with pytest.raises(ValueError, match="friction"):
        terrain.mjcf(friction=(1, 2, 3, 4))
    with pytest.raises(TypeError, match="friction"):
        terrain.mjcf(friction="high")


# --- one terrain as a world folder, preview, CSV ----------------------------


def test_write_world_writes_the_batch_world_of_that_terrain(tmp_path: Path) -> None:
    scheme = rse.Scheme.load(SIX)
    rse.write_worlds(scheme, tmp_path / "batch", amount=4, seed=9, targets="gazebo,mujoco,urdf", difficulty=0.5)
    terrain = scheme.generate(seed=9, index=3, difficulty=0.5)
    folder = tmp_path / "mine" / "world_0003"
    assert rse.write_world(terrain, folder, targets="gazebo,mujoco,urdf") == "written"
    batch = tmp_path / "batch" / "world_0003"
    files = sorted(p.relative_to(batch) for p in batch.rglob("*") if p.is_file())
    assert files == sorted(p.relative_to(folder) for p in folder.rglob("*") if p.is_file())
    for f in files:
        assert (batch / f).read_bytes() == (folder / f).read_bytes(), f
    assert rse.write_world(terrain, folder, targets="gazebo,mujoco,urdf") == "skipped"
    named = tmp_path / "mine" / "stairs_demo"
    rse.write_world(pickle.loads(pickle.dumps(terrain)), named, targets="mujoco")
    report = rse.check([named])
    assert report.ok, report
    assert json.loads((named / "rse.json").read_text())["world"] == "stairs_demo"
    with pytest.raises(FileExistsError, match=r"pass force=True to replace it") as caught:
        rse.write_world(terrain, named, targets="gazebo")
    assert "--force" not in str(caught.value)
    assert rse.write_world(terrain, named, targets="gazebo", force=True) == "replaced"
    with pytest.raises(ValueError, match="Atlas.write"):
        rse.write_world(rse.Atlas([SIX], 1, 2).terrain, tmp_path / "atlas")


def test_preview_csv_and_drawn_are_the_world_folders(tmp_path: Path) -> None:
    scheme = rse.Scheme.load(SIX)
    rse.write_worlds(scheme, tmp_path, amount=2, targets="mujoco")
    terrain = scheme.generate(index=1)
    world = tmp_path / "world_0001"
    assert terrain.preview() == (world / "preview.png").read_bytes()
    assert terrain.heightmap_csv() == (world / "heightmap.csv").read_text()
    assert terrain.drawn == json.loads((world / "rse.json").read_text())["drawn"]
    terrain.save(tmp_path / "t.png")
    terrain.save(tmp_path / "t.csv")
    assert (tmp_path / "t.png").read_bytes() == terrain.preview()
    assert (tmp_path / "t.csv").read_text() == terrain.heightmap_csv()
    big = terrain.preview(cell_pixels=8)
    assert big[:8] == b"\x89PNG\r\n\x1a\n" and len(big) > len(terrain.preview(cell_pixels=1))
    with pytest.raises(ValueError, match="pass a smaller cell_pixels"):
        terrain.preview(cell_pixels=10_000)
