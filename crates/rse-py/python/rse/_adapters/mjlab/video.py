"""The video of ``python -m rse.mjlab_video`` (its documentation says what
it records): a checkpoint's policy on its run's terrains, rendered
offscreen."""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path
from typing import Any, Optional


def record(
    checkpoint: str,
    task: str = "Rse-Velocity-Rough-Unitree-Go1",
    *,
    steps: int = 200,
    num_envs: int = 4,
    folder: Optional[str] = None,
    device: str = "cpu",
) -> Path:
    """Records ``steps`` env steps of ``checkpoint``'s policy in ``task``'s
    play config into ``folder`` (default: the run's ``videos/rse/``) and
    returns the video's path."""
    import importlib

    import torch

    # torch's compiler (triton, which rsl-rl's tensordict loads) before
    # MuJoCo's OSMesa renderer: the other way round, two LLVMs in one
    # process crashed it (MUJOCO_GL=osmesa, Debian's libosmesa6).
    try:
        importlib.import_module("tensordict")
    except ImportError:
        pass
    import mjlab.tasks  # noqa: F401  (registers the tasks)
    from mjlab.envs import ManagerBasedRlEnv
    from mjlab.tasks.registry import load_env_cfg
    from mjlab.utils.wrappers import VideoRecorder

    from rse._adapters.mjlab.run_record import load_policy, run_terrain

    if steps < 1 or num_envs < 1:
        raise ValueError(f"steps and num_envs: {steps}, {num_envs}; expected 1 or more")
    if not Path(checkpoint).is_file():
        raise ValueError(f"checkpoint: {checkpoint} is not a file")
    cfg = load_env_cfg(task, play=True)
    cfg.scene.num_envs = num_envs
    recorded = run_terrain(checkpoint)
    if recorded is not None and type(cfg.scene.terrain).__name__ == "EnvTerrainCfg":
        cfg.scene.terrain = dataclasses.replace(cfg.scene.terrain, **recorded)
        print(f"rse.mjlab_video: the terrains the run trained on (seed {recorded['seed']})", file=sys.stderr)
    out = Path(folder) if folder is not None else Path(checkpoint).resolve().parent / "videos" / "rse"
    env: Any = ManagerBasedRlEnv(cfg, device=device, render_mode="rgb_array")
    env = VideoRecorder(env, video_folder=out, step_trigger=lambda step: step == 0, video_length=steps, disable_logger=True)
    try:
        wrapped, policy = load_policy(task, env, checkpoint, device)
        obs = wrapped.get_observations()
        for _ in range(steps):
            with torch.inference_mode():
                obs, *_ = wrapped.step(policy(obs))
    finally:
        # Closing the recorder writes the video out.
        env.close()
    videos = sorted(out.glob("*.mp4"), key=lambda p: p.stat().st_mtime)
    if not videos:
        raise RuntimeError(f"no video was written into {out}")
    return videos[-1]


def main(argv: Optional[list[str]] = None) -> int:
    """``python -m rse.mjlab_video``: the command line."""
    parser = argparse.ArgumentParser(prog="python -m rse.mjlab_video", description=__doc__.split("\n\n")[0])
    parser.add_argument("checkpoint", help="an rsl-rl checkpoint (model_N.pt) of the task")
    parser.add_argument("--task", default="Rse-Velocity-Rough-Unitree-Go1", help="the task it was trained on")
    parser.add_argument("--steps", type=int, default=200, help="env steps recorded (default 200: 4 s)")
    parser.add_argument("--num-envs", type=int, default=4, help="robots, each on its own terrain (default 4)")
    parser.add_argument("--folder", help="where the video goes (default: the run's videos/rse/)")
    parser.add_argument("--device", default="cpu", help="cpu or cuda:N (default cpu)")
    args = parser.parse_args(argv)
    try:
        video = record(args.checkpoint, args.task, steps=args.steps, num_envs=args.num_envs, folder=args.folder, device=args.device)
    except (ValueError, OSError) as e:
        print(f"rse.mjlab_video: {e}", file=sys.stderr)
        return 2
    print(video)
    return 0
