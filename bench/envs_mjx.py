"""A new terrain per environment in MJX, printed, not asserted:
4096 worlds of 8 m x 8 m tiles of six_obstacles.csv at k = 2 (160x160
samples each) on the CPU: rse.mjx.sync of 64 reset envs' rows into the
batched hfield_data, beside replacing the whole batched field (the upload
users do without it), and the memory of the batched field.

Run: .venv-mjx/bin/python bench/envs_mjx.py [NUM_ENVS] (make bench runs it;
make test makes .venv-mjx).
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

os.environ.setdefault("JAX_PLATFORMS", "cpu")

import jax
import mujoco
import numpy as np
import rse
import rse.mjx

sys.path.insert(0, str(Path(__file__).resolve().parent))
from envs import SIX, timed  # noqa: E402  (bench/envs.py: the same scheme, the same timer)


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 4096
    scheme = rse.Scheme.load(SIX).replace(size=(80, 80))
    envs = rse.EnvTerrains(scheme, n, oversample=2)
    spec = mujoco.MjSpec()
    rse.mjx.add_terrain(spec, envs)
    mjm = spec.compile()
    start = time.perf_counter()
    state = {"m": rse.mjx.put_model(mjm, envs)}
    put = time.perf_counter() - start
    rng = np.random.default_rng(0)
    batches = iter([sorted(rng.choice(n, 64, replace=False).tolist()) for _ in range(60)])

    def sync64() -> None:
        ids = next(batches)
        envs.reset(ids)
        state["m"] = rse.mjx.sync(state["m"], mjm, envs, ids)
        state["m"].hfield_data.block_until_ready()

    sync64()  # compiles the scatter once
    ours = timed(sync64, 50)
    device = state["m"].hfield_data.devices().pop()

    def whole() -> None:
        state["m"] = state["m"].replace(hfield_data=jax.device_put(rse.mjx.hfield_rows(mjm, envs), device))
        state["m"].hfield_data.block_until_ready()

    theirs = timed(whole, 5)
    size = state["m"].hfield_data.nbytes / 2**20
    print(f"MJX (jax CPU), {n} worlds of 160x160 samples: put_model with the batched field {put:.2f} s")
    print(f"  reset 64 envs + rse.mjx.sync of their rows: {ours * 1e3:.2f} ms")
    print(f"  replacing the whole batched field instead: {theirs * 1e3:.1f} ms ({theirs / ours:.0f}x slower)")
    print(f"  batched hfield_data: {size:.0f} MiB (num_envs x nrow x ncol x 4 bytes)")


if __name__ == "__main__":
    main()
