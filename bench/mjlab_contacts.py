"""Contacts on mjlab's terrain and on rse's per-env stepfields, side by
side, in mjlab's rough velocity tasks: MuJoCo Warp's overflow warnings
(height-field pairs past its 50-prism cap, broadphase past ``nconmax``),
the terrain contacts per foot, and the deepest penetration of any geom
into the terrain. Robots take random actions (an untrained policy's
flailing and falls, where contacts are most), episodes are cut short so
that terrains are renewed often.

Usage (make bench-frameworks, in .venv-frameworks):
    python bench/mjlab_contacts.py [--task Go1] [--num-envs 16] [--steps 200]
    python bench/mjlab_contacts.py --device cuda --num-envs 4096 --steps 100   # a GPU
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Optional

import numpy as np
import torch

REPO = Path(__file__).resolve().parent.parent


@dataclass
class Tally:
    """What one run saw."""

    steps: int = 0
    hfield_overflow: int = 0  # world-steps with a height-field pair past the cap
    other_overflow: int = 0  # world-steps with any other overflow bit
    printed: int = 0  # overflow lines MuJoCo Warp printed
    foot_contacts: list[float] = field(default_factory=list)  # per loaded foot
    deepest: float = 0.0  # most negative contact distance, metres
    deepest_geom: str = ""
    foot_deepest: float = 0.0
    depths: list[float] = field(default_factory=list)  # every terrain contact's penetration, metres


class CapturedStdout:
    """The process's own stdout (fd 1), where Warp's ``printf`` writes,
    into a file for the duration."""

    def __enter__(self) -> "CapturedStdout":
        sys.stdout.flush()
        self.file = tempfile.TemporaryFile(mode="w+b")
        self.saved = os.dup(1)
        os.dup2(self.file.fileno(), 1)
        return self

    def __exit__(self, *exc: Any) -> None:
        sys.stdout.flush()
        os.dup2(self.saved, 1)
        os.close(self.saved)
        self.file.seek(0)
        self.text = self.file.read().decode(errors="replace")
        self.file.close()


def make(
    task: str, num_envs: int, device: str, episode_s: float, rse: bool, oversample: Optional[int], play: bool, spawn_radius: Optional[float] = None
) -> Any:
    import mjlab.tasks  # noqa: F401
    from mjlab.envs import ManagerBasedRlEnv
    from mjlab.tasks.registry import load_env_cfg

    cfg = load_env_cfg(task, play=play)
    cfg.scene.num_envs = num_envs
    cfg.episode_length_s = episode_s
    if rse:
        import rse as rse_pkg
        from rse.mjlab import use_env_terrains
        from rse.mjlab_tasks import STEPFIELD

        use_env_terrains(cfg, rse_pkg.Scheme.from_csv(STEPFIELD), oversample=oversample, spawn_radius=spawn_radius)
    env = ManagerBasedRlEnv(cfg, device=device)
    env.reset()
    return env


def run(env: Any, steps: int, seed: int) -> Tally:
    import mujoco
    from mujoco_warp._src.types import OverflowType

    m = env.sim.mj_model
    terrain_body = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "terrain")
    terrain = np.zeros(m.ngeom, dtype=bool)
    terrain[m.geom_bodyid == terrain_body] = True
    feet = np.zeros(m.ngeom, dtype=bool)
    for g in range(m.ngeom):
        name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, g) or ""
        if "foot" in name and "collision" in name:
            feet[g] = True
    d = env.sim.wp_data
    gen = torch.Generator(device="cpu").manual_seed(seed)
    t = Tally()
    with CapturedStdout() as out:
        for _ in range(steps):
            action = (torch.rand(env.action_space.shape, generator=gen) * 2 - 1).to(env.device)
            env.step(action)
            t.steps += 1
            flags = d.overflow.numpy()
            t.hfield_overflow += int(((flags & int(OverflowType.HFIELD)) != 0).sum())
            t.other_overflow += int(((flags & ~int(OverflowType.HFIELD)) != 0).sum())
            n = int(d.nacon.numpy()[0])
            geom = d.contact.geom.numpy()[:n]
            dist = d.contact.dist.numpy()[:n]
            world = d.contact.worldid.numpy()[:n]
            on_terrain = terrain[geom[:, 0]] | terrain[geom[:, 1]]
            if on_terrain.any():
                t.depths.extend((-dist[on_terrain]).clip(0, None).tolist())
                i = int(np.argmin(np.where(on_terrain, dist, np.inf)))
                if dist[i] < t.deepest:
                    t.deepest = float(dist[i])
                    other = geom[i, 1] if terrain[geom[i, 0]] else geom[i, 0]
                    t.deepest_geom = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, int(other)) or str(other)
            foot = on_terrain & (feet[geom[:, 0]] | feet[geom[:, 1]])
            if foot.any():
                t.foot_deepest = min(t.foot_deepest, float(dist[foot].min()))
                key = world[foot] * m.ngeom + np.where(feet[geom[foot, 0]], geom[foot, 0], geom[foot, 1])
                _, per_foot = np.unique(key, return_counts=True)
                t.foot_contacts.extend(per_foot.tolist())
        torch.cuda.synchronize() if env.device.startswith("cuda") else None
    t.printed = sum(1 for line in out.text.splitlines() if "overflow" in line)
    return t


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="Go1", help="Go1 or G1 (mjlab's Mjlab-Velocity-Rough-Unitree-TASK)")
    parser.add_argument("--num-envs", type=int, default=16)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--episode-s", type=float, default=2.0)
    parser.add_argument("--device", default="cpu")
    parser.add_argument("--oversample", type=int, action="append", help="rse oversamples to try (default: the default)")
    parser.add_argument("--play", action="store_true", help="the play config (one long episode)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--spawn-radius", type=float, default=None)
    parser.add_argument("--rse-only", action="store_true", help="leave out mjlab's terrain (one env in memory at 4096)")
    args = parser.parse_args()

    task = f"Mjlab-Velocity-Rough-Unitree-{args.task}"
    runs: list[tuple[str, bool, Optional[int]]] = [] if args.rse_only else [("mjlab's terrain", False, None)]
    for k in args.oversample or [None]:
        runs.append((f"rse, oversample {k if k is not None else 'default'}", True, k))
    print(
        f"{task}{' (play)' if args.play else ''}, {args.num_envs} envs on {args.device}, "
        f"{args.steps} steps of random actions, episodes of {args.episode_s} s",
        file=sys.stderr,
    )
    print(
        f"{'terrain':26} {'hfield overflow':>16} {'other overflow':>15} {'printed':>8} "
        f"{'contacts/foot mean (max)':>25} {'penetration mm p99':>19} {'deepest mm (feet)':>18}  deepest geom",
        file=sys.stderr,
    )
    for label, rse, k in runs:
        torch.manual_seed(args.seed)
        env = make(task, args.num_envs, args.device, args.episode_s, rse, k, args.play, args.spawn_radius)
        t = run(env, args.steps, args.seed)
        env.close()
        per_foot = np.asarray(t.foot_contacts or [0])
        p99 = float(np.percentile(t.depths, 99)) if t.depths else 0.0
        print(
            f"{label:26} {t.hfield_overflow:16d} {t.other_overflow:15d} {t.printed:8d} "
            f"{per_foot.mean():17.2f} ({per_foot.max():3d}) {1e3 * p99:19.1f} "
            f"{1e3 * t.deepest:9.1f} ({1e3 * t.foot_deepest:5.1f})  {t.deepest_geom}",
            file=sys.stderr,
            flush=True,
        )


if __name__ == "__main__":
    main()
