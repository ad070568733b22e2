"""A new terrain per environment, printed, not asserted:
4096 envs of 8 m x 8 m tiles of six_obstacles.csv (80x80 cells of 0.1 m),
k = 2 (160x160 samples each), on this machine's cores:

1. rse.EnvTerrains: reset of all 4096 envs and of 64 (a typical step's
   resets), regenerated and written, in the slots and tiles layouts
   (targets: 64 <= 2 ms, 4096 <= 150 ms);
2. MuJoCo Warp on the CPU device: rse.mujoco_warp.sync of 64 slots into the
   device model, beside what users do today to change terrains: rebuild and
   re-upload the model (MjSpec.compile + mujoco_warp.put_model);
3. the memory of the pool.

Run: .venv/bin/python bench/envs.py [NUM_ENVS] (make bench runs it).
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import numpy as np
import rse

SIX = Path(__file__).resolve().parents[1] / "schemes" / "six_obstacles.csv"


def timed(fn, repeats: int) -> float:
    """Median seconds of `fn()` over `repeats` calls."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 4096
    scheme = rse.Scheme.load(SIX).replace(size=(80, 80))
    rng = np.random.default_rng(0)
    nx, ny = scheme.fields()["size"]
    print(f"{n} envs of {nx}x{ny} cells ({nx * scheme.block_size:g} m), k = 2")
    for layout, extra in (("slots", {}), ("tiles", {"cols": int(np.ceil(np.sqrt(n))), "border": 0})):
        start = time.perf_counter()
        envs = rse.EnvTerrains(scheme, n, oversample=2, layout=layout, **extra)
        made = time.perf_counter() - start
        every = list(range(n))
        all_s = timed(lambda: envs.reset(every), 5)
        some = [rng.choice(n, 64, replace=False) for _ in range(200)]
        it = iter(some)
        some_s = timed(lambda: envs.reset(next(it)), 200)
        print(
            f"  {layout:5}: made {made * 1e3:7.1f} ms | reset all {n}: {all_s * 1e3:7.1f} ms (target 150) | "
            f"reset 64: {some_s * 1e3:6.2f} ms (target 2) | samples {envs.samples.nbytes / 2**20:.0f} MiB"
        )
    warp_figures(scheme, min(n, 4096))


def warp_figures(scheme: rse.Scheme, n: int) -> None:
    import mujoco
    import mujoco_warp as mjw
    import warp as wp

    import rse.mujoco_warp

    wp.config.quiet = True
    envs = rse.EnvTerrains(scheme, n, oversample=2)

    def spec_of():
        spec = mujoco.MjSpec()
        rse.mujoco_warp.add_terrain(spec, envs)
        return spec

    start = time.perf_counter()
    mjm = spec_of().compile()
    compile_s = time.perf_counter() - start
    start = time.perf_counter()
    m = rse.mujoco_warp.put_model(mjm, envs)
    wp.synchronize()
    put_s = time.perf_counter() - start
    ids = np.random.default_rng(1).choice(n, 64, replace=False)

    def sync() -> None:
        rse.mujoco_warp.sync(m, mjm, envs, ids)
        wp.synchronize()

    sync_s = timed(sync, 50)
    reset_s = timed(lambda: envs.reset(ids), 50)
    print(
        f"  MuJoCo Warp (CPU device), {n} worlds: reset 64 {reset_s * 1e3:.2f} ms + sync 64 slots {sync_s * 1e3:.2f} ms "
        f"= {(reset_s + sync_s) * 1e3:.2f} ms; rebuilding instead (MjSpec.compile {compile_s:.2f} s + put_model {put_s:.2f} s) "
        f"= {compile_s + put_s:.2f} s: {(compile_s + put_s) / (reset_s + sync_s):,.0f}x slower"
    )
    print(f"  pool: {envs.samples.nbytes / 2**20:.0f} MiB of float32 on the host, the same again in the device model "
          f"(n x (80k)^2 x 4 bytes: size it by num_envs and k)")


if __name__ == "__main__":
    main()
