"""mjlab's Go1 rough velocity task on mjlab's own terrain and on rse's
per-env stepfields (a new terrain every episode), same envs, same run: env
steps per second, what the contact solver is given and does (terrain
contacts per loaded foot, constraint rows and solver iterations per world,
broadphase pairs, penetration), the time of one PPO iteration of mjlab's
runner, and the height scan from rays (mjlab's ``height_scan``) beside
rse's exact one (``exact_height_scan``), per step. The aim: rse's overhead
at most 5 % of a step.

Episodes are cut short (``--episode-s``) so that resets, where rse writes
new terrains, happen as often as in a long training run's worst case.

Usage (make bench-frameworks, in .venv-frameworks):
    python bench/mjlab_tasks.py [--num-envs 32] [--steps 30] [--rounds 7] [--device cpu]
    python bench/mjlab_tasks.py --device cuda --num-envs 4096   # on a GPU
"""

from __future__ import annotations

import argparse
import statistics
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
    start = time.perf_counter()
    for _ in range(steps):
        env.step(action)
    return steps * env.num_envs / (time.perf_counter() - start)


def solver_load(env, steps: int) -> dict[str, float]:
    """What MuJoCo Warp's contact solver is given and does over ``steps``
    env steps (standing robots, zero actions, as timed), per world after
    each step's last physics step: terrain contacts per foot that touches
    the terrain, constraint rows (``nefc``), solver iterations, broadphase
    pairs, the 99th percentile of terrain penetration (mm), and the steps
    with any overflow."""
    import mujoco
    import numpy as np

    m = env.sim.mj_model
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, g) or "" for g in range(m.ngeom)]
    feet = np.array(["foot" in n and "collision" in n for n in names])
    terrain = m.geom_bodyid == mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "terrain")
    d = env.sim.wp_data
    action = torch.zeros(env.action_space.shape, device=env.device)
    per_foot, nefc, niter, pairs, depths, overflows = [], [], [], [], [], 0
    for _ in range(steps):
        env.step(action)
        n = int(d.nacon.numpy()[0])
        geom, world, dist = d.contact.geom.numpy()[:n], d.contact.worldid.numpy()[:n], d.contact.dist.numpy()[:n]
        on_terrain = terrain[geom[:, 0]] | terrain[geom[:, 1]]
        foot = on_terrain & (feet[geom[:, 0]] | feet[geom[:, 1]])
        key = world[foot] * m.ngeom + np.where(feet[geom[foot, 0]], geom[foot, 0], geom[foot, 1])
        per_foot.extend(np.unique(key, return_counts=True)[1].tolist())
        depths.extend((-dist[on_terrain]).clip(0, None).tolist())
        nefc.append(float(d.nefc.numpy().mean()))
        niter.append(float(d.solver_niter.numpy().mean()))
        pairs.append(float(d.ncollision.numpy()[0]) / env.num_envs)
        overflows += int((d.overflow.numpy() != 0).any())
    return {
        "contacts/foot": float(np.mean(per_foot)) if per_foot else 0.0,
        "rows": float(np.mean(nefc)),
        "iterations": float(np.mean(niter)),
        "pairs": float(np.mean(pairs)),
        "p99 mm": 1e3 * float(np.percentile(depths, 99)) if depths else 0.0,
        "overflows": float(overflows),
    }


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
    parser.add_argument("--num-envs", type=int, default=32)
    parser.add_argument("--steps", type=int, default=30, help="steps per round")
    parser.add_argument("--rounds", type=int, default=7, help="alternating rounds of each terrain")
    parser.add_argument("--episode-s", type=float, default=1.0, help="episode length: resets every so many seconds")
    parser.add_argument("--device", default="cpu")
    args = parser.parse_args()

    # Both envs live side by side and are measured in alternating rounds:
    # on a small machine one long run of each is at the mercy of whatever
    # else runs (single runs of a second differed by 40 %).
    envs = {rse: make(args.task, args.num_envs, args.device, args.episode_s, rse) for rse in (False, True)}
    for env in envs.values():
        steps_per_second(env, 5)
    rates: dict[bool, list[float]] = {False: [], True: []}
    for _ in range(args.rounds):
        for rse, env in envs.items():
            rates[rse].append(steps_per_second(env, args.steps))
    load = {rse: solver_load(env, 10) for rse, env in envs.items()}
    rays, exact = scan_cost(envs[True], 20)
    # One runner per env (a second runner on an env the first used meets
    # its inference-mode tensors): a warm-up iteration, then one timed.
    ppo = {rse: [ppo_iteration(args.task, env)] for rse, env in envs.items()}
    rows = [
        (label, statistics.median(rates[rse]), min(rates[rse]), max(rates[rse]), statistics.median(ppo[rse]), load[rse])
        for label, rse in (("mjlab's terrain", False), ("rse, new terrain per episode", True))
    ]
    for env in envs.values():
        env.close()
    print(
        f"{args.task}, {args.num_envs} envs on {args.device}, episodes of {args.episode_s} s, "
        f"{args.rounds} alternating rounds of {args.steps} steps"
    )
    print(f"{'terrain':32} {'env steps/s (median, min-max)':>30} {'PPO iteration s':>16}")
    for label, median, low, high, ppo_s, _ in rows:
        print(f"{label:32} {median:12.1f} ({low:6.1f}-{high:6.1f}) {ppo_s:16.2f}")
    base, ours = rows[0][1], rows[1][1]
    print(f"rse/mjlab time per step (medians): {base / ours:.3f}, rse's overhead {100 * (base / ours - 1):+.1f} % (aim: at most 5 %)")
    print(f"what the contact solver is given and does, per world (10 steps standing; nconmax {envs[True].sim.cfg.nconmax} on rse):")
    print(f"{'terrain':32} {'contacts/foot':>13} {'rows':>6} {'iterations':>10} {'pairs':>6} {'p99 mm':>7} {'overflows':>9}")
    for label, *_, stats in rows:
        print(
            f"{label:32} {stats['contacts/foot']:13.2f} {stats['rows']:6.1f} {stats['iterations']:10.2f} "
            f"{stats['pairs']:6.1f} {stats['p99 mm']:7.1f} {stats['overflows']:9.0f}"
        )
    print(f"height scan per step: rays (read) {1e3 * rays:.3f} ms, rse exact {1e3 * exact:.3f} ms")


if __name__ == "__main__":
    main()
