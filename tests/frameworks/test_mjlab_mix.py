"""A mix of schemes in mjlab's rough task, as mjlab mixes sub-terrains by
proportion: each env draws its scheme from the proportions by its global
env id and seed, keeps it for the run, and the curriculum is logged per
scheme; set in Python (``use_env_terrains(cfg, {path: proportion})``) or
from ``train``'s command line (``--env.scene.terrain.schemes``), which
records every scheme in the run folder."""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import mjlab.tasks  # noqa: F401  (registers the tasks)
import numpy as np
import rse
from mjlab.envs import ManagerBasedRlEnv
from mjlab.tasks.registry import load_env_cfg
from mjlab_cli import train_main
from rse.mjlab import contact_sheet, env_terrains, terrain_difficulty, use_env_terrains

REPO = Path(__file__).resolve().parents[2]
STAIRS, WALLS = REPO / "schemes" / "mix_stairs.csv", REPO / "schemes" / "mix_walls.csv"
FLIGHTS, ROUGH = REPO / "schemes" / "mix_flights.csv", REPO / "schemes" / "mix_rough.csv"
RAMPS, NIST = REPO / "schemes" / "mix_ramps.csv", REPO / "schemes" / "nist_flat.csv"


def test_each_env_draws_its_scheme_by_proportion_and_the_curriculum_is_logged_per_scheme() -> None:
    cfg = load_env_cfg("Mjlab-Velocity-Rough-Unitree-Go1")
    cfg.scene.num_envs = 8
    use_env_terrains(cfg, {str(STAIRS): 3.0, str(WALLS): 1.0}, seed=4, difficulty=0.5)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        envs = env_terrains(env)
        drawn = rse.scheme_mix([3.0, 1.0], 8, seed=4)
        np.testing.assert_array_equal(envs.scheme_ids, drawn)
        assert set(drawn) == {0, 1}, "both schemes among the 8 envs of seed 4"
        want = rse.EnvTerrains([rse.Scheme.load(STAIRS), rse.Scheme.load(WALLS)], 8, seed=4, difficulty=0.5, proportions=[3, 1])
        for e in range(8):
            np.testing.assert_array_equal(envs.terrain(e).heights, want.terrain(e).heights)
        logged = terrain_difficulty(env, None)
        assert set(logged) == {"mean", "max", "mix_stairs", "mix_walls"}
        assert logged["mix_stairs"] == 0.5
        # The sheet names each tile's scheme.
        assert contact_sheet(env) == envs.contact_sheet(names=["mix_stairs", "mix_walls"])
    finally:
        env.close()


def test_a_mix_from_trains_command_line_runs_logs_per_scheme_and_records_every_scheme(tmp_path) -> None:
    """The usual mix — straight and pyramid stairs of 5 cm steps, ramps
    (inclined planes), rough ground, and a NIST stepfield of 10 cm steps
    on framed pallets (another step height and grid in one mix) — trains
    from ``train``'s command line; the run records every scheme."""
    mix = ((FLIGHTS, 2.0), (RAMPS, 1.0), (ROUGH, 1.0), (NIST, 1.0))
    train = Path(sys.executable).parent / "train"
    done = subprocess.run(
        [str(train), "Rse-Velocity-Rough-Unitree-Go1", "--env.scene.num-envs", "6", "--env.episode-length-s", "0.1",
         # mjlab's tyro reads collections in Python's syntax.
         "--env.scene.terrain.schemes", "{" + ", ".join(f'"{p}": {w}' for p, w in mix) + "}", "--env.scene.terrain.seed", "2",
         "--agent.max-iterations", "1", "--agent.num-steps-per-env", "12", "--agent.logger", "tensorboard"],
        cwd=tmp_path, capture_output=True, text=True, timeout=1200,
        env={**os.environ, "CUDA_VISIBLE_DEVICES": ""},
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert list(rse.scheme_mix([2, 1, 1, 1], 6, seed=2)) == [3, 2, 2, 0, 0, 1], "every scheme among the 6 envs"
    for name in ("mix_flights", "mix_ramps", "mix_rough", "nist_flat"):
        assert f"Curriculum/rse_terrain_difficulty/{name}" in done.stdout, done.stdout[-3000:]
    params = next(tmp_path.glob("logs/rsl_rl/rse_go1_velocity/*/params"))
    for path, _ in mix:
        assert (params / "rse_schemes" / path.name).read_bytes() == path.read_bytes()
    record = json.loads((params / "rse_terrain.json").read_text())
    assert record["schemes"] == {
        p.stem: {"file": str(p), "sha256": hashlib.sha256(p.read_bytes()).hexdigest(), "proportion": w} for p, w in mix
    }
    assert record["seed"] == 2 and not (params / "rse_scheme.csv").exists()
    # Evaluated on the same mix, found in the run.
    checkpoint = next(params.parent.glob("model_*.pt"))
    done = subprocess.run(
        [sys.executable, "-m", "rse.mjlab_eval", str(checkpoint), "--levels", "2", "--per-level", "2", "--seconds", "0.2"],
        cwd=tmp_path, capture_output=True, text=True, timeout=1200, env={**os.environ, "CUDA_VISIBLE_DEVICES": ""},
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert "scheme from the run folder: a mix of" in done.stderr and "mix_flights.csv (2)" in done.stderr, done.stderr[-2000:]


def test_a_mix_of_other_block_sizes_or_a_bad_proportion_is_refused_at_the_flag(tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("COLUMNS", "300")
    other = tmp_path / "coarse.csv"
    other.write_text("# size: 40x40\n# block_size: 0.2\ntype,height\nrandom,2\n")
    for mix, words in ((f'{{"{STAIRS}": 1, "{other}": 1}}', "scheme 2 has block_size 0.2 m"),
                       (f'{{"{STAIRS}": -1}}', "proportion is -1"),
                       (f'{{"{STAIRS}": 1, "missing.csv": 1}}', "missing.csv: cannot read it")):
        done = train_main(capsys, "--env.scene.terrain.schemes", mix)
        text = " ".join((done.stdout + done.stderr).replace("│", " ").split())
        assert done.returncode == 2 and "Traceback" not in text, text[-2000:]
        assert "--env.scene.terrain.schemes" in text and words in text, text[-2000:]
        assert "Base Environment" not in text and not (tmp_path / "logs").exists()


def test_play_of_a_checkpoint_shows_the_scheme_and_seed_its_run_recorded(tmp_path, capsys, monkeypatch) -> None:
    """mjlab's ``play`` takes no terrain flags; its command line names the
    checkpoint (``--checkpoint-file``): rse finds the run's record beside
    it and plays on what the run trained on. Outside ``play`` the same
    command line changes nothing."""
    import dataclasses

    import mjlab.scripts.play  # noqa: F401  (this process is mjlab's play)
    from rse._adapters.mjlab import run_record

    mine = tmp_path / "mine.csv"
    mine.write_text("# size: 30x20\ntype,height\nrandom,3\n")
    run = tmp_path / "logs" / "run"
    cfg = load_env_cfg("Rse-Velocity-Rough-Unitree-Go1", play=True)
    run_record.write(run, dataclasses.replace(cfg.scene.terrain, scheme=str(mine), seed=7))
    cfg.scene.num_envs = 2
    argv = ["play", "Rse-Velocity-Rough-Unitree-Go1", "--num-envs", "2", "--checkpoint-file", str(run / "model_3.pt")]
    monkeypatch.setattr(sys, "argv", argv)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        envs = env_terrains(env)
        want = rse.EnvTerrains(rse.Scheme.load(mine), 1, seed=7)
        assert envs.terrain(0).heights.shape == (20, 30)
        assert envs.terrain(0).seed == 7 and want.terrain(0).seed == 7
    finally:
        env.close()
    assert f"playing on what the run trained on: {run / 'params' / 'rse_scheme.csv'} (seed 7)" in capsys.readouterr().out

    from rse._adapters.mjlab.spec_fn import plays_checkpoint

    assert plays_checkpoint(["play", "T", f"--checkpoint_file={run}/model_9.pt"]) == f"{run}/model_9.pt"
    assert plays_checkpoint(["play", "T", "--wandb-run-path", "a/b/c"]) is None
    monkeypatch.delitem(sys.modules, "mjlab.scripts.play")
    assert plays_checkpoint(argv) is None, "not play: its flags mean nothing"


def test_a_mix_of_grids_runs_every_slot_the_largest_and_the_exact_tops_agree_on_the_device() -> None:
    """A 4 m stepfield beside the 8 m flights: every env's slot is 8 m, the
    smaller terrain in its corner with ground around it; the exact tops a
    GPU reads from the fields (a kernel) are the host's, off the smaller
    terrain too (0, the ground plane), and the Go1s step on it."""
    import torch
    from host_copies import as_a_gpu_runs_them
    from rse._adapters.mjlab.reset_event import event_of

    small = rse.Scheme.from_csv("# size: 40x40\n# step_height: 0.05\ntype,height\nrandom,1..2\n")
    cfg = load_env_cfg("Mjlab-Velocity-Rough-Unitree-Go1")
    cfg.scene.num_envs = 6
    use_env_terrains(cfg, {str(FLIGHTS): 1.0, small.to_csv(): 1.0}, seed=2, difficulty=1.0)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        envs = env_terrains(env)
        assert set(envs.scheme_ids) == {0, 1} and envs.field_shape == (160, 160)
        env.reset()
        for _ in range(5):
            env.step(torch.zeros(env.action_space.shape))
        tops = event_of(env, "rse_terrain").exact_tops()
        xy = torch.rand((6, 50, 2), generator=torch.Generator().manual_seed(0), dtype=torch.float64) * 8.0
        on_host = tops.tops(xy)
        with as_a_gpu_runs_them(tops):
            on_device = tops.tops(xy)
        assert torch.allclose(on_host, on_device, atol=1e-6)
        smaller = [e for e in range(6) if envs.scheme_ids[e] == 1]
        assert (on_device[smaller][xy[smaller].amax(dim=-1) > 4.05] == 0).all(), "the ground around a smaller terrain"
        assert torch.isfinite(env.scene["robot"].data.root_link_pos_w).all()
    finally:
        env.close()
