"""Python-side figures, printed with ratios:

1. generating a 50x50 six-obstacle terrain from Python against the same
   call timed inside Rust (aim: under 1.2x);
2. generate_batch of 10,000 such terrains on 2 jobs: wall and CPU time
   (both cores used when CPU / wall is near 2);
3. the numpy way RL frameworks build a random-grid terrain and its mesh
   (per-cell boxes concatenated, as Isaac Lab's random grid does) against
   scheme.generate() + terrain.mesh() (aim: 50x faster);
4. a height scan as RL code takes one (4096 robots x 187 rays, Isaac Lab's
   default grid scanner): Terrain.height_at against the numpy lookup
   people write by hand on Terrain.elevation (cell index, clip, gather).

Run: .venv/bin/python bench/python.py   (make bench runs it)
"""

import os
import time
from pathlib import Path

import numpy as np
import rse
import trimesh

REPO = Path(__file__).resolve().parents[1]


def best_per_call(fn, calls: int, rounds: int = 5) -> float:
    """Best over `rounds` of the mean seconds per call of `fn` over `calls`."""
    best = float("inf")
    for _ in range(rounds):
        start = time.perf_counter()
        for i in range(calls):
            fn(i)
        best = min(best, (time.perf_counter() - start) / calls)
    return best


def naive_random_grid(nx: int, ny: int, block: float, step: float, max_height: int, rng) -> trimesh.Trimesh:
    """A random grid as the RL terrain generators build it: numpy heights,
    then one closed box per cell, concatenated."""
    heights = rng.integers(0, max_height + 1, size=(ny, nx))
    boxes = []
    for y in range(ny):
        for x in range(nx):
            top = heights[y, x] * step
            if top <= 0:
                continue
            transform = trimesh.transformations.translation_matrix([(x + 0.5) * block, (y + 0.5) * block, top / 2])
            boxes.append(trimesh.creation.box(extents=[block, block, top], transform=transform))
    return trimesh.util.concatenate(boxes)


def main() -> None:
    scheme = rse.Scheme.load(REPO / "schemes/six_obstacles.csv")
    calls = 2000
    rust = min(rse._rse._time_generate(scheme, calls) for _ in range(5)) / calls
    python = best_per_call(lambda i: scheme.generate(index=i), calls)
    print(f"generate 50x50 six obstacles: Python {python * 1e6:.1f} us/call, Rust {rust * 1e6:.1f} us/call, "
          f"ratio {python / rust:.2f} (aim < 1.2)")

    amount, jobs = 10_000, 2
    cpu0, wall0 = time.process_time(), time.perf_counter()
    terrains = rse.generate_batch(scheme, amount, jobs=jobs)
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    assert len(terrains) == amount
    print(f"generate_batch {amount} terrains on {jobs} jobs: {wall:.2f} s wall, {cpu:.2f} s CPU, "
          f"CPU/wall {cpu / wall:.2f} ({os.cpu_count()} cores; 2.0 = both used), {amount / wall:.0f} terrains/s")

    random = rse.Scheme.from_csv("# size: 50x50\ntype,height\nrandom,4\n")
    ours = best_per_call(lambda i: random.generate(index=i).mesh(), 50)
    rng = np.random.default_rng(0)
    naive = best_per_call(lambda i: naive_random_grid(50, 50, 0.1, 0.1, 4, rng), 3, rounds=3)
    v, f = random.generate().mesh()
    mesh = naive_random_grid(50, 50, 0.1, 0.1, 4, np.random.default_rng(1))
    print(f"50x50 random grid + mesh: numpy per-cell boxes {naive * 1e3:.1f} ms ({len(mesh.faces)} triangles), "
          f"rse generate + mesh {ours * 1e3:.2f} ms ({len(f)} triangles): {naive / ours:.0f}x faster (aim 50x)")

    terrain = scheme.generate(index=3)
    points = np.random.default_rng(2).uniform(-0.5, 5.5, size=(2, 4096, 187))
    ours = best_per_call(lambda i: terrain.height_at(points[0], points[1]), 5)
    elevation, s = terrain.elevation, terrain.block_size

    def by_hand(i: int) -> np.ndarray:
        ix = np.floor(points[0] / s).astype(np.int64)
        iy = np.floor(points[1] / s).astype(np.int64)
        inside = (ix >= 0) & (iy >= 0) & (ix < elevation.shape[1]) & (iy < elevation.shape[0])
        return np.where(inside, elevation[np.clip(iy, 0, elevation.shape[0] - 1), np.clip(ix, 0, elevation.shape[1] - 1)], 0.0)

    naive = best_per_call(by_hand, 5)
    print(f"height scan 4096x187 points: Terrain.height_at {ours * 1e3:.1f} ms, numpy gather by hand "
          f"{naive * 1e3:.1f} ms: ratio {ours / naive:.2f} (height_at also takes the higher cell on an edge)")


if __name__ == "__main__":
    main()
