"""Box counts of the block model: rse's cover (`Terrain.boxes()`,
boxes that may overlap inside the solid) beside the partition into
rectangles of equal height it replaced (re-implemented here as the
baseline: greedy, along x then y, the pre-0.1 `rse-core` algorithm) and a
box per cell, for worlds 0-4 of every sample and a random 50x50 field of
height 4. With `--optimum`, also the fewest boxes any cover standing on the
ground can have, for world 0, from an exact integer program over every
maximal rectangle (needs scipy: its HiGHS solver).

Run: .venv/bin/python bench/boxes.py [--optimum]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import rse

REPO = Path(__file__).resolve().parents[1]


def levels(terrain: rse.Terrain) -> np.ndarray:
    """Level of each cell's top, 0 where there is no solid (as rse-core's)."""
    h = np.asarray(terrain.heights).astype(int)
    return h + 1 if terrain.base > 0 else h


def partition(lv: np.ndarray) -> int:
    """Rectangles of equal level, grown along x then y (the baseline)."""
    ny, nx = lv.shape
    used = np.zeros(lv.shape, bool)
    count = 0
    for y in range(ny):
        x = 0
        while x < nx:
            v = lv[y, x]
            if used[y, x] or v == 0:
                x += 1
                continue
            x1 = x + 1
            while x1 < nx and not used[y, x1] and lv[y, x1] == v:
                x1 += 1
            y1 = y + 1
            while y1 < ny and not used[y1, x:x1].any() and (lv[y1, x:x1] == v).all():
                y1 += 1
            used[y:y1, x:x1] = True
            count += 1
            x = x1
    return count


def optimum(lv: np.ndarray) -> int:
    """The fewest boxes of any exact ground-standing cover: per level, the
    fewest rectangles of cells at least that high holding every cell of
    exactly that level, over every maximal rectangle (an exact set cover)."""
    from scipy.optimize import Bounds, LinearConstraint, milp
    from scipy.sparse import lil_matrix

    ny, nx = lv.shape
    total = 0
    for level in sorted(set(lv.flat) - {0}):
        allowed = lv >= level
        exact = {(int(y), int(x)): i for i, (y, x) in enumerate(zip(*np.nonzero(lv == level)))}
        rects = set()
        for y, x in exact:
            x0, x1 = x, x + 1
            while x0 > 0 and allowed[y, x0 - 1]:
                x0 -= 1
            while x1 < nx and allowed[y, x1]:
                x1 += 1
            for a in range(x0, x + 1):
                for b in range(x + 1, x1 + 1):
                    y0, y1 = y, y + 1
                    while y0 > 0 and allowed[y0 - 1, a:b].all():
                        y0 -= 1
                    while y1 < ny and allowed[y1, a:b].all():
                        y1 += 1
                    rects.add((a, y0, b, y1))
        rects = sorted(rects)
        cover = lil_matrix((len(exact), len(rects)))
        for j, (a, y0, b, y1) in enumerate(rects):
            for yy in range(y0, y1):
                for xx in range(a, b):
                    if (yy, xx) in exact:
                        cover[exact[(yy, xx)], j] = 1
        ones = np.ones(len(rects))
        result = milp(ones, constraints=LinearConstraint(cover.tocsr(), lb=1), integrality=ones, bounds=Bounds(0, 1))
        total += round(result.fun)
    return total


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--optimum", action="store_true", help="also the exact minimum for world 0 (scipy)")
    args = parser.parse_args()
    fields = [(p.stem, rse.Scheme.load(p)) for p in sorted((REPO / "schemes").glob("*.csv"))]
    fields.append(("random H4 50x50", rse.Scheme([rse.Obstacle("random", height=4)], size=(50, 50))))
    print("boxes, mean of worlds 0-4: cover (rse) / partition (baseline) = ratio; a box per cell"
          + ("; world 0: cover / fewest possible" if args.optimum else ""))  # fmt: skip
    for name, scheme in fields:
        terrains = [scheme.generate(index=i) for i in range(5)]
        cover = np.mean([len(t.boxes()) for t in terrains])
        base = np.mean([partition(levels(t)) for t in terrains])
        cells = np.mean([np.count_nonzero(levels(t)) for t in terrains])
        line = f"  {name:22s} {cover:8.1f} / {base:8.1f} = {cover / base:4.2f}x; {cells:7.0f}"
        if args.optimum:
            line += f"; {len(terrains[0].boxes())} / {optimum(levels(terrains[0]))}"
        print(line, flush=True)


if __name__ == "__main__":
    main()
