"""Many processes (one per GPU in training): two CPU processes joined by
gloo, each an mjlab env of rse terrains with its launcher's RANK, draw
disjoint global env ids — together the terrains of one process holding
both ranges."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
from pathlib import Path

import numpy as np
from test_mjlab_envs import NUM_ENVS, SCHEME

HERE = Path(__file__).resolve().parent


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_two_gloo_processes_are_one_run_of_both_ranges(tmp_path) -> None:
    out = tmp_path / "terrains.npz"
    port = str(free_port())
    procs = []
    for rank in (0, 1):
        env = {**os.environ, "RANK": str(rank), "WORLD_SIZE": "2", "LOCAL_RANK": str(rank),
               "MASTER_ADDR": "127.0.0.1", "MASTER_PORT": port, "CUDA_VISIBLE_DEVICES": ""}
        procs.append(subprocess.Popen([sys.executable, str(HERE / "gloo_worker.py"), str(out)], env=env,
                                      stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True))
    for p in procs:
        said, _ = p.communicate(timeout=900)
        assert p.returncode == 0, said[-3000:]
    run = np.load(out)
    both, episodes = run["heights"], run["episodes"]
    assert both.shape[0] == 2 * NUM_ENVS
    # Global env g at episode k is world k·2³² + g of the scheme: the
    # terrains of one process holding both ranges.
    for g in range(2 * NUM_ENVS):
        alone = SCHEME.generate(seed=11, index=int(episodes[g]) * 2**32 + g, difficulty=1.0)
        assert np.array_equal(both[g], alone.heights), g
    # Disjoint: no two envs of the run drew the same terrain.
    assert len({b.tobytes() for b in both}) == 2 * NUM_ENVS
