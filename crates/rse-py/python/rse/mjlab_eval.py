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
``params/`` (``rse._adapters.mjlab.run_record``), else the task's; ``--scheme`` gives
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

import sys

from rse._adapters.mjlab.evaluation import LevelResult, evaluate
from rse._adapters.mjlab.evaluation_cli import main, table

__all__ = ["LevelResult", "evaluate", "main", "table"]

if __name__ == "__main__":
    sys.exit(main())
