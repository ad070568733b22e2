"""Evaluate a velocity policy on a fixed, seeded set of stepfields per
difficulty level: the NIST test-method idea (repeatable terrain, repeated
trials) for learned policies. Takes a checkpoint of an rse task
(``Rse-Velocity-Rough-*``) or of mjlab's own rough task
(``Mjlab-Velocity-Rough-*``: its terrain is replaced by rse's), runs
``per_level`` envs at each of ``levels`` difficulties on the CPU or a GPU,
each env one episode, walking straight ahead at a fixed command, and
reports per level the distance made good, the falls and the time to cross
(docs/train.md, "Evaluate")::

    python -m rse.mjlab_eval logs/rsl_rl/rse_go1_velocity/<run>/model_1000.pt \\
        --task Rse-Velocity-Rough-Unitree-Go1 --levels 10 --per-level 8 --seed 0 --json eval.json

Env ``e`` is at level ``e // per_level`` (difficulty ``level / (levels -
1)``) and walks on the terrain of global env ``e`` of ``seed`` at the
episode the env is at after it is built and reset (the report gives it):
the same terrains on every machine, whatever ran before. Every
robot starts at its terrain's origin facing +x, commanded ``speed`` m/s
forward (no sideways or turning command); an episode lasts ``seconds``.
The env is the task's play config (no observation noise) seeded with
``seed`` (its randomized events too): a rerun gives the same figures. The
terrains are the scheme (or mix) the checkpoint's run recorded in its
``params/`` (``rse._mjlab_run``), else the task's; ``--scheme`` gives
another. It says which.

- **distance made good**: how far the robot got along +x from its start,
  metres, when its episode ended (at a fall: the last control step before
  it; at the end of time: where it stood);
- **falls**: episodes ended by a termination that is not a time-out
  (mjlab's ``fell_over``, illegal contacts);
- **time to cross**: seconds until the robot was half a terrain ahead of
  its start (the terrain's far edge), for the episodes that got there.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Optional

import numpy as np

from rse._adapters import contacts

__all__ = ["LevelResult", "evaluate", "main", "table"]


@dataclass(frozen=True)
class LevelResult:
    """One level's episodes, summarised."""

    level: int
    difficulty: float
    episodes: int
    distance_mean: float
    """Distance made good, metres, mean over the episodes."""
    distance_min: float
    falls: int
    crossed: int
    time_to_cross_mean: Optional[float]
    """Seconds, over the episodes that crossed; None when none did."""


def _scheme_name(terrain: Any) -> str:
    """The scheme as a person reads it: its file, its first line, or a
    mix's files and proportions."""
    if terrain.schemes:
        return "a mix of " + ", ".join(f"{k} ({p:g})" for k, p in terrain.schemes.items() if "\n" not in k)
    if "\n" not in terrain.scheme:
        return terrain.scheme
    return "CSV text: " + terrain.scheme.strip().splitlines()[0][:60]


def evaluate(
    checkpoint: str,
    task: str,
    *,
    levels: int = 10,
    per_level: int = 8,
    seed: int = 0,
    scheme: Optional[str] = None,
    seconds: float = 10.0,
    speed: float = 1.0,
    device: str = "cpu",
) -> dict[str, Any]:
    """Runs the evaluation (see the module's documentation) and returns its
    report: the settings, one ``LevelResult`` per level (as dicts) and the
    per-episode figures."""
    import mjlab.tasks  # noqa: F401  (registers the tasks)
    from mjlab.envs import ManagerBasedRlEnv
    from mjlab.tasks.registry import load_env_cfg

    from rse._adapters.mjlab.config import use_env_terrains
    from rse._adapters.mjlab.event import event_of
    from rse._mjlab_run import load_policy, run_terrain
    from rse.mjlab_tasks import STEPFIELD

    if levels < 1 or per_level < 1:
        raise ValueError(f"levels and per_level: {levels}, {per_level}; expected 1 or more")
    if not seconds > 0 or not math.isfinite(speed):
        raise ValueError(f"seconds and speed: {seconds}, {speed}; expected seconds > 0 and a finite speed")
    # The play config: no observation noise, as a policy is deployed; the
    # env's own seed too, for its randomized events (friction at startup).
    cfg = load_env_cfg(task, play=True)
    cfg.seed = seed
    n = levels * per_level
    cfg.scene.num_envs = n
    source = "given"
    # Made anew below, so that every field is checked and recorded again.
    changes: dict[str, Any] = {"seed": seed, "difficulty": 0.0, "apart": False}
    if scheme is not None:
        changes.update(scheme=scheme, schemes={})
    else:
        # The scheme (or mix) the checkpoint's run trained on, where it
        # recorded one; the set's own seed stays.
        recorded = run_terrain(checkpoint)
        if recorded is not None:
            changes.update({k: v for k, v in recorded.items() if k != "seed"})
            source = "the run folder"
    if type(cfg.scene.terrain).__name__ != "EnvTerrainCfg":
        use_env_terrains(cfg, STEPFIELD, seed=seed, difficulty=0.0)
        source = source if "scheme" in changes or "schemes" in changes else "rse.mjlab_tasks.STEPFIELD"
    elif source == "given" and scheme is None:
        source = f"the task's ({task})"
    cfg.scene.terrain = dataclasses.replace(cfg.scene.terrain, **changes)
    terrain = cfg.scene.terrain
    digest = f" (SHA-256 {terrain.scheme_sha256[:16]}…)" if terrain.scheme_sha256 else ""
    print(f"rse.mjlab_eval: scheme from {source}: {_scheme_name(terrain)}{digest}", file=sys.stderr)
    _fix_for_evaluation(cfg, seconds, speed)
    env = ManagerBasedRlEnv(cfg, device=device)
    try:
        event = event_of(env, "rse_terrain")
        level_of = np.arange(n) // per_level
        difficulty = level_of / max(levels - 1, 1)
        event.envs.difficulty[:] = difficulty
        wrapped, policy = load_policy(task, env, checkpoint, device)
        # Every env's evaluated terrain: its next episode, at its level.
        wrapped.reset()
        # Half a terrain ahead: its far edge, from its centre.
        half = 0.5 * event.envs.terrain(0).block_size * contacts.slot_cells(event.envs)[1]
        episodes = _run(env, wrapped, policy, event, seconds, half)
    finally:
        env.close()
    results = []
    for level in range(levels):
        rows = [e for e in episodes if e["env"] // per_level == level]
        crossed = [e["time_to_cross"] for e in rows if e["time_to_cross"] is not None]
        results.append(
            asdict(
                LevelResult(
                    level=level,
                    difficulty=float(difficulty[level * per_level]),
                    episodes=len(rows),
                    distance_mean=float(np.mean([e["distance"] for e in rows])),
                    distance_min=float(np.min([e["distance"] for e in rows])),
                    falls=sum(e["fell"] for e in rows),
                    crossed=len(crossed),
                    time_to_cross_mean=float(np.mean(crossed)) if crossed else None,
                )
            )
        )
    return {
        "checkpoint": checkpoint,
        "task": task,
        "seed": seed,
        "scheme": terrain.scheme_csv,
        "schemes": {name: {"csv": text, "proportion": float(p)} for (name, text), p in zip(terrain.schemes_csv.items(), terrain.schemes.values())},
        "scheme_source": source,
        "scheme_sha256": terrain.scheme_sha256,
        "levels": levels,
        "per_level": per_level,
        "seconds": seconds,
        "speed": speed,
        "cross_distance": half,
        "per_level_results": results,
        "episodes": episodes,
    }


def _fix_for_evaluation(cfg: Any, seconds: float, speed: float) -> None:
    """The same start and command for every env: at the terrain's origin
    facing +x, ``speed`` m/s straight ahead; no curriculum, no pushes."""
    cfg.episode_length_s = seconds
    for name in list(cfg.curriculum):
        del cfg.curriculum[name]
    base = cfg.events.get("reset_base")
    if base is not None and "pose_range" in base.params:
        base.params["pose_range"] = {**base.params["pose_range"], "x": (0.0, 0.0), "y": (0.0, 0.0), "yaw": (0.0, 0.0)}
    for name in [k for k in cfg.events if "push" in k]:
        del cfg.events[name]
    twist = cfg.commands.get("twist")
    if twist is not None:
        twist.ranges.lin_vel_x = (speed, speed)
        twist.ranges.lin_vel_y = (0.0, 0.0)
        twist.ranges.ang_vel_z = (0.0, 0.0)
        twist.heading_command = False
        twist.ranges.heading = None
        twist.rel_standing_envs = 0.0
        twist.rel_heading_envs = 0.0
        for name in ("rel_forward_envs", "rel_world_envs", "init_velocity_prob"):
            if hasattr(twist, name):
                setattr(twist, name, 0.0)
        twist.resampling_time_range = (1e9, 1e9)


def _run(env: Any, wrapped: Any, policy: Any, event: Any, seconds: float, half: float) -> list[dict[str, Any]]:
    """Steps every env until its first episode ends; each env's figures
    (crossed: ``half`` metres ahead of its start)."""
    import torch

    n = env.num_envs
    episode = event.envs.episode.copy()
    robot = env.scene["robot"]
    start = robot.data.root_link_pos_w[:, :2].detach().cpu().numpy().copy()
    dt = env.step_dt
    steps = int(math.ceil(seconds / dt)) + 1
    done = np.zeros(n, dtype=bool)
    fell = np.zeros(n, dtype=bool)
    distance = np.zeros(n)
    crossed: list[Optional[float]] = [None] * n
    obs = wrapped.get_observations()
    for step in range(steps):
        last = robot.data.root_link_pos_w[:, :2].detach().cpu().numpy().copy()
        with torch.inference_mode():
            obs, _, dones, extras = wrapped.step(policy(obs))
        ended = dones.detach().cpu().numpy().astype(bool) & ~done
        now = robot.data.root_link_pos_w[:, :2].detach().cpu().numpy()
        t = (step + 1) * dt
        for e in np.flatnonzero(~done & ~ended):
            if crossed[e] is None and now[e, 0] - start[e, 0] >= half:
                crossed[e] = t
        time_outs = extras.get("time_outs")
        timed_out = time_outs.detach().cpu().numpy().astype(bool) if time_outs is not None else np.zeros(n, bool)
        for e in np.flatnonzero(ended):
            # The step that ended it also reset it: its last place is the
            # one before the step.
            distance[e] = last[e, 0] - start[e, 0]
            fell[e] = not timed_out[e]
            if crossed[e] is None and distance[e] >= half:
                crossed[e] = t
        done |= ended
        if done.all():
            break
    for e in np.flatnonzero(~done):
        distance[e] = now[e, 0] - start[e, 0]
    return [
        {
            "env": int(e),
            "difficulty": float(event.envs.difficulty[e]),
            "episode": int(episode[e]),
            "distance": float(distance[e]),
            "fell": bool(fell[e]),
            "time_to_cross": crossed[e],
        }
        for e in range(n)
    ]


def table(report: dict[str, Any]) -> str:
    """The report as a table a person reads."""
    lines = [
        f"{report['task']} on {report['levels']} levels × {report['per_level']} stepfields, seed {report['seed']}, "
        f"{report['speed']} m/s for {report['seconds']} s (crossing: {report['cross_distance']:.1f} m)",
        "level  difficulty  distance mean (min)  falls  crossed  time to cross",
    ]
    for r in report["per_level_results"]:
        cross = "—" if r["time_to_cross_mean"] is None else f"{r['time_to_cross_mean']:.2f} s"
        lines.append(
            f"{r['level']:>5}  {r['difficulty']:>10.3f}  {r['distance_mean']:>7.2f} m ({r['distance_min']:.2f})"
            f"  {r['falls']:>2}/{r['episodes']:<2}  {r['crossed']:>3}/{r['episodes']:<3}  {cross:>13}"
        )
    return "\n".join(lines) + "\n"


def main(argv: Optional[list[str]] = None) -> int:
    """``python -m rse.mjlab_eval``: the command line."""
    parser = argparse.ArgumentParser(prog="python -m rse.mjlab_eval", description=__doc__.split("\n\n")[0])
    parser.add_argument("checkpoint", help="an rsl-rl checkpoint (model_N.pt) of the task")
    parser.add_argument("--task", default="Rse-Velocity-Rough-Unitree-Go1", help="the task it was trained on")
    parser.add_argument("--levels", type=int, default=10, help="difficulty levels, from 0 to 1 (default 10)")
    parser.add_argument("--per-level", type=int, default=8, help="stepfields (episodes) per level (default 8)")
    parser.add_argument("--seed", type=int, default=0, help="the set's seed (default 0)")
    parser.add_argument(
        "--scheme", help="a scheme CSV (default: the one the checkpoint's run trained on, from its params/, else the task's)"
    )
    parser.add_argument("--seconds", type=float, default=10.0, help="episode length (default 10)")
    parser.add_argument("--speed", type=float, default=1.0, help="forward command, m/s (default 1)")
    parser.add_argument("--device", default="cpu", help="cpu or cuda:N (default cpu)")
    parser.add_argument("--json", help="also write the report, every episode included, as JSON here")
    args = parser.parse_args(argv)
    try:
        report = evaluate(
            args.checkpoint,
            args.task,
            levels=args.levels,
            per_level=args.per_level,
            seed=args.seed,
            scheme=args.scheme,
            seconds=args.seconds,
            speed=args.speed,
            device=args.device,
        )
    except (ValueError, OSError) as e:
        print(f"rse.mjlab_eval: {e}", file=sys.stderr)
        return 2
    sys.stdout.write(table(report))
    if args.json:
        from rse._mjlab_run import write_whole

        # Whole or not at all: beside it, then renamed over it.
        write_whole(Path(args.json), json.dumps(report, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
