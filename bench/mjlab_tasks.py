"""mjlab's Go1 rough velocity task on mjlab's own terrain and on rse's
per-env stepfields (a new terrain every episode), same envs, same run: env
steps per second, each part's share of a step for both terrains (physics,
of it the collision pipeline, the ray sensors, the managers' terms, the
resets at the episodes' rate), what the contact solver is given and does
(terrain contacts per loaded foot, constraint rows and solver iterations
per world, broadphase pairs, penetration), the time of one PPO iteration
of mjlab's runner, the height scan from rays (mjlab's ``height_scan``)
beside rse's exact one (``exact_height_scan``), and the proxies a CPU
checks for a GPU (docs/train.md): terrain bytes per env on the device
(counted from the arrays, the estimate the ``[INFO]`` line prints, and on
a GPU what Warp's allocator holds for each env beside mjlab's), a reset's
host time and bytes uploaded per env, host copies in rse's step terms.
The aim: rse's overhead at most 5 % of a step.

Episodes are cut short (``--episode-s``) so that resets, where rse writes
new terrains, happen as often as in a long training run's worst case.

Usage (make bench-frameworks, in .venv-frameworks):
    python bench/mjlab_tasks.py [--num-envs 32] [--steps 30] [--rounds 7] [--device cpu]
    python bench/mjlab_tasks.py --device cuda --num-envs 4096   # on a GPU
    python bench/mjlab_tasks.py --schemes schemes/mix_flights.csv=2 schemes/mix_ramps.csv=1 ...   # a mix
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import torch

REPO = Path(__file__).resolve().parent.parent


SCHEMES: dict[str, float] = {}
"""``--schemes``: a mix's files and proportions; empty: the task's stepfield."""


def rse_schemes():
    """What rse's task runs on: the ``--schemes`` mix, or the stepfield."""
    import rse as rse_pkg
    from rse.mjlab_tasks import STEPFIELD

    return dict(SCHEMES) if SCHEMES else rse_pkg.Scheme.from_csv(STEPFIELD)


def probe():
    """One env of rse's terrains (its slot's size, whatever the envs)."""
    import rse as rse_pkg

    if not SCHEMES:
        from rse._adapters.mjlab.terrains import probe_envs

        return probe_envs(rse_schemes(), None)
    schemes = [rse_pkg.Scheme.load(path) for path in SCHEMES]
    return rse_pkg.EnvTerrains(schemes, 1, proportions=list(SCHEMES.values()))


def make(task: str, num_envs: int, device: str, episode_s: float, rse: bool):
    import mjlab.tasks  # noqa: F401
    from mjlab.envs import ManagerBasedRlEnv
    from mjlab.tasks.registry import load_env_cfg
    from rse.mjlab import use_env_terrains

    cfg = load_env_cfg(task)
    cfg.scene.num_envs = num_envs
    cfg.episode_length_s = episode_s
    if rse:
        use_env_terrains(cfg, rse_schemes())
    env = ManagerBasedRlEnv(cfg, device=device)
    env.reset()
    return env


def steps_per_second(env, steps: int) -> float:
    action = torch.zeros(env.action_space.shape, device=env.device)
    sync(env)
    start = time.perf_counter()
    for _ in range(steps):
        env.step(action)
    sync(env)
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

    return (
        timed(env, lambda: envs_mdp.height_scan(env, "terrain_scan"), repeats),
        timed(env, lambda: exact_height_scan(env, "terrain_scan"), repeats),
    )


def sync(env) -> None:
    import warp as wp

    wp.synchronize_device(env.sim.wp_device)
    if str(env.device).startswith("cuda"):
        torch.cuda.synchronize()


def timed(env, f, repeats: int) -> float:
    """Seconds per call of ``f``, the device drained before and after."""
    sync(env)
    start = time.perf_counter()
    for _ in range(repeats):
        f()
    sync(env)
    return (time.perf_counter() - start) / repeats


def step_parts(env, episode_s: float, repeats: int) -> dict[str, float]:
    """Milliseconds per env step of each part of one: physics (the
    decimation's ``sim.step``s), of it the collision pipeline (MuJoCo
    Warp's ``collision``: broadphase and narrowphase, captured in a graph
    on a GPU as mjlab captures the step), the sensors (``sim.sense``: ray
    casting), the managers' terms (observations, rewards, terminations),
    and the resets at the episodes' rate (``reset_part``: what a step does
    for the envs it resets, on average: rse's new terrains among them),
    and the step events (rse's ``bound_near_robots``; mjlab's task has
    none)."""
    import mujoco_warp as mjw
    import warp as wp

    sim, decimation = env.sim, env.cfg.decimation
    collision = lambda: mjw.collision(sim.wp_model, sim.wp_data)  # noqa: E731
    if sim.wp_device.is_cuda:
        with wp.ScopedDevice(sim.wp_device), wp.ScopedCapture() as capture:
            collision()
        graph = capture.graph
        collision = lambda: wp.capture_launch(graph)  # noqa: E731
    per_step = max(1, round(env.num_envs * env.step_dt / episode_s))
    ids = torch.arange(per_step, device=env.device)
    step_events = lambda: env.event_manager.apply(mode="step", dt=env.step_dt)  # noqa: E731
    return {
        "physics": 1e3 * decimation * timed(env, sim.step, repeats),
        "of it collision": 1e3 * decimation * timed(env, collision, repeats),
        "sensors": 1e3 * timed(env, sim.sense, repeats),
        "terms": 1e3
        * timed(env, lambda: (env.observation_manager.compute(), env.reward_manager.compute(dt=env.step_dt), env.termination_manager.compute()), repeats),
        "resets": 1e3 * timed(env, lambda: reset_part(env, ids), max(1, repeats // 2)),
        "step events": 1e3 * timed(env, step_events, repeats) if "step" in env.event_manager.available_modes else 0.0,
    }


def reset_part(env, ids) -> None:
    """What ``env.step`` does for the envs ``ids`` it resets (mjlab's
    ``_reset_idx``, then the state written to the simulation): the
    forward pass and the sensors that follow run for every env in any
    step, so they are the physics' and the sensors' parts. (Until
    2026-11-29 this part was ``env.reset(env_ids=ids)``, which also runs
    a forward pass, every sensor and the observations: the H200 run's
    resets counted the sensors a second time.)"""
    env.extras["log"] = {}
    env._reset_idx(ids)
    env.scene.write_data_to_sim()


def proxies(env, episode_s: float) -> dict[str, float]:
    """The CPU-checkable proxies of rse's env: terrain bytes per env on
    the device (from the arrays), the reset event's host time per env
    (generation, then the upload) and bytes uploaded per env, the host
    copies rse's step terms make and the kernels each launches from Python
    (``launches: <term>``; on a GPU each is a gap outside mjlab's captured
    graphs)."""
    import sys

    from rse._adapters.mjlab.reset_event import event_of
    from rse._adapters.mjlab.step_terms import bound_near_robots
    from rse.mjlab import exact_height_scan, out_of_slot

    sys.path.insert(0, str(REPO / "tests" / "frameworks"))
    from host_copies import HostCopies, as_a_gpu_runs_them
    from launches import Launches

    event = event_of(env, "rse_terrain")
    parts = event.device_bytes()
    n = max(1, round(env.num_envs * env.step_dt / episode_s))
    ids = list(range(n))
    generate = timed(env, lambda: event.envs.reset(ids), 5) / n
    upload = timed(env, lambda: event._copy_out(ids), 5) / n
    cells = parts["fields"] + parts["coarse fields"]
    terms = {
        "exact_height_scan": lambda: exact_height_scan(env, "terrain_scan"),
        "out_of_slot": lambda: out_of_slot(env),
        "bound_near_robots": lambda: bound_near_robots(env),
    }
    launched = {}
    with as_a_gpu_runs_them(event.exact_tops()):
        with HostCopies() as copies:
            for term in terms.values():
                term()
        for name, term in terms.items():
            with Launches() as launches:
                term()
            launched[name] = len(launches.found)
    # What the allocator gave the arrays that hold them: the model's
    # height fields (the Go1 scene has none but rse's) and the per-world
    # routing and bounds, less the one row each had before rse expanded it.
    m = env.sim.wp_model
    geoms = int(m.geom_dataid.shape[1])
    held = int(m.hfield_data.capacity) + int(m.geom_dataid.capacity) + int(m.geom_aabb.capacity) - geoms * (4 + 24)
    staging = parts.pop("upload staging")
    return {
        "device bytes/env": sum(parts.values()) / env.num_envs,
        "allocated bytes/env": held / env.num_envs,
        # A fixed few MiB whatever the envs (none on the CPU device).
        "upload staging bytes": float(staging),
        "reset generate us/env": 1e6 * generate,
        "reset upload us/env": 1e6 * upload,
        # The samples, each field's start (4 bytes), its box (24) and the
        # origin (12).
        "uploaded bytes/env": cells / env.num_envs + 2 * (4 + 24) + 12,
        "host copies in step terms": float(len(copies.found)),
        **{f"launches: {name}": float(n) for name, n in launched.items()},
    }


def allocated(device: str) -> int:
    """Bytes Warp's allocator holds on ``device`` (0 on the CPU)."""
    import warp as wp

    if not device.startswith("cuda"):
        return 0
    return int(wp.get_mempool_used_mem_current(device))


def warp_arrays(env) -> int:
    """Bytes of every Warp array of ``env``'s simulation (the device model
    and data, their nested structs too, each array once): on the CPU,
    where Warp has no allocator to ask, what it would hold on a GPU."""
    import warp as wp

    seen: set[int] = set()

    def held(value, depth: int = 0) -> int:
        if isinstance(value, wp.array):
            if value.ptr is None or value.ptr in seen:
                return 0
            seen.add(value.ptr)
            return int(value.capacity)
        if depth > 2 or not hasattr(value, "__dict__"):
            return 0
        return sum(held(v, depth + 1) for v in vars(value).values())

    return held(env.sim.wp_model) + held(env.sim.wp_data)


def ppo_iteration(task: str, env) -> float:
    import tempfile
    from dataclasses import asdict

    from mjlab.rl import RslRlVecEnvWrapper
    from mjlab.tasks.registry import load_rl_cfg, load_runner_cls

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


def device_used(device: str) -> int:
    """Bytes in use on the whole device (every allocator, the CUDA
    context), as ``cudaMemGetInfo`` tells them: what a card must have. On
    the CPU the process's peak resident memory."""
    if not device.startswith("cuda"):
        import resource

        return 1024 * resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    free, total = torch.cuda.mem_get_info(torch.device(device))
    return total - free


def memory_only(args) -> None:
    """Builds each terrain's task alone, each in a process of its own (a
    device's memory is not handed back within one), at ``--num-envs``,
    steps it through resets and reports what Warp's and torch's
    allocators hold and what the whole device has in use (on the CPU: the
    process's peak resident memory); then what rse's task takes beside
    mjlab's own (does it fit a 24 GB card?)."""
    import json
    import subprocess
    import sys

    if args.terrain is not None:
        print("MEMORY " + json.dumps(memory_of(args, args.terrain == "rse")), flush=True)
        return
    held = {}
    for terrain in ("mjlab", "rse"):
        run = subprocess.run([sys.executable, __file__, *sys.argv[1:], "--terrain", terrain], check=True, stdout=subprocess.PIPE, text=True)
        line = [x for x in run.stdout.splitlines() if x.startswith("MEMORY ")][-1]
        held[terrain] = m = json.loads(line[len("MEMORY ") :])
        print(
            f"{terrain}'s task alone, {args.num_envs} envs on {args.device} after {m['steps']} steps (every env reset): "
            f"Warp's allocator {m['warp'] / 2**30:.2f} GiB ({m['warp'] / args.num_envs / 1024:.1f} KiB an env), "
            f"torch's {m['torch max'] / 2**30:.2f} GiB at most ({m['torch reserved'] / 2**30:.2f} GiB reserved), "
            f"the device {m['used'] / 2**30:.2f} GiB in use ({m['added'] / 2**30:.2f} GiB more than before the build)",
            flush=True,
        )
    more = held["rse"]["used"] - held["mjlab"]["used"]
    warp = held["rse"]["warp"] - held["mjlab"]["warp"]
    print(
        f"rse's task beside mjlab's: the device {more / 2**30:+.2f} GiB in use ({more / args.num_envs / 1024:+.1f} KiB an env), "
        f"Warp's allocator {warp / 2**30:+.2f} GiB ({warp / args.num_envs / 1024:+.1f} KiB an env)",
        flush=True,
    )


def memory_of(args, rse: bool) -> dict[str, float]:
    """One terrain's task built and stepped through resets: bytes held by
    Warp's allocator, by torch's (at most, and reserved), and in use on the
    whole device (and more than before the build)."""
    cuda = args.device.startswith("cuda")
    before, used_before = allocated(args.device), device_used(args.device)
    env = make(args.task, args.num_envs, args.device, args.episode_s[0], rse)
    steps = 2 * round(args.episode_s[0] / env.step_dt)
    steps_per_second(env, steps)
    used = device_used(args.device)
    return {
        "steps": steps,
        "warp": allocated(args.device) - before if cuda else warp_arrays(env),
        "torch max": torch.cuda.max_memory_allocated(args.device) if cuda else 0,
        "torch reserved": torch.cuda.memory_reserved(args.device) if cuda else 0,
        "used": used,
        "added": used - used_before,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="Mjlab-Velocity-Rough-Unitree-Go1")
    parser.add_argument("--num-envs", type=int, default=32)
    parser.add_argument("--steps", type=int, default=30, help="steps per round")
    parser.add_argument("--rounds", type=int, default=7, help="alternating rounds of each terrain")
    parser.add_argument(
        "--episode-s",
        type=float,
        nargs="+",
        default=[1.0],
        help="episode lengths, each measured in turn on the same envs (a GPU builds them once): resets every so many seconds",
    )
    parser.add_argument("--device", default="cpu")
    parser.add_argument(
        "--schemes",
        nargs="+",
        default=[],
        metavar="FILE=PROPORTION",
        help="rse's task on a mix of these scheme files (default: the task's stepfield)",
    )
    parser.add_argument(
        "--memory-only", action="store_true", help="build each terrain's task alone (a process each) and report the device memory it holds"
    )
    parser.add_argument("--terrain", choices=("mjlab", "rse"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    for item in args.schemes:
        path, _, weight = item.partition("=")
        SCHEMES[str(Path(path).resolve())] = float(weight or 1.0)
    if args.memory_only:
        memory_only(args)
        return

    # Both envs live side by side and are measured in alternating rounds:
    # on a small machine one long run of each is at the mercy of whatever
    # else runs (single runs of a second differed by 40 %).
    envs, held = {}, {}
    for rse in (False, True):
        before = allocated(args.device)
        start = time.perf_counter()
        envs[rse] = make(args.task, args.num_envs, args.device, args.episode_s[0], rse)
        held[rse] = allocated(args.device) - before
        print(f"{'rse' if rse else 'mjlab'}'s env built in {time.perf_counter() - start:.1f} s", flush=True)
    labels = (("mjlab's terrain", False), ("rse, new terrain per episode", True))
    print(f"{args.task}, {args.num_envs} envs on {args.device}, {args.rounds} alternating rounds of {args.steps} steps", flush=True)
    # At the task's starting levels, before the rounds' short episodes let
    # the curriculum lower the standing robots' terrains.
    # The robots land in the first steps after a reset: 10 to settle.
    for env in envs.values():
        steps_per_second(env, 10)
    load = {rse: solver_load(env, 20) for rse, env in envs.items()}
    print(f"what the contact solver is given and does, per world (steps 10-30 standing from the start; nconmax {envs[True].sim.cfg.nconmax} on rse):")
    print(f"{'terrain':32} {'contacts/foot':>13} {'rows':>6} {'iterations':>10} {'pairs':>6} {'p99 mm':>7} {'overflows':>9}")
    for label, rse in labels:
        stats = load[rse]
        print(
            f"{label:32} {stats['contacts/foot']:13.2f} {stats['rows']:6.1f} {stats['iterations']:10.2f} "
            f"{stats['pairs']:6.1f} {stats['p99 mm']:7.1f} {stats['overflows']:9.0f}",
            flush=True,
        )
    for episode_s in args.episode_s:
        # The managers read the episode's length from the config at each
        # step: envs past a shorter one end at the next step.
        for env in envs.values():
            env.cfg.episode_length_s = episode_s
        rates: dict[bool, list[float]] = {False: [], True: []}
        for _ in range(args.rounds):
            for rse, env in envs.items():
                rates[rse].append(steps_per_second(env, args.steps))
        print(f"episodes of {episode_s} s:")
        print(f"{'terrain':32} {'env steps/s (median, min-max)':>30}")
        for label, rse in labels:
            print(f"{label:32} {statistics.median(rates[rse]):12.1f} ({min(rates[rse]):6.1f}-{max(rates[rse]):6.1f})")
        base, ours = statistics.median(rates[False]), statistics.median(rates[True])
        print(f"rse/mjlab time per step (medians): {base / ours:.3f}, rse's overhead {100 * (base / ours - 1):+.1f} % (aim: at most 5 %)", flush=True)
        shares = {rse: step_parts(env, episode_s, 10) for rse, env in envs.items()}
        print("each part of a step, ms per env step (share of the parts' sum):")
        names = list(shares[False])
        print(f"{'terrain':32} " + " ".join(f"{n:>17}" for n in names))
        for label, rse in labels:
            total = sum(v for k, v in shares[rse].items() if not k.startswith("of it"))
            print(f"{label:32} " + " ".join(f"{v:9.3f} ({100 * v / total:3.0f} %)" for v in shares[rse].values()), flush=True)
    rays, exact = scan_cost(envs[True], 20)
    print(f"height scan per step: rays (read) {1e3 * rays:.3f} ms, rse exact {1e3 * exact:.3f} ms", flush=True)
    proxy = proxies(envs[True], args.episode_s[-1])
    from rse._adapters.mjlab.scene_pool import pool_memory, staging_bytes

    probed, geoms = probe(), envs[True].sim.mj_model.ngeom
    host, on_device = pool_memory(probed, args.num_envs, "cuda", geoms=geoms)
    staging = staging_bytes(probed, args.num_envs)
    print(
        f"terrain on the device per env: {proxy['device bytes/env'] / 1024:.1f} KiB counted from the arrays, "
        f"{proxy['allocated bytes/env'] / 1024:.1f} KiB allocated to them, "
        f"{(on_device - staging) / args.num_envs / 1024:.1f} KiB estimated ([INFO] line, less the upload buffers), "
        + (f"{(held[True] - held[False]) / args.num_envs / 1024:.1f} KiB by Warp's allocator (rse's env less mjlab's)" if held[True] else "no allocator on the CPU")
    )
    print(
        f"a reset's upload buffers on the device: {proxy['upload staging bytes'] / 2**20:.2f} MiB counted, "
        f"{staging / 2**20:.2f} MiB estimated on a GPU (none on the CPU device); "
        f"terrains in all at these envs: {(proxy['device bytes/env'] * args.num_envs + proxy['upload staging bytes']) / 2**30:.3f} GiB, "
        f"estimated at 4096 envs on a GPU: {pool_memory(probed, 4096, 'cuda', geoms=geoms)[1] / 2**30:.3f} GiB",
        flush=True,
    )
    print(
        f"a reset, per env: generation {proxy['reset generate us/env']:.0f} us, upload {proxy['reset upload us/env']:.0f} us "
        f"of the host's time, {proxy['uploaded bytes/env'] / 1024:.1f} KiB uploaded; host copies in rse's step terms: {proxy['host copies in step terms']:.0f}",
        flush=True,
    )
    launches = ", ".join(f"{k.split(': ')[1]} {v:.0f}" for k, v in proxy.items() if k.startswith("launches: "))
    print(f"kernels launched from Python a step, rse's step terms: {launches}", flush=True)
    # One runner per env (a second runner on an env the first used meets
    # its inference-mode tensors): a warm-up iteration, then one timed.
    ppo = {rse: ppo_iteration(args.task, env) for rse, env in envs.items()}
    print(
        f"one PPO iteration (24 steps, episodes of {args.episode_s[-1]} s): mjlab's terrain {ppo[False]:.2f} s, rse {ppo[True]:.2f} s, "
        f"rse/mjlab {ppo[True] / ppo[False]:.3f}",
        flush=True,
    )
    for env in envs.values():
        env.close()


if __name__ == "__main__":
    main()
