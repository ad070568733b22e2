"""The evaluation of ``rse.mjlab_eval`` (its documentation says what it
measures): the env config of a fixed, seeded set of stepfields per level,
the episodes run, and the report of each level."""

from __future__ import annotations

import dataclasses
import math
import sys
from dataclasses import asdict, dataclass
from typing import Any, Optional

import numpy as np

from rse._adapters import contacts


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


def _check_settings(levels: int, per_level: int, seconds: float, speed: float) -> None:
    if levels < 1 or per_level < 1:
        raise ValueError(f"levels and per_level: {levels}, {per_level}; expected 1 or more")
    if not seconds > 0 or not math.isfinite(speed):
        raise ValueError(f"seconds and speed: {seconds}, {speed}; expected seconds > 0 and a finite speed")


def _evaluation_cfg(task: str, checkpoint: str, n: int, seed: int, scheme: Optional[str]) -> tuple[Any, str]:
    """The task's play config for ``n`` envs on the evaluated terrains,
    and where their scheme came from."""
    from mjlab.tasks.registry import load_env_cfg

    from rse._adapters.mjlab.env_cfg import use_env_terrains
    from rse._adapters.mjlab.run_record import run_terrain
    from rse._adapters.mjlab.tasks import STEPFIELD

    # The play config: no observation noise, as a policy is deployed; the
    # env's own seed too, for its randomized events (friction at startup).
    cfg = load_env_cfg(task, play=True)
    cfg.seed = seed
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
    return cfg, source


def _episodes(cfg: Any, task: str, checkpoint: str, per_level: int, run: tuple[float, str]) -> tuple[list[dict[str, Any]], np.ndarray, float]:
    """Every env's episode at its level (``run``: seconds, device), each
    level's difficulty by env, and the distance that counts as crossing."""
    from mjlab.envs import ManagerBasedRlEnv

    from rse._adapters.mjlab.reset_event import event_of
    from rse._adapters.mjlab.run_record import load_policy

    seconds, device = run
    env = ManagerBasedRlEnv(cfg, device=device)
    try:
        event = event_of(env, "rse_terrain")
        levels = max(cfg.scene.num_envs // per_level, 1)
        difficulty = (np.arange(cfg.scene.num_envs) // per_level) / max(levels - 1, 1)
        event.envs.difficulty[:] = difficulty
        wrapped, policy = load_policy(task, env, checkpoint, device)
        # Every env's evaluated terrain: its next episode, at its level.
        wrapped.reset()
        # Half a terrain ahead: its far edge, from its centre.
        half = 0.5 * event.envs.terrain(0).block_size * contacts.slot_cells(event.envs)[1]
        return _run(env, wrapped, policy, event, seconds, half), difficulty, half
    finally:
        env.close()


def _level_results(episodes: list[dict[str, Any]], levels: int, per_level: int, difficulty: np.ndarray) -> list[dict[str, Any]]:
    """One ``LevelResult`` per level, as a dict."""
    results = []
    for level in range(levels):
        ran = [e for e in episodes if e["env"] // per_level == level]
        crossed = [e["time_to_cross"] for e in ran if e["time_to_cross"] is not None]
        result = LevelResult(
            level=level,
            difficulty=float(difficulty[level * per_level]),
            episodes=len(ran),
            distance_mean=float(np.mean([e["distance"] for e in ran])),
            distance_min=float(np.min([e["distance"] for e in ran])),
            falls=sum(e["fell"] for e in ran),
            crossed=len(crossed),
            time_to_cross_mean=float(np.mean(crossed)) if crossed else None,
        )
        results.append(asdict(result))
    return results


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
    """Runs the evaluation (see ``rse.mjlab_eval``'s documentation) and
    returns its report: the settings, one ``LevelResult`` per level (as
    dicts) and the per-episode figures."""
    import mjlab.tasks  # noqa: F401  (registers the tasks)

    _check_settings(levels, per_level, seconds, speed)
    cfg, source = _evaluation_cfg(task, checkpoint, levels * per_level, seed, scheme)
    terrain = cfg.scene.terrain
    digest = f" (SHA-256 {terrain.scheme_sha256[:16]}…)" if terrain.scheme_sha256 else ""
    print(f"rse.mjlab_eval: scheme from {source}: {_scheme_name(terrain)}{digest}", file=sys.stderr)
    _fix_for_evaluation(cfg, seconds, speed)
    episodes, difficulty, half = _episodes(cfg, task, checkpoint, per_level, (seconds, device))
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
        "per_level_results": _level_results(episodes, levels, per_level, difficulty),
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
