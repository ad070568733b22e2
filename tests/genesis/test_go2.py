"""examples/genesis_go2 inside Genesis 1.4.5 on the CPU (.venv-genesis, make
test-frameworks): Genesis's Go2 (from its wheel) on rse tiles. Each robot
stands on its own tile's tops; a reset renews the reset envs' tiles only,
in the built scene, and their robots stand on the new tops; the PPO
training script runs one rsl-rl iteration."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import genesis as gs
import numpy as np
import pytest
import rse
import rse.genesis
import torch

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "genesis_go2"
sys.path.insert(0, str(EXAMPLE))
from go2_stepfield import Go2Stepfield  # noqa: E402

# 2 m tiles (small fields build fast on the CPU): 2.5 cm steps under a hill.
SCHEME = "# size: 20x20\n# block_size: 0.1\n# step_height: 0.025\ntype,height,angle,x1,y1\nrandom,0..2,,,\npeak,2..5,30,5..15,5..15\n"
N_ENVS = 4
STAND_STEPS = 50  # 1 s at the task's 50 Hz


@pytest.fixture(scope="module")
def env():
    gs.init(backend=gs.cpu, precision="32", logging_level="warning", seed=1)
    tiles = rse.EnvTerrains(rse.Scheme.from_csv(SCHEME), N_ENVS, layout="tiles", border=2, seed=3, spawn_radius=0.3)
    yield Go2Stepfield(tiles)
    gs.destroy()


def resting_height(env: Go2Stepfield, e: int, centre: np.ndarray) -> float:
    """Where a foot (a sphere) over ``centre`` (x, y) rests on env ``e``'s
    ground as Genesis collides it (rse's samples, planar between them:
    ``get_terrain_height``): the highest of h(p) + sqrt(r² - |p - c|²) over
    the disc."""
    r = env.foot_radius
    offsets = np.stack(np.meshgrid(np.linspace(-r, r, 41), np.linspace(-r, r, 41)), -1).reshape(-1, 2)
    offsets = offsets[np.hypot(*offsets.T) <= r]
    points = torch.as_tensor(np.broadcast_to(centre + offsets, (N_ENVS, len(offsets), 2)).copy(), dtype=torch.float32)
    ground = env.terrain.get_terrain_height(points)[e].cpu().numpy().astype(np.float64)
    return float(np.max(ground + np.sqrt(r**2 - np.sum(offsets**2, axis=1))))


def stand(env: Go2Stepfield) -> np.ndarray:
    """Holds the standing pose for a second; returns which envs reset."""
    reset = torch.zeros(N_ENVS, dtype=torch.bool)
    for _ in range(STAND_STEPS):
        _, _, dones, _ = env.step(torch.zeros((N_ENVS, env.num_actions)))
        reset |= dones.cpu()
    return reset.numpy()


def assert_on_own_tops(env: Go2Stepfield, envs: list[int]) -> None:
    feet = env.feet_pos().cpu().numpy().astype(np.float64)
    half = env.tile_half_extent.cpu().numpy()
    origins = env.tiles.origins
    for e in envs:
        assert np.all(np.abs(feet[e, :, :2] - origins[e, :2]) < half), f"env {e}'s feet are on its own tile"
        want = [resting_height(env, e, foot[:2]) for foot in feet[e]]
        # 3 mm: Genesis's soft contact lets a 15 kg robot's feet sink a little.
        assert np.allclose(feet[e, :, 2], want, atol=3e-3), (e, feet[e, :, 2], want)
        # On rse's tops: within a step of the block under the foot (a foot
        # on a block's edge rests on Genesis's ramp between two samples).
        tops = env.tiles.heights_at([e], feet[e : e + 1, :, :2])[0]
        assert np.all(np.abs(feet[e, :, 2] - env.foot_radius - tops) <= env.tiles.terrain(e).step_height + 3e-3)


def test_each_go2_stands_on_its_own_tiles_tops(env) -> None:
    assert not stand(env).any(), "standing still ends no episode"
    assert_on_own_tops(env, list(range(N_ENVS)))
    feet = env.feet_pos().cpu().numpy()
    assert len(set(np.round(feet[:, :, 2].ravel(), 3))) > 2, "the feet stand on different tops"


def test_a_reset_renews_only_the_reset_envs_tiles_and_their_robots_stand_on_them(env) -> None:
    tiles = env.tiles
    before = [tiles.terrain(e).elevation.copy() for e in range(N_ENVS)]
    episodes = tiles.episode.copy()
    kept_base = env.robot.get_pos().cpu().numpy()
    mask = torch.tensor([True, False, True, False])
    env._reset_idx(mask)

    reset, kept = [0, 2], [1, 3]
    assert list(tiles.episode - episodes) == [1, 0, 1, 0]
    assert all(np.array_equal(tiles.terrain(e).elevation, before[e]) for e in kept)
    assert all(not np.array_equal(tiles.terrain(e).elevation, before[e]) for e in reset)
    field = env.scene.sim.rigid_solver.collider.collider_info.terrain_hf.to_numpy()
    assert np.array_equal(field, rse.genesis.heights(tiles)), "the built scene's field is the tiles' map"
    base = env.robot.get_pos().cpu().numpy()
    assert np.allclose(base[reset], tiles.origins[reset] + [0, 0, env.cfg.spawn_height], atol=1e-5)
    assert np.allclose(base[kept], kept_base[kept]), "the other robots were not moved"

    assert not stand(env).any()
    assert_on_own_tops(env, list(range(N_ENVS)))


def test_the_training_script_runs_one_ppo_iteration(tmp_path) -> None:
    scheme = tmp_path / "scheme.csv"
    scheme.write_text(SCHEME)
    logs = tmp_path / "logs"
    run = subprocess.run(
        [sys.executable, str(EXAMPLE / "train.py"), "--device", "cpu", "-B", "4", "--max_iterations", "1",
         "--scheme", str(scheme), "--log_dir", str(logs)],
        capture_output=True, text=True, timeout=1800,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-3000:]
    assert "Learning iteration" in run.stdout, run.stdout[-2000:]
    assert sorted(p.name for p in logs.glob("model_*.pt")), "the runner saved its policy"
    assert list(logs.glob("events.out.tfevents.*")), "the runner logged to tensorboard"
