"""One process of a two-process gloo run (tests/frameworks/test_mjlab_ranks.py):
the mjlab ball env of test_mjlab_envs with RANK from the launcher's
environment, its envs' terrains gathered over gloo onto rank 0, which
writes them to the file named on the command line."""

from __future__ import annotations

import sys

import numpy as np
import torch.distributed as dist

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from test_mjlab_envs import make_env  # noqa: E402

from rse.mjlab import env_terrains  # noqa: E402

dist.init_process_group(backend="gloo")
env = make_env()
env.reset()
envs = env_terrains(env)
mine = (np.stack([envs.terrain(e).heights for e in range(env.num_envs)]), envs.episode.copy())
gathered: list = [None] * dist.get_world_size()
dist.all_gather_object(gathered, (dist.get_rank(), mine))
if dist.get_rank() == 0:
    ranks = [m for _, m in sorted(gathered, key=lambda g: g[0])]
    np.savez(sys.argv[1], heights=np.concatenate([h for h, _ in ranks]), episodes=np.concatenate([k for _, k in ranks]))
env.close()
dist.destroy_process_group()
