"""Gazebo's physics (gz-physics 5, Debian's libignition-physics) on rse
worlds: builds `harness.cc`, drops seeded bodies on cell centres, and judges
where they came to rest. Used by tests/python/test_gz_physics.py and
bench/gz_physics.py."""

from __future__ import annotations

import glob
import json
import math
import subprocess
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
PACKAGES = [
    "ignition-physics5",
    "ignition-physics5-sdf",
    "ignition-physics5-mesh",
    "ignition-common4-graphics",
    "ignition-plugin1-loader",
    "ignition-math6-eigen3",
    "sdformat12",
]
# The engines gz-sim can load from Debian's packages.
ENGINES = ("dartsim", "bullet")
# A body off the top under it by more than this is a physics error, metres
# (as in bench/robots.py and the rapier smoke test).
TOLERANCE = 0.01
SPEED_LIMIT = 10.0
SPHERE_RADIUS = 0.03
BOX_HALF = 0.02


def build(out: Path) -> Path:
    """Compiles the harness into `out`; its path."""
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", *PACKAGES], capture_output=True, text=True, check=True)
    binary = out / "gz_harness"
    subprocess.run(
        ["g++", "-std=c++17", "-O2", str(HERE / "harness.cc"), "-o", str(binary), *flags.stdout.split()],
        check=True,
    )
    return binary


def plugin(engine: str) -> Path:
    """The engine's plugin library as Debian installs it."""
    found = sorted(glob.glob(f"/usr/lib/*/ign-physics-5/engine-plugins/libignition-physics-{engine}-plugin.so"))
    if not found:
        raise FileNotFoundError(f"no gz-physics 5 {engine} plugin: install libignition-physics5-{engine}-plugin5")
    return Path(found[0])


@dataclass(frozen=True)
class Drop:
    """A body dropped from `start` over the centre of cell `cell`: a sphere
    of radius `half` or a cube of half size `half`; `flat_z` is its start
    on a plane, `rest` where its centre must come to rest (the cell's top
    plus `half`)."""

    shape: str
    half: float
    start: tuple[float, float, float]
    flat_z: float
    cell: tuple[int, int]
    rest: float

    @property
    def line(self) -> str:
        """The harness's line for it: `sphere R X Y Z ZFLAT` or `box HX HY HZ X Y Z ZFLAT`."""
        size = [self.half] * (1 if self.shape == "sphere" else 3)
        return " ".join([self.shape, *map(repr, [*size, *self.start, self.flat_z])])


def drops(
    elevation: np.ndarray, block_size: float, count: int, seed: int, ramps: list[dict] | None = None
) -> list[Drop]:
    """`count` spheres and boxes (in turn) over distinct seeded cells, each
    5 cm above the top it must land on; the same bodies 5 cm above the
    ground for the flat control. Both fit inside a cell (radius 3 cm, half
    size 2 cm, cells of 5 cm half size), so they land on one top. Never
    over `ramps` (`Terrain.ramps`), and not beside one, where a body
    rolls or slides down a plane instead of resting (tested apart)."""
    ny, nx = elevation.shape
    rng = np.random.default_rng(seed)
    allowed = np.ones((ny, nx), dtype=bool)
    for ramp in ramps or []:
        x0, y0, x1, y1 = ramp["cells"]
        allowed[max(y0 - 1, 0) : y1 + 2, max(x0 - 1, 0) : x1 + 2] = False
    if allowed.all():
        # The draws of every terrain without ramps, as they always were.
        cells = rng.choice(nx * ny, size=min(count, nx * ny), replace=False)
    else:
        free = np.flatnonzero(allowed)
        cells = rng.choice(free, size=min(count, free.size), replace=False)
    out = []
    for i, c in enumerate(cells):
        y, x = divmod(int(c), nx)
        top = float(elevation[y, x])
        shape, half = ("sphere", SPHERE_RADIUS) if i % 2 == 0 else ("box", BOX_HALF)
        start = ((x + 0.5) * block_size, (y + 0.5) * block_size, top + half + 0.05)
        out.append(Drop(shape, half, start, half + 0.05, (x, y), top + half))
    return out


def run(harness: Path, engine: str, model_sdf: Path, bodies: list[Drop], seconds: float, flat: bool = False) -> dict:
    """Runs the harness; its JSON report."""
    listing = model_sdf.parent / "drops.txt"
    listing.write_text("".join(d.line + "\n" for d in bodies))
    args = [str(harness), str(plugin(engine)), str(model_sdf), str(listing), str(seconds)]
    done = subprocess.run(args + (["--flat"] if flat else []), capture_output=True, text=True)
    listing.unlink()
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(args)}: exit {done.returncode}\n{done.stderr}")
    return json.loads(done.stdout)


def errors(report: dict, bodies: list[Drop]) -> list[str]:
    """The physics errors in `report`: a body not finite, faster than
    10 m/s, or off the top it was dropped on by more than 1 cm."""
    found = []
    for i, ((x, y, z, speed), drop) in enumerate(zip(report["bodies"], bodies)):
        name = f"body {i} over cell {drop.cell}"
        if not all(math.isfinite(v) for v in (x, y, z, speed)):
            found.append(f"{name}: its state is not finite")
        elif speed > SPEED_LIMIT:
            found.append(f"{name}: {speed:.1f} m/s")
        elif abs(z - drop.rest) > TOLERANCE:
            found.append(f"{name}: rests at z = {z:.4f} m, its top puts it at {drop.rest:.4f} m")
    return found
