"""What a reset of Genesis tiles costs, printed, not asserted: new
terrains (``envs.reset``) and ``rse.genesis.sync`` writing the whole map
(every reset before, and still without ids), beside ``rse.genesis.reset``
writing the reset envs' tiles alone, in one process, alternating.

The Go2 example's tiles (40 x 40 cells of 0.1 m, k = 2, border 2: 84 x 84
samples each), a ball to collide, Genesis on the CPU (``--device cuda``
where a GPU is at hand). Genesis builds the terrain's signed-distance
field when it builds the scene: minutes for a few hundred tiles.

Run: .venv-genesis/bin/python bench/genesis_sync.py [--num-envs 256]
[--resets 4 64] [--rounds 7] (make test-frameworks makes the venv).
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

import rse
import rse.genesis

TILE = "# size: 40x40\n# block_size: 0.1\n# step_height: 0.05\n# seed: 3\ntype,height,angle,x1,y1\nrandom,0..4,,,\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--num-envs", type=int, default=256)
    parser.add_argument("--resets", type=int, nargs="+", default=[4, 64], help="envs reset a call")
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--device", default="cpu", choices=["cpu", "cuda"])
    args = parser.parse_args()

    import genesis as gs

    gs.init(backend=gs.cpu if args.device == "cpu" else gs.gpu, logging_level="warning", precision="32")
    envs = rse.EnvTerrains(rse.Scheme.from_csv(TILE), args.num_envs, layout="tiles", border=2, seed=1)
    print(f"{args.num_envs} tiles of {envs.field_shape[0]} x {envs.field_shape[1]} samples, map {envs.samples.shape[1:]}, "
          f"{envs.samples.nbytes / 2**20:.1f} MiB")
    start = time.perf_counter()
    scene = gs.Scene(sim_options=gs.options.SimOptions(dt=0.005), show_viewer=False)
    terrain = scene.add_entity(rse.genesis.terrain_morph(envs))
    scene.add_entity(gs.morphs.Sphere(radius=0.02, pos=(0.0, 0.0, 1.0)))
    scene.build(n_envs=args.num_envs)
    print(f"scene built in {time.perf_counter() - start:.0f} s")
    rse.genesis.sync(scene, terrain, envs)  # the whole map once: later syncs may write tiles
    rng = np.random.default_rng(0)

    def timed(ids: np.ndarray, whole: bool) -> float:
        """Seconds of a reset of ``ids``: new terrains, then the scene's
        field rewritten whole, or their tiles alone (``reset``)."""
        sync_device()
        begin = time.perf_counter()
        if whole:
            envs.reset(ids)
            rse.genesis.sync(scene, terrain, envs)
        else:
            rse.genesis.reset(scene, terrain, envs, ids)
        sync_device()
        return time.perf_counter() - begin

    def sync_device() -> None:
        if args.device == "cuda":
            import torch

            torch.cuda.synchronize()

    print(f"\nA reset (new terrains and the rewrite), median of {args.rounds} alternating rounds (each after one of its kind):")
    print(f"{'envs reset':>10} | {'whole map, ms':>14} | {'their tiles, ms':>15} | whole / tiles")
    for n in args.resets:
        times: dict[bool, list[float]] = {True: [], False: []}
        for _ in range(args.rounds):
            for whole in (True, False):
                # One untimed first: a whole map's write leaves the caches
                # cold for what follows it, which a training run's resets
                # (all of one kind) do not see.
                for _warm in range(2):
                    took = timed(np.sort(rng.choice(args.num_envs, n, replace=False)), whole)
                times[whole].append(took)
        w, t = statistics.median(times[True]), statistics.median(times[False])
        print(f"{n:>10} | {1e3 * w:>14.2f} | {1e3 * t:>15.2f} | {w / t:.1f}x")


if __name__ == "__main__":
    main()
