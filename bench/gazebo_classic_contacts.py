"""Do bodies resting on an interior edge of the terrain's top faces slide in
Gazebo classic 11's ODE? Measured in the real gzserver (a Debian bullseye
chroot, tests/gazebo_classic/gz11.py; needs root), for the classic target's
colliders side by side in the same run: the single mesh and the box set.

Spheres (the body that rolls at the least sideways push) are placed on the
midpoints of the mesh's interior top-face edges that cut across cells (the
diagonals of its triangulation), where the top is flat for a sphere's width
around them: once resting exactly (centre one radius above the top) and once
dropped from 2 cm. The box-set world gets spheres at the very same points.
After 5 s of simulated time (ODE, 1 kHz, uncapped: `--iters 5000`, poses
read from Gazebo's state log) a sphere whose centre moved more than 1 cm
sideways, or sank 1 cm, has slid off its place. The control: the same
spheres on the mesh half a radius beside the diagonal, inside one face.

    sudo python3 bench/gazebo_classic_contacts.py [--worlds 5] [--spheres 20]

Prints, per scheme and collider, how many spheres slid and the worst
displacement, and the mean real-time factor of the runs (simulated seconds
per real second, Gazebo's own clocks; the spheres are most of the work)."""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "gazebo_classic"))
import gz11  # noqa: E402
from drops import RADIUS, SECONDS, SLID, Sphere, places, run  # noqa: E402

# Sizes of the paper's Table 3 (random blocks), and the benchmark scheme.
SCHEMES = {
    "random 10x10": "# size: 10x10\n# block_size: 0.1\n# step_height: 0.05\ntype,height\nrandom,4\n",
    "random 15x60": "# size: 15x60\n# block_size: 0.1\n# step_height: 0.05\ntype,height\nrandom,4\n",
    "six_obstacles 50x50": (REPO / "schemes" / "six_obstacles.csv").read_text(),
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--worlds", type=int, default=5, help="worlds of each scheme (indices 0..N-1)")
    parser.add_argument("--spheres", type=int, default=20, help="spheres per world")
    parser.add_argument("--only", default="", help="the schemes whose label holds this text (e.g. 15x60)")
    parser.add_argument("--rse-gen", default=str(REPO / "target" / "release" / "rse-gen"))
    parser.add_argument("--root", type=Path, default=gz11.DEFAULT_ROOT, help="the Gazebo 11 chroot (made if missing)")
    args = parser.parse_args()
    root = gz11.ensure_root(args.root)
    print(f"Gazebo {gz11.gazebo_version(root)} (ODE, 1 kHz, uncapped), spheres r={RADIUS} m, {SECONDS} s; slid = moved > {SLID} m")
    print(f"{'scheme':<22}{'collider':<7}{'where':<9}{'start':<16}{'slid':>8}{'worst (m)':>11}{'RTF':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        for label, csv in SCHEMES.items():
            if args.only not in label:
                continue
            scheme = Path(tmp) / (label.replace(" ", "_") + ".csv")
            scheme.write_text(csv)
            for mesh in ("single", "blocks"):
                out = Path(tmp) / f"{scheme.stem}_{mesh}"
                subprocess.run(
                    [args.rse_gen, "batch", str(scheme), "-o", str(out), "--amount", str(args.worlds),
                     "--target", "gazebo-classic", "--mesh", mesh],
                    check=True,
                )
            # (collider, where, start): the mesh and the boxes with spheres on
            # the diagonals; the control, the mesh with them half a radius
            # beside the diagonal, inside one face.
            for mesh, where, lift in (
                ("single", "on edge", 0.0),
                ("single", "beside", 0.0),
                ("blocks", "on edge", 0.0),
                ("single", "on edge", 0.02),
                ("blocks", "on edge", 0.02),
            ):
                slid = total = 0
                worst = 0.0
                factors = []
                for index in range(args.worlds):
                    name = f"world_{index:04d}"
                    # The same points on both colliders: found on the mesh's diagonals.
                    points = places(Path(tmp) / f"{scheme.stem}_single" / name, args.spheres, seed=index)
                    aside = RADIUS / 2 if where == "beside" else 0.0
                    spheres = [Sphere(x - dy * aside, y + dx * aside, z, lift) for x, y, z, dx, dy in points]
                    moved, factor = run(root, Path(tmp) / f"{scheme.stem}_{mesh}" / name, spheres)
                    slid += sum(m > SLID for m in moved)
                    total += len(moved)
                    worst = max([worst, *moved])
                    factors.append(factor)
                collider = "mesh" if mesh == "single" else "boxes"
                start = "resting" if lift == 0 else f"dropped {lift * 100:.0f} cm"
                rtf = sum(factors) / len(factors)
                print(
                    f"{label:<22}{collider:<7}{where:<9}{start:<16}{f'{slid}/{total}':>8}{worst:>11.4f}{rtf:>7.1f}",
                    flush=True,
                )

if __name__ == "__main__":
    main()
