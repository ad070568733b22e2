"""``python -m rse.mjlab_video CHECKPOINT``: a video of a checkpoint
walking on the terrains its run trained on, written, then done. mjlab's
``play --video`` records the same video but keeps its viewer open until
it is stopped; this records without a viewer (an offscreen renderer:
``MUJOCO_GL=egl`` on a GPU machine, ``osmesa`` on a CPU one) and exits::

    python -m rse.mjlab_video logs/rsl_rl/rse_go1_velocity/<run>/model_<n>.pt --steps 200
    # -> logs/rsl_rl/rse_go1_velocity/<run>/videos/rse/rl-video-step-0.mp4

The task's play config (each robot on its own terrain, laid out apart),
the scheme and seed the run recorded (``rse._adapters.mjlab.run_record``; else the
task's), the policy in inference mode, as mjlab's ``play`` runs it."""

from __future__ import annotations

import sys

from rse._adapters.mjlab.video import main, record

__all__ = ["main", "record"]

if __name__ == "__main__":
    sys.exit(main())
