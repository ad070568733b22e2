"""``python -m rse.mjlab_eval``: the command line of the evaluation
(``rse._adapters.mjlab.evaluation``) and its report as a table."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any, Optional

from rse._adapters.mjlab.evaluation import evaluate

DESCRIPTION = (
    "Evaluate a velocity policy on a fixed, seeded set of stepfields per difficulty level: "
    "the NIST test-method idea (repeatable terrain, repeated trials) for learned policies."
)


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
    parser = argparse.ArgumentParser(prog="python -m rse.mjlab_eval", description=DESCRIPTION)
    parser.add_argument("checkpoint", help="an rsl-rl checkpoint (model_N.pt) of the task")
    parser.add_argument("--task", default="Rse-Velocity-Rough-Unitree-Go1", help="the task it was trained on")
    parser.add_argument("--levels", type=int, default=10, help="difficulty levels, from 0 to 1 (default 10)")
    parser.add_argument("--per-level", type=int, default=8, help="stepfields (episodes) per level (default 8)")
    parser.add_argument("--seed", type=int, default=0, help="the set's seed (default 0)")
    parser.add_argument("--scheme", help="a scheme CSV (default: the one the checkpoint's run trained on, from its params/, else the task's)")
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
        from rse._adapters.mjlab.run_record import write_whole

        # Whole or not at all: beside it, then renamed over it.
        write_whole(Path(args.json), json.dumps(report, indent=1) + "\n")
    return 0
