"""rse inside mjlab's own locomotion task: the registered
`Mjlab-Velocity-Rough-Unitree-Go1` config taken as it is by
`rse.mjlab.use_env_terrains` (its terrain, terrain-level curriculum and
out-of-bounds term replaced, every other term kept), built and stepped with
mjlab's Go1 on MuJoCo Warp's CPU device: its `terrain_scan` ray sensor sees
each env's own terrain (equal to `heights_at` where a ray hits a top away
from a step edge), the feet stand on their own env's tops, a reset renews
only the named envs, and the curriculum moves the difficulty of the envs
that reset."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest
import rse
import torch
from mjlab.envs import ManagerBasedRlEnv
from mjlab.tasks.registry import load_env_cfg
from rse.mjlab import env_terrains, out_of_slot, terrain_difficulty, use_env_terrains
from rse.mjlab_tasks import STEPFIELD

import mjlab.tasks  # noqa: F401  (registers the tasks)

TASK = "Mjlab-Velocity-Rough-Unitree-Go1"
# Two stepped hills, placed and sized anew for every env and episode: their
# terraces are tops wide enough for the ray sensor's grid to land on.
SCHEME = rse.Scheme.from_csv(
    "# size: 40x40\n# step_height: 0.04\ntype,height,angle,x1,y1\npeak,3..6,12,8..32,8..32\npeak,2..5,12,8..32,8..32\n"
)
NUM_ENVS = 4


def task_cfg():
    cfg = load_env_cfg(TASK)
    cfg.scene.num_envs = NUM_ENVS
    return cfg


@pytest.fixture(scope="module")
def go1():
    cfg = task_cfg()
    use_env_terrains(cfg, SCHEME, seed=5, difficulty=0.5)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    env.reset()
    yield env
    env.close()


def step(env: ManagerBasedRlEnv, n: int) -> None:
    """Steps the default pose (zero actions: the joints held at their
    default positions)."""
    for _ in range(n):
        env.step(torch.zeros(env.action_space.shape))


def test_the_registered_config_is_taken_as_it_is() -> None:
    cfg = task_cfg()
    before = {k: set(getattr(cfg, k)) for k in ("events", "rewards", "terminations", "curriculum", "commands")}
    sensors = [s.name for s in cfg.scene.sensors]
    use_env_terrains(cfg, SCHEME)
    assert type(cfg.scene.terrain).__name__ == "EnvTerrainCfg" and cfg.scene.terrain.terrain_type == "plane"
    assert cfg.scene.terrain.scheme == SCHEME.to_csv() and cfg.scene.terrain.max_init_terrain_level == 5
    assert set(cfg.rewards) == before["rewards"] and set(cfg.commands) == before["commands"]
    assert [s.name for s in cfg.scene.sensors] == sensors
    assert set(cfg.events) == before["events"] | {"rse_terrain", "rse_terrain_near"} and next(iter(cfg.events)) == "rse_terrain"
    assert cfg.events["rse_terrain_near"].mode == "step"
    assert set(cfg.curriculum) == before["curriculum"] - {"terrain_levels"} | {"rse_terrain_difficulty"}
    term = cfg.curriculum["rse_terrain_difficulty"]
    assert term.func is terrain_difficulty and term.params["command_name"] == "twist"
    assert set(cfg.terminations) == before["terminations"]
    assert cfg.terminations["out_of_terrain_bounds"].func is out_of_slot
    assert cfg.terminations["out_of_terrain_bounds"].time_out


def flat_under(envs: rse.EnvTerrains, e: int, xy: np.ndarray, reach: float) -> np.ndarray:
    """Where the tops within ``reach`` of each point (x and y, probed at a
    tenth of a cell) are one top."""
    here = envs.heights_at([e], xy[None])[0]
    same = np.isfinite(here)
    for dx in np.linspace(-reach, reach, 9):
        for dy in np.linspace(-reach, reach, 9):
            there = envs.heights_at([e], (xy + [dx, dy])[None])[0]
            same &= there == here
    return same


def test_terrain_scan_sees_each_envs_own_terrain(go1) -> None:
    envs = env_terrains(go1)
    step(go1, 2)
    hits = go1.scene.sensors["terrain_scan"].data.hit_pos_w.cpu().numpy().astype(np.float64)
    t = envs.terrain(0)
    spacing = t.block_size / envs.field_shape[0] * t.heights.shape[0]  # one sample
    compared = 0
    for e in range(NUM_ENVS):
        xy = hits[e, :, :2]
        exact = envs.heights_at([e], xy[None])[0]
        # Away from step edges the field's surface is the top itself; within
        # a sample of one it is MuJoCo's slope between two samples.
        flat = flat_under(envs, e, xy, 1.5 * spacing)
        assert flat.sum() >= 10, f"env {e}: too few rays on flat tops"
        assert np.abs(hits[e, flat, 2] - exact[flat]).max() <= 0.01, e
        compared += int(flat.sum())
        # Other envs' tops are not what this env's rays see. Under a small
        # scan two random terrains can agree (both at ground level there:
        # seen once in CI), so some other env must differ, not the next one.
        others = [envs.heights_at([o], xy[None])[0] for o in range(NUM_ENVS) if o != e]
        assert max(np.abs(hits[e, flat, 2] - other[flat]).max() for other in others) > 0.01, e
    assert compared >= 60


def test_the_feet_stand_on_their_own_envs_tops(go1) -> None:
    envs = env_terrains(go1)
    go1.reset()
    step(go1, 25)
    model = go1.sim.mj_model
    robot = go1.scene["robot"]
    feet = [n for n in robot.geom_names if n.endswith("_foot_collision")]
    assert len(feet) == 4, robot.geom_names
    ids = [mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, f"robot/{n}") for n in feet]
    assert min(ids) >= 0
    radius = float(model.geom_size[ids[0], 0])
    before = go1.sim.data.geom_xpos.cpu().numpy()[:, ids].astype(np.float64)
    step(go1, 1)
    xpos = go1.sim.data.geom_xpos.cpu().numpy()[:, ids].astype(np.float64)  # (envs, feet, 3)
    # Feet at rest (under 2 mm in a 20 ms step): a robot the zero action
    # lets fall, or one its reset just moved, has feet in flight or landing
    # (sinking 4 cm into the soft contact for a moment); they are not
    # standing anywhere yet.
    resting = np.linalg.norm(xpos - before, axis=2) < 0.002
    assert resting.sum() >= NUM_ENVS, resting
    t = envs.terrain(0)
    reach = radius + 1.5 * t.block_size * t.heights.shape[0] / envs.field_shape[0]
    probes = np.array([[dx, dy] for dx in np.linspace(-reach, reach, 9) for dy in np.linspace(-reach, reach, 9)])
    for e in range(NUM_ENVS):
        # The tops of this env's terrain around each foot: a foot rests on
        # one, or on the field's slope between two within a sample of an edge.
        around = np.stack([envs.heights_at([e], (xpos[e, :, :2] + d)[None])[0] for d in probes])
        # MuJoCo's contacts are soft: a foot landing sinks a centimetre or two.
        bottom = xpos[e, :, 2] - radius
        still = resting[e]
        assert np.all(bottom[still] > around.min(axis=0)[still] - 0.025), (e, bottom, around.min(axis=0))
        assert np.all(bottom[still] < around.max(axis=0)[still] + 0.01), (e, bottom, around.max(axis=0))


def test_a_reset_renews_only_the_named_envs(go1) -> None:
    envs = env_terrains(go1)
    # Hills again (the curriculum may have flattened them as robots fell).
    envs.difficulty = [1.0] * NUM_ENVS
    go1.reset()
    before_samples = envs.samples.copy()
    before_episode = envs.episode.copy()
    go1.reset(env_ids=torch.tensor([1, 2]))
    assert (envs.episode - before_episode).tolist() == [0, 1, 1, 0]
    for e in (0, 3):
        assert np.array_equal(envs.samples[e], before_samples[e])
    for e in (1, 2):
        assert not np.array_equal(envs.samples[e], before_samples[e])
    # The simulation's fields hold the new samples.
    model = go1.sim.mj_model
    data = go1.sim.wp_model.hfield_data.numpy()
    for e in range(NUM_ENVS):
        hid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_HFIELD, f"rse_env{e}")
        adr, n = model.hfield_adr[hid], model.hfield_nrow[hid] * model.hfield_ncol[hid]
        assert np.array_equal(data[adr : adr + n], envs.samples[e].ravel()), e


def test_the_curriculum_moves_the_difficulty_of_the_envs_that_reset(go1) -> None:
    envs = env_terrains(go1)
    envs.difficulty = [0.5] * NUM_ENVS
    step(go1, 5)
    # Every robot was asked to walk 1 m/s and stands near its spawn point:
    # it walked less than half of that, so the envs that reset go down a
    # level (mjlab's terrain-levels rule; one of its 10 rows: 1/9), the
    # others keep theirs.
    go1.command_manager.get_command("twist")[:, 0] = 1.0
    go1.reset(env_ids=torch.tensor([0, 3]))
    down = 0.5 - 1 / 9
    assert np.allclose(envs.difficulty, [down, 0.5, 0.5, down]), envs.difficulty
    assert envs.terrain(0).difficulty == pytest.approx(down)


def scan_matches(env: ManagerBasedRlEnv, min_rays: int) -> int:
    """Compares ``terrain_scan``'s hits with ``heights_at`` where the rays
    land on a top (not within a sample and a half of a step edge, where the
    field is MuJoCo's slope between two samples); returns how many."""
    envs = env_terrains(env)
    hits = env.scene.sensors["terrain_scan"].data.hit_pos_w.cpu().numpy().astype(np.float64)
    t = envs.terrain(0)
    spacing = t.block_size * t.heights.shape[0] / envs.field_shape[0]
    compared = 0
    for e in range(env.num_envs):
        xy = hits[e, :, :2]
        flat = flat_under(envs, e, xy, 1.5 * spacing)
        assert flat.sum() >= min_rays, f"env {e}: {flat.sum()} rays on tops"
        exact = envs.heights_at([e], xy[None])[0]
        assert np.abs(hits[e, flat, 2] - exact[flat]).max() <= 0.01, e
        compared += int(flat.sum())
    return compared


def test_the_rse_tasks_are_in_mjlabs_registry() -> None:
    """rse's ``mjlab.tasks`` entry point registers a variant of each of
    mjlab's rough tasks, its terms in place (``train`` runs one below)."""
    from mjlab.tasks.registry import list_tasks

    assert {"Rse-Velocity-Rough-Unitree-Go1", "Rse-Velocity-Rough-Unitree-G1"} <= set(list_tasks())
    for robot in ("Go1", "G1"):
        for play in (False, True):
            cfg = load_env_cfg(f"Rse-Velocity-Rough-Unitree-{robot}", play=play)
            terrain = cfg.scene.terrain
            assert type(terrain).__name__ == "EnvTerrainCfg" and next(iter(cfg.events)) == "rse_terrain"
            assert terrain.scheme == STEPFIELD and terrain.difficulty is None
            # The robots may be moved ±0.5 m in x and y around their origin
            # (reset_base): the spawn disc covers that square.
            assert cfg.events["reset_base"].params["pose_range"]["x"] == (-0.5, 0.5)
            assert terrain.spawn_radius == pytest.approx(0.5 * 2**0.5)
            assert "terrain_levels" not in cfg.curriculum


def test_the_registered_task_starts_spread_over_the_easy_levels_as_mjlabs_does() -> None:
    """mjlab starts each env at a level drawn from 0 … 5 of its 10 rows
    (``max_init_terrain_level``); the rse task starts each at difficulty
    level/9 for such a level, the same for the same seed, and its
    curriculum moves one level at a time."""
    mjlab_terrain = load_env_cfg("Mjlab-Velocity-Rough-Unitree-Go1").scene.terrain
    assert (mjlab_terrain.max_init_terrain_level, mjlab_terrain.terrain_generator.num_rows) == (5, 10)
    cfg = load_env_cfg("Rse-Velocity-Rough-Unitree-Go1")
    cfg.scene.num_envs = 24
    # One level a step: the step follows the scene's terrain_levels when run.
    assert cfg.scene.terrain.terrain_levels == 10 and "step" not in cfg.curriculum["rse_terrain_difficulty"].params
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        d = env_terrains(env).difficulty
        levels = d * 9
        np.testing.assert_allclose(levels, np.round(levels), atol=1e-9)
        assert set(np.round(levels).astype(int)) <= set(range(6)) and len(set(np.round(levels))) >= 4
        assert [env_terrains(env).terrain(e).difficulty for e in range(24)] == pytest.approx(list(d))
    finally:
        env.close()
    # Given explicitly, one difficulty for all; out of range, refused at the call.
    cfg = load_env_cfg("Mjlab-Velocity-Rough-Unitree-Go1")
    with pytest.raises(ValueError, match="max_init_terrain_level"):
        use_env_terrains(cfg, SCHEME, max_init_terrain_level=10)


def test_the_g1_task_builds_with_the_envs_asked_for_and_scans_its_own_terrain() -> None:
    """mjlab's G1 rough task on rse's pool: a config whose env count is set
    after ``use_env_terrains`` builds that many fields, and the G1's
    ``terrain_scan`` sees each env's own terrain."""
    cfg = load_env_cfg("Mjlab-Velocity-Rough-Unitree-G1")
    use_env_terrains(cfg, SCHEME, seed=2)
    cfg.scene.num_envs = 3
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        model = env.sim.mj_model
        fields = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_HFIELD, h) for h in range(model.nhfield)]
        assert [f for f in fields if f.startswith("rse_env")] == [f"rse_env{s}{e}" for s in ("", "_coarse") for e in range(3)]
        env.reset()
        step(env, 2)
        assert scan_matches(env, min_rays=5) >= 30
    finally:
        env.close()


def test_mjlabs_own_train_script_runs_an_rse_task_on_a_users_scheme_set_on_its_command_line(tmp_path) -> None:
    """mjlab's ``train`` runs ``Rse-Velocity-Rough-Unitree-Go1`` by name on
    the CPU with the scheme, seed and starting difficulty set on its own
    command line (``--env.scene.terrain.*``): one PPO iteration of its own
    runner, episodes short enough to end within it, so rse's curriculum
    term is logged, into rse's own log folder."""
    import json
    import os
    import subprocess
    import sys

    scheme = tmp_path / "mine.csv"
    scheme.write_text("# size: 30x30\n# step_height: 0.04\ntype,height,angle,x1,y1\npeak,3,45,15,15\n")
    train = Path(sys.executable).parent / "train"
    done = subprocess.run(
        [str(train), "Rse-Velocity-Rough-Unitree-Go1", "--env.scene.num-envs", "3", "--env.episode-length-s", "0.1",
         "--env.scene.terrain.scheme", str(scheme), "--env.scene.terrain.seed", "7",
         "--env.scene.terrain.difficulty", "0.3",
         "--agent.max-iterations", "1", "--agent.num-steps-per-env", "12", "--agent.logger", "tensorboard"],
        cwd=tmp_path, capture_output=True, text=True, timeout=1200,
        env={**os.environ, "CUDA_VISIBLE_DEVICES": ""},
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "Learning iteration 0/1" in done.stdout
    assert "Curriculum/rse_terrain_difficulty/mean" in done.stdout, done.stdout[-3000:]
    # Its own experiment folder, apart from mjlab's go1_velocity.
    logged = list(tmp_path.glob("logs/rsl_rl/*/*/params/env.yaml"))
    assert [p.parents[2].name for p in logged] == ["rse_go1_velocity"]
    params = logged[0].read_text()
    assert "rse_terrain_difficulty" in params and "num_envs: 3" in params
    assert str(scheme) in params and "difficulty: 0.3" in params and "seed: 7" in params
    # The run says what it trained on: the scheme's text in env.yaml and
    # beside it, its SHA-256, the seed, rule, levels and rse's version; no
    # stale copy of the registered scheme.
    import hashlib

    import yaml

    class Lenient(yaml.SafeLoader):
        """Reads mjlab's env.yaml, its Python objects as None."""

    Lenient.add_multi_constructor("tag:yaml.org,2002:python/", lambda loader, suffix, node: None)
    env_yaml = yaml.load(logged[0].read_text(), Loader=Lenient)
    terrain = env_yaml["scene"]["terrain"]
    sha = hashlib.sha256(scheme.read_bytes()).hexdigest()
    assert terrain["scheme_csv"] == scheme.read_text() and terrain["scheme_sha256"] == sha
    assert "random 5 cm steps" not in params and "two stepped" not in params, "a stale copy of STEPFIELD"
    run = logged[0].parent
    assert (run / "rse_scheme.csv").read_bytes() == scheme.read_bytes()
    record = json.loads((run / "rse_terrain.json").read_text())
    assert record["scheme_sha256"] == sha and record["seed"] == 7 and record["difficulty"] == 0.3
    assert record["rse_version"] == rse.__version__ and record["difficulty_rule"] == rse.DIFFICULTY_RULE
    assert record["scheme_file"] == str(scheme) and record["env_offset"] == 0
    assert (record["max_init_terrain_level"], record["terrain_levels"]) == (5, 10)

    # The one-iteration checkpoint, evaluated on a fixed set of stepfields:
    # the same report twice, and for mjlab's own task (rse's terrain in
    # place of its own) on the same terrains.
    checkpoint = next(logged[0].parents[1].glob("model_*.pt"))
    reports = []
    for task in ("Rse-Velocity-Rough-Unitree-Go1", "Rse-Velocity-Rough-Unitree-Go1", "Mjlab-Velocity-Rough-Unitree-Go1"):
        out = tmp_path / f"eval{len(reports)}.json"
        done = subprocess.run(
            [sys.executable, "-m", "rse.mjlab_eval", str(checkpoint), "--task", task, "--levels", "3", "--per-level", "2",
             "--seconds", "1", "--seed", "5", "--json", str(out)],
            cwd=tmp_path, capture_output=True, text=True, timeout=1200,
            env={**os.environ, "CUDA_VISIBLE_DEVICES": ""},
        )
        assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
        assert "level  difficulty  distance mean (min)  falls  crossed  time to cross" in done.stdout, done.stdout[-2000:]
        assert f"scheme from the run folder: {run / 'rse_scheme.csv'}" in done.stderr, done.stderr[-2000:]
        reports.append(json.loads(out.read_text()))
    first = reports[0]
    # Evaluated on the scheme the checkpoint trained on, found in its run.
    assert first["seed"] == 5 and first["levels"] == 3 and first["scheme"] == scheme.read_text()
    assert first["scheme_source"] == "the run folder" and first["scheme_sha256"] == sha
    assert [r["difficulty"] for r in first["per_level_results"]] == [0.0, 0.5, 1.0]
    assert [e["difficulty"] for e in first["episodes"]] == [0.0, 0.0, 0.5, 0.5, 1.0, 1.0]
    assert all(r["episodes"] == 2 and 0 <= r["falls"] <= 2 for r in first["per_level_results"])
    assert reports[1]["episodes"] == first["episodes"], "the same terrains and results on a rerun"
    assert [e["episode"] for e in reports[2]["episodes"]] == [e["episode"] for e in first["episodes"]]
    done = subprocess.run([sys.executable, "-m", "rse.mjlab_eval", str(checkpoint), "--levels", "0"],
                          capture_output=True, text=True, timeout=600, env={**os.environ, "CUDA_VISIBLE_DEVICES": ""})
    assert done.returncode == 2 and "levels and per_level: 0" in done.stderr, done.stderr[-2000:]

    # A video of the checkpoint on its run's terrains, written, then done
    # (mjlab's play --video keeps its viewer open): OSMesa renders on the CPU.
    done = subprocess.run(
        [sys.executable, "-m", "rse.mjlab_video", str(checkpoint), "--steps", "10", "--num-envs", "2"],
        cwd=tmp_path, capture_output=True, text=True, timeout=1200,
        # PyOpenGL's platform too: mjlab sets MUJOCO_GL=egl when imported,
        # and MuJoCo imported after it sets PYOPENGL_PLATFORM=egl in this
        # process, which the child would read in place of osmesa (seen when
        # a test module importing mjlab first ran before this one).
        env={**os.environ, "CUDA_VISIBLE_DEVICES": "", "MUJOCO_GL": "osmesa", "PYOPENGL_PLATFORM": "osmesa"},
    )
    assert done.returncode == 0, done.stderr[-3000:]
    video = Path(done.stdout.strip().splitlines()[-1])
    assert video.parent == run.parent / "videos" / "rse" and video.suffix == ".mp4"
    # Decoded apart: imageio's ffmpeg reader leaves its pipes to the collector.
    probe = subprocess.run(
        [sys.executable, "-c", "import imageio.v3 as iio, sys; f = iio.imread(sys.argv[1]); print(f.shape[0], float(f.std()))", str(video)],
        capture_output=True, text=True, timeout=300,
    )
    frames, spread = probe.stdout.split()
    assert int(frames) == 10 and float(spread) > 5, "ten frames of something"
    assert "the terrains the run trained on (seed 7)" in done.stderr


def test_the_scene_terrains_fields_set_the_pool(tmp_path) -> None:
    """What ``train`` sets on the command line lands in the envs: the
    scheme's grid, the seed's terrains, the difficulty, the starting
    levels (``max_init_terrain_level``, mjlab's knob)."""
    scheme = tmp_path / "mine.csv"
    scheme.write_text("# size: 30x20\ntype,height\nrandom,3\n")
    cfg = load_env_cfg("Rse-Velocity-Rough-Unitree-Go1")
    cfg.scene.num_envs = 4
    cfg.scene.terrain.scheme, cfg.scene.terrain.seed, cfg.scene.terrain.difficulty = str(scheme), 7, 0.3
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        pool = env_terrains(env)
        assert pool.terrain(0).heights.shape == (20, 30)
        np.testing.assert_array_equal(pool.difficulty, [0.3] * 4)
        want = rse.EnvTerrains(rse.Scheme.load(scheme), 4, seed=7, difficulty=0.3)
        for e in range(4):
            np.testing.assert_array_equal(pool.terrain(e).heights, want.terrain(e).heights)
    finally:
        env.close()
    cfg = load_env_cfg("Rse-Velocity-Rough-Unitree-Go1")
    cfg.scene.num_envs = 30
    cfg.scene.terrain.max_init_terrain_level = 1
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        assert set(np.round(env_terrains(env).difficulty * 9).astype(int)) == {0, 1}
    finally:
        env.close()


def test_the_exact_height_scan_is_the_ray_scan_on_tops_and_exact_at_edges(go1) -> None:
    """``exact_height_scan`` has ``height_scan``'s shape and frames and its
    values where the rays land on a top; at step edges it is the exact
    top, where the rays see MuJoCo's slope between two samples."""
    from mjlab.envs import mdp as envs_mdp
    from rse.mjlab import exact_height_scan

    envs = env_terrains(go1)
    envs.difficulty = [1.0] * NUM_ENVS
    go1.reset()
    step(go1, 1)
    rays = envs_mdp.height_scan(go1, "terrain_scan").cpu().numpy()
    exact = exact_height_scan(go1, "terrain_scan").cpu().numpy()
    assert exact.shape == rays.shape
    sensor = go1.scene.sensors["terrain_scan"]
    hits = sensor.data.hit_pos_w.cpu().numpy().astype(np.float64)
    frame_z = sensor.data.frame_pos_w.cpu().numpy()[:, 0, 2]
    t = envs.terrain(0)
    spacing = t.block_size * t.heights.shape[0] / envs.field_shape[0]
    differ = 0
    for e in range(NUM_ENVS):
        xy = hits[e, :, :2]
        flat = flat_under(envs, e, xy, 1.5 * spacing)
        assert flat.sum() >= 5
        assert np.abs(exact[e, flat] - rays[e, flat]).max() <= 0.01, e
        tops = np.nan_to_num(envs.heights_at([e], xy[None])[0])
        assert np.allclose(exact[e], frame_z[e] - tops, atol=1e-5), e
        differ += int((np.abs(exact[e] - rays[e]) > 0.005).sum())
    assert differ > 0, "no ray near an edge: nothing shows the scan is exact there"


def test_play_lays_the_envs_out_apart_each_robot_on_its_own_terrain_in_the_viewers_model() -> None:
    """mjlab's viewers draw the env they follow from the host model with
    that env's per-world fields synced in (mjlab's ``sync_model_fields``),
    and every other env's dynamic geoms (``mjv_addGeoms``, ``mjCAT_DYNAMIC``).
    In the play config each env's terrain is in its own place: the view
    geom (a mocap body's, so drawn for every env) shows the env's own field
    there, its robot stands on it, and ``out_of_slot`` measures in the
    env's own slot."""
    import copy

    from mjlab.viewer.model_sync import VIEWER_MODEL_FIELDS, sync_model_fields

    cfg = load_env_cfg("Rse-Velocity-Rough-Unitree-Go1", play=True)
    assert cfg.scene.terrain.apart and not load_env_cfg("Rse-Velocity-Rough-Unitree-Go1").scene.terrain.apart
    cfg.scene.num_envs = 4
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        env.reset()
        for _ in range(5):
            env.step(torch.zeros(env.action_space.shape))
        sim, pool = env.sim, env_terrains(env)
        host = copy.copy(sim.mj_model)
        data = mujoco.MjData(host)
        view = mujoco.mj_name2id(host, mujoco.mjtObj.mjOBJ_GEOM, "rse_terrain_view")
        first = mujoco.mj_name2id(host, mujoco.mjtObj.mjOBJ_HFIELD, "rse_env0")
        x, y, _ = pool.hfield_pos
        places = []
        for e in range(4):
            sync_model_fields(host, sim.model, sim.expanded_fields & VIEWER_MODEL_FIELDS, e)
            data.qpos[:] = sim.data.qpos[e].cpu().numpy()
            data.mocap_pos[:] = sim.data.mocap_pos[e].cpu().numpy()
            mujoco.mj_forward(host, data)
            assert host.geom_dataid[view] == first + e
            centre = data.geom_xpos[view][:2].copy()
            places.append(centre)
            scene = mujoco.MjvScene(host, maxgeom=10000)
            mujoco.mjv_addGeoms(host, data, mujoco.MjvOption(), mujoco.MjvPerturb(), mujoco.mjtCatBit.mjCAT_DYNAMIC.value, scene)
            assert view in {scene.geoms[i].objid for i in range(scene.ngeom)}, "other envs' terrains are drawn"
            root = env.scene["robot"].data.root_link_pos_w[e].numpy()
            assert abs(root[0] - centre[0]) < x and abs(root[1] - centre[1]) < y, (e, root, centre)
            top = pool.heights_at([e], [[[root[0] - centre[0] + x, root[1] - centre[1] + y]]])[0, 0]
            assert 0.1 < root[2] - top < 0.6, (e, root[2], top)
        for a in range(4):
            for b in range(a):
                assert np.abs(places[a] - places[b]).max() >= 2 * min(x, y), "the envs' terrains are apart"
        assert not out_of_slot(env).any()
        # The contact sheet of the running pool: every env's current terrain.
        import struct

        png = pool.contact_sheet()
        assert png[:8] == b"\x89PNG\r\n\x1a\n"
        width, height = struct.unpack(">II", png[16:24])
        assert width >= 2 * 160 and height >= 2 * 160, (width, height)
    finally:
        env.close()


def test_the_registered_stepfield_has_no_dead_level_on_mjlabs_ten_levels() -> None:
    """Every level the curriculum moves through teaches something: no level
    above 0 all flat, the mean height rising level by level."""
    report = rse.check_curriculum(rse.Scheme.from_csv(STEPFIELD), levels=10, draws=30)
    assert report.ok, report.problems
    assert report.levels[0].flat_share == 1.0 and all(level.flat_share == 0.0 for level in report.levels[1:])
    assert all(level.distinct == 30 for level in report.levels[1:]), "every env its own terrain at every level"


def test_a_built_scene_says_the_seed_and_oversample_it_used_in_its_config_and_record() -> None:
    """Neither set: the scene's ``EnvTerrainCfg`` holds, once built, the
    scheme's own seed and rse's default oversample, so mjlab's ``env.yaml``
    (dumped from the config after the env is built) and rse's
    ``rse_terrain.json`` (``record``) say the same values, not None."""
    from rse._adapters.mjlab.run_record import record

    cfg = task_cfg()
    seeded = rse.Scheme.from_csv("# seed: 11\n" + SCHEME.to_csv())
    use_env_terrains(cfg, seeded)
    assert cfg.scene.terrain.seed is None and cfg.scene.terrain.oversample is None
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        terrain = env.cfg.scene.terrain
        assert (terrain.seed, terrain.oversample) == (11, rse.DEFAULT_ENV_OVERSAMPLE)
        said = record(terrain)
        assert (said["seed"], said["oversample"]) == (11, rse.DEFAULT_ENV_OVERSAMPLE)
        assert env_terrains(env).schemes[0].seed == 11
    finally:
        env.close()
