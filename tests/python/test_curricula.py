"""Curricula: difficulty from Python is the CLI's, and bad
difficulties are refused."""

from pathlib import Path

import numpy as np
import pytest
import rse
from conftest import SCHEMES, heights, run

SAMPLES = sorted(SCHEMES.glob("*.csv"))


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_difficulty_matches_rse_gen_heightmap(scheme: Path) -> None:
    loaded = rse.Scheme.load(scheme)
    full = loaded.generate(seed=3, index=2).heights
    for d in [0.0, 0.25, 0.5, 0.9]:
        terrain = loaded.generate(seed=3, index=2, difficulty=d)
        assert terrain.difficulty == d
        np.testing.assert_array_equal(terrain.heights, heights(scheme, 3, 2, d))
        assert (terrain.heights <= full).all()
    assert loaded.generate(seed=3, index=2, difficulty=1).difficulty == 1.0


def test_generate_batch_and_write_worlds_take_a_difficulty(tmp_path: Path) -> None:
    scheme = rse.Scheme.load(SCHEMES / "six_obstacles.csv")
    batch = rse.generate_batch(scheme, 3, seed=1, difficulty=0.4)
    for i, terrain in enumerate(batch):
        np.testing.assert_array_equal(terrain.heights, scheme.generate(seed=1, index=i, difficulty=0.4).heights)
    rse.write_worlds(scheme, tmp_path, amount=2, seed=1, targets="obj", difficulty=0.4)
    report = rse.check(tmp_path)
    assert report.ok and report.checked == 2, report
    text = (tmp_path / "world_0001" / "heightmap.csv").read_text()
    written = np.array([[int(v) for v in line.split(",")] for line in text.splitlines()])
    np.testing.assert_array_equal(written, heights(SCHEMES / "six_obstacles.csv", 1, 1, 0.4))


@pytest.mark.parametrize("bad", [-0.1, 1.5, float("nan"), float("inf")])
def test_bad_difficulties_are_refused(bad: float) -> None:
    scheme = rse.Scheme.load(SCHEMES / "wall.csv")
    with pytest.raises(ValueError, match="from 0 to 1"):
        scheme.generate(difficulty=bad)
    with pytest.raises(ValueError, match="from 0 to 1"):
        rse.generate_batch(scheme, 1, difficulty=bad)


def test_a_difficulty_that_is_text_is_a_type_error() -> None:
    with pytest.raises(TypeError):
        rse.Scheme.load(SCHEMES / "wall.csv").generate(difficulty="hard")  # type: ignore[arg-type]


# --- atlases ------------------------------------------------------------------

ATLAS_SCHEMES = [SCHEMES / "random.csv", SCHEMES / "gaussian.csv"]
ATLAS_ARGS = dict(rows=3, cols=4, seed=5, border=2, difficulty=(0.2, 1.0), flat_patches=3, patch_radius=0.2, max_step=1)


def cli_atlas(out: Path, *extra: str) -> None:
    a = ATLAS_ARGS
    run(
        "atlas",
        *map(str, ATLAS_SCHEMES),
        "--rows", str(a["rows"]), "--cols", str(a["cols"]), "--seed", str(a["seed"]),
        "--border", str(a["border"]), "--difficulty", "0.2..1",
        "--flat-patches", "3", "--patch-radius", "0.2", "--max-step", "1",
        "-o", str(out), *extra,
    )  # fmt: skip


def test_atlas_from_python_is_the_cli_atlas_byte_for_byte(tmp_path: Path) -> None:
    targets = ",".join(rse.TARGETS)
    cli_atlas(tmp_path / "cli" / "atlas", "--target", targets)
    atlas = rse.Atlas([str(p) for p in ATLAS_SCHEMES], **ATLAS_ARGS)
    assert atlas.write(tmp_path / "py" / "atlas", targets=targets) == "written"
    assert atlas.write(tmp_path / "py" / "atlas", targets=targets) == "skipped"
    cli = sorted(p.relative_to(tmp_path / "cli") for p in (tmp_path / "cli").rglob("*") if p.is_file())
    py = sorted(p.relative_to(tmp_path / "py") for p in (tmp_path / "py").rglob("*") if p.is_file())
    assert cli == py and len(cli) > 10
    for rel in cli:
        assert (tmp_path / "cli" / rel).read_bytes() == (tmp_path / "py" / rel).read_bytes(), rel
    # Scheme objects loaded from the files record the same names.
    from_objects = rse.Atlas([rse.Scheme.load(p) for p in ATLAS_SCHEMES], **ATLAS_ARGS)
    assert from_objects.to_json() == atlas.to_json()
    written = np.loadtxt(tmp_path / "py" / "atlas" / "heightmap.csv", delimiter=",", dtype=np.uint16)
    np.testing.assert_array_equal(atlas.terrain.heights, written)


def test_atlas_origins_tiles_and_patches() -> None:
    atlas = rse.Atlas(ATLAS_SCHEMES, **ATLAS_ARGS)
    rows, cols = ATLAS_ARGS["rows"], ATLAS_ARGS["cols"]
    assert atlas.origins.shape == (rows, cols, 3) and atlas.origins.dtype == np.float64
    tiles = atlas.tiles
    assert len(tiles) == rows * cols
    terrain = atlas.terrain
    for t in tiles:
        r, c = t["row"], t["col"]
        np.testing.assert_allclose(atlas.origins[r, c], t["origin"], atol=1e-9)
        x0, y0, x1, y1 = t["cells"]
        scheme = rse.Scheme.load(ATLAS_SCHEMES[c % 2])
        tile = scheme.generate(seed=5, index=r * cols + c, difficulty=t["difficulty"]).heights
        np.testing.assert_array_equal(terrain.heights[y0:y1, x0:x1], tile)
        assert len(t["flat_patches"]) <= 3
    patches = atlas.flat_patches(5, radius=0.25, max_step=1)
    assert patches.shape == (rows, cols, 5, 3)
    s = terrain.block_size
    found = 0
    for r in range(rows):
        for c in range(cols):
            for k, (x, y, z) in enumerate(patches[r, c]):
                if np.isnan(x):
                    assert np.isnan(patches[r, c, k:]).all()
                    break
                found += 1
                # Every cell the disc touches is within one step, z on the highest.
                xs, ys = np.arange(terrain.heights.shape[1]), np.arange(terrain.heights.shape[0])
                dx = np.maximum(np.maximum(xs * s - x, x - (xs + 1) * s), 0)
                dy = np.maximum(np.maximum(ys * s - y, y - (ys + 1) * s), 0)
                near = dx[None, :] ** 2 + dy[:, None] ** 2 <= (0.25 + 1e-9) ** 2
                under = terrain.elevation[near]
                assert under.max() - under.min() <= terrain.step_height + 1e-9
                assert under.max() == pytest.approx(z)
    assert found > 0
    # Borders are 0 all round.
    h = terrain.heights
    assert (h[:2] == 0).all() and (h[-2:] == 0).all() and (h[:, :2] == 0).all() and (h[:, -2:] == 0).all()


def test_atlas_bad_arguments_name_the_argument(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="rows"):
        rse.Atlas(ATLAS_SCHEMES, 0, 2)
    with pytest.raises(ValueError, match="from 0 to 1"):
        rse.Atlas(ATLAS_SCHEMES, 2, 2, difficulty=(0.0, 2.0))
    other = tmp_path / "steps.csv"
    other.write_text("# size: 20x20\n# step_height: 0.05\ntype,height\nrandom,2\n")
    with pytest.raises(rse.SchemeError, match="step_height") as err:
        rse.Atlas([ATLAS_SCHEMES[0], other], 2, 2)
    assert err.value.field == "step_height"
    with pytest.raises(TypeError, match=r"schemes\[0\]"):
        rse.Atlas([42], 1, 1)  # type: ignore[list-item]


def test_atlas_origins_start_no_body_inside_a_block_in_mujoco() -> None:
    """Spheres set on every origin touch the terrain without penetrating it."""
    import mujoco

    atlas = rse.Atlas([SCHEMES / "six_obstacles.csv"], 3, 3, seed=1, spawn_radius=0.05)
    spec = mujoco.MjSpec.from_string(atlas.terrain.mjcf())
    radius = 0.05
    for i, (x, y, z) in enumerate(atlas.origins.reshape(-1, 3)):
        body = spec.worldbody.add_body(name=f"robot_{i}", pos=[x, y, z + radius + 1e-4])
        body.add_freejoint()
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[radius, 0, 0], mass=1.0)
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert all(data.contact[k].dist > -1e-6 for k in range(data.ncon))


def test_atlas_world_loads_in_pybullet_with_no_body_inside_a_block(tmp_path: Path) -> None:
    """The atlas's URDF (a concave mesh) in PyBullet: spheres set on every
    origin touch the terrain without sinking into it."""
    import pybullet as p

    atlas = rse.Atlas([SCHEMES / "six_obstacles.csv"], 2, 3, seed=4, border=1, spawn_radius=0.06)
    atlas.write(tmp_path / "atlas", targets="urdf")
    client = p.connect(p.DIRECT)
    try:
        terrain = p.loadURDF(str(tmp_path / "atlas" / "urdf" / "rse.urdf"), useFixedBase=True, physicsClientId=client)
        assert terrain >= 0
        shape = p.createCollisionShape(p.GEOM_SPHERE, radius=0.05, physicsClientId=client)
        bodies = [
            p.createMultiBody(0.1, shape, basePosition=[x, y, z + 0.05 + 1e-4], physicsClientId=client)
            for x, y, z in atlas.origins.reshape(-1, 3)
        ]
        p.performCollisionDetection(physicsClientId=client)
        for body in bodies:
            for contact in p.getContactPoints(bodyA=body, physicsClientId=client):
                assert contact[8] > -1e-3, contact  # contact distance: no penetration
    finally:
        p.disconnect(client)


def test_check_curriculum_is_the_cli_report() -> None:
    import json

    for scheme in SAMPLES:
        report = rse.check_curriculum(scheme, draws=10, seed=4)
        assert report.ok, (scheme, report.problems)
        assert [level.level for level in report.levels] == list(range(10))
        means = [level.mean_height for level in report.levels]
        assert means[0] == 0 and all(a < b for a, b in zip(means, means[1:])), means
        assert all(level.flat_share < 1 for level in report.levels[1:])
        cli = json.loads(run("check-curriculum", str(scheme), "--draws", "10", "--seed", "4", "--json"))
        assert cli["ok"] and cli["seed"] == report.seed == 4
        for ours, theirs in zip(report.levels, cli["per_level"]):
            assert ours.mean_height == theirs["mean_height"] and ours.distinct == theirs["distinct"]


def test_check_curriculum_finds_a_flat_scheme_and_refuses_bad_counts() -> None:
    flat = rse.Scheme.from_csv("# size: 4x4\ntype,height\n")
    report = rse.check_curriculum(flat, levels=3, draws=2)
    assert not report and "flat at difficulty 1" in report.problems[0]
    with pytest.raises(ValueError, match="levels 1"):
        rse.check_curriculum(flat, levels=1)
    with pytest.raises(ValueError, match="draws 0"):
        rse.check_curriculum(flat, draws=0)


def test_check_curriculum_is_priced_and_stops_on_ctrl_c() -> None:
    """Fifth hardening round: 1000 levels x 100,000 draws of 300x300 (~72 h)
    were accepted with no estimate, and Ctrl-C was ignored to the end. A
    check priced over its budget is refused before a world is made; one
    running stops between worlds on Ctrl-C."""
    import os
    import signal
    import threading
    import time

    big = rse.Scheme.from_csv("# size: 300x300\ntype,height\nrandom,4\n")
    started = time.monotonic()
    with pytest.raises(ValueError, match="over the budget"):
        rse.check_curriculum(big, levels=1000, draws=100_000)
    assert time.monotonic() - started < 5, "refused before a world is made"
    with pytest.raises(ValueError, match="budget"):
        rse.check_curriculum(big, budget=0)
    # Python's own Ctrl-C (an earlier test in the same worker, through an
    # event loop, may have left another handler): what a user's shell gets.
    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    try:
        # 100,000 worlds, some two minutes to the end: a missed Ctrl-C
        # fails the bound below instead of hanging the suite.
        with pytest.raises(KeyboardInterrupt):
            rse.check_curriculum(big, levels=200, draws=500, budget=1000)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, handler)
    assert time.monotonic() - started < 10, "stopped between worlds, not at the end"
