"""Gazebo's own physics on rse terrains: gz-physics 5 from Debian,
the terrain model built as gz-sim's Physics system builds it
(tests/gz_physics/harness.cc), 60 seeded bodies dropped on cell centres,
5 s at 1 kHz; per engine and collider the steps per second as a ratio to
the same bodies on a plane (as bench/robots.py), and the bodies off their
top by more than 1 cm. Printed, not
asserted (tests/python/test_gz_physics.py asserts the errors).

Terrains: the paper's sizes 10x10, 15x60 and 50x50 (random 0..2 steps under
a gaussian of 3), a random 50x50 field of height 4, and `six_obstacles`.

Run: .venv/bin/python bench/gz_physics.py [--repeats R]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
from pathlib import Path

import rse

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "gz_physics"))
import gz  # noqa: E402


def fields() -> list[tuple[str, rse.Scheme]]:
    paper = [rse.Obstacle("random", height=2), rse.Obstacle("gaussian", height=3)]
    out = [(f"{nx}x{ny}", rse.Scheme(paper, size=(nx, ny))) for nx, ny in [(10, 10), (15, 60), (50, 50)]]
    out.append(("random H4 50x50", rse.Scheme([rse.Obstacle("random", height=4)], size=(50, 50))))
    out.append(("six_obstacles", rse.Scheme.load(REPO / "schemes" / "six_obstacles.csv")))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--bodies", type=int, default=60)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        harness = gz.build(Path(tmp))
        print("gz-physics 5: steps/s on the RSE as a ratio to a plane, median [min-max] "
              f"of {args.repeats}; bodies off their top by > 1 cm; terrain collisions")  # fmt: skip
        for name, scheme in fields():
            terrain = scheme.generate(index=0)
            bodies = gz.drops(terrain.elevation, terrain.block_size, args.bodies, seed=7)
            for mesh in ("single", "blocks"):
                out = Path(tmp) / f"{name}-{mesh}".replace(" ", "_")
                rse.write_worlds(scheme, out, amount=1, targets="gazebo", mesh=mesh)
                model = out / "world_0000" / "gazebo" / "rse_terrain" / "model.sdf"
                shapes = 1 if mesh == "single" else len(terrain.boxes())
                for engine in gz.ENGINES:
                    ratios, errors = [], 0
                    for _ in range(args.repeats):
                        report = gz.run(harness, engine, model, bodies, seconds=5.0, flat=True)
                        ratios.append(report["flat_step_us"] / report["step_us"])
                        errors = max(errors, len(gz.errors(report, bodies)))
                    collider = "mesh" if mesh == "single" else "boxes"
                    print(f"  {name:16s} {engine:8s} {collider:6s} {statistics.median(ratios):5.2f}x "
                          f"[{min(ratios):.2f}-{max(ratios):.2f}]  errors {errors:2d}  shapes {shapes}",
                          flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
