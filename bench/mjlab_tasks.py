"""mjlab's Go1 rough velocity task on mjlab's own terrain and on rse's
per-env stepfields (a new terrain every episode), same envs, same run: env
steps per second, the time of one PPO iteration of mjlab's runner, and the
height scan from rays (mjlab's ``height_scan``) beside rse's exact one
(``exact_height_scan``), per step. The aim: rse's overhead at most 5 % of a
step.

Episodes are cut short (``--episode-s``) so that resets, where rse writes
new terrains, happen as often as in a long training run's worst case.

Usage (make bench-frameworks, in .venv-frameworks):
    python bench/mjlab_tasks.py [--num-envs 16] [--steps 60] [--device cpu]
    python bench/mjlab_tasks.py --device cuda --num-envs 4096   # on a GPU
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import torch

REPO = Path(__file__).resolve().parent.parent


def make(task: str, num_envs: int, device: str, episode_s: float, rse: bool):
    import mjlab.tasks  # noqa: F401
    from mjlab.envs import ManagerBasedRlEnv
    from mjlab.tasks.registry import load_env_cfg

    from rse.mjlab import use_env_terrains
    from rse.mjlab_tasks import STEPFIELD

    cfg = load_env_cfg(task)
    cfg.scene.num_envs = num_envs
    cfg.episode_length_s = episode_s
    if rse:
        import rse as rse_pkg

        use_env_terrains(cfg, rse_pkg.Scheme.from_csv(STEPFIELD))
    env = ManagerBasedRlEnv(cfg, device=device)
    env.reset()
    return env


def steps_per_second(env, steps: int) -> float:
    action = torch.zeros(env.action_space.shape, device=env.device)
    for _ in range(3):
        env.step(action)
    start = time.perf_counter()
    for _ in range(steps):
        env.step(action)
    return steps * env.num_envs / (time.perf_counter() - start)


def scan_cost(env, repeats: int) -> tuple[float, float]:
    """Seconds per call of mjlab's ray height scan (reading the sensor the
    step already cast: the rays' cost is in the step) and of rse's exact
    scan."""
    from mjlab.envs import mdp as envs_mdp

    from rse.mjlab import exact_height_scan

    def timed(f) -> float:
        start = time.perf_counter()
        for _ in range(repeats):
            f(env, "terrain_scan")
        return (time.perf_counter() - start) / repeats

    return timed(envs_mdp.height_scan), timed(exact_height_scan)


def ppo_iteration(task: str, env) -> float:
    from dataclasses import asdict

    from mjlab.rl import RslRlVecEnvWrapper
    from mjlab.tasks.registry import load_rl_cfg, load_runner_cls

    import tempfile

    agent = load_rl_cfg(task)
    agent.num_steps_per_env = 24
    agent.logger = "tensorboard"
    runner_cls = load_runner_cls(task)
    wrapped = RslRlVecEnvWrapper(env, clip_actions=agent.clip_actions)
    with tempfile.TemporaryDirectory() as logs:
        runner = runner_cls(wrapped, asdict(agent), logs, str(env.device))
        runner.learn(num_learning_iterations=1, init_at_random_ep_len=True)
        start = time.perf_counter()
        runner.learn(num_learning_iterations=1)
        return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="Mjlab-Velocity-Rough-Unitree-Go1")
    parser.add_argument("--num-envs", type=int, default=16)
    parser.add_argument("--steps", type=int, default=60)
    parser.add_argument("--episode-s", type=float, default=1.0, help="episode length: resets every so many seconds")
    parser.add_argument("--device", default="cpu")
    args = parser.parse_args()

    rows = []
    for label, rse in (("mjlab's terrain", False), ("rse, new terrain per episode", True)):
        env = make(args.task, args.num_envs, args.device, args.episode_s, rse)
        sps = steps_per_second(env, args.steps)
        rays, exact = scan_cost(env, 20) if rse else (float("nan"), float("nan"))
        ppo = ppo_iteration(args.task, env)
        rows.append((label, sps, ppo, rays, exact))
        env.close()
    print(f"{args.task}, {args.num_envs} envs on {args.device}, episodes of {args.episode_s} s, {args.steps} steps")
    print(f"{'terrain':32} {'env steps/s':>12} {'PPO iteration s':>16}")
    for label, sps, ppo, _, _ in rows:
        print(f"{label:32} {sps:12.1f} {ppo:16.2f}")
    base, ours = rows[0][1], rows[1][1]
    print(f"rse's overhead per step: {100 * (base / ours - 1):+.1f} % (aim: at most 5 %)")
    _, _, _, rays, exact = rows[1]
    print(f"height scan per step: rays (read) {1e3 * rays:.3f} ms, rse exact {1e3 * exact:.3f} ms")


if __name__ == "__main__":
    main()
