"""Spheres on the terrain's top-face diagonals in Gazebo classic 11: where
the single mesh's triangulation puts an interior edge across cells (and the
top is flat a sphere's width around it), spheres are placed, simulated in
the chroot's gzserver (gz11.py) and their displacement read back. Used by
tests/gazebo_classic/test_gzserver.py and bench/gazebo_classic_contacts.py."""

from __future__ import annotations

import json
import math
import random
import re
import time
from dataclasses import dataclass
from pathlib import Path

import gz11

# A sphere rolls at the least sideways push: the strictest body to rest.
RADIUS = 0.03
MASS = 0.05
SECONDS = 5.0
# Moved more than this (sideways, or sunk) in SECONDS: slid off its place.
SLID = 0.01


@dataclass(frozen=True)
class Sphere:
    x: float
    y: float
    top: float
    lift: float

    @property
    def z(self) -> float:
        return self.top + RADIUS + self.lift


def obj_diagonals(obj: Path) -> list[tuple[tuple[float, float, float], tuple[float, float, float]]]:
    """The interior edges of the mesh's upward faces that are not on a cell
    border: shared by two upward triangles, and neither along x nor y."""
    vertices: list[tuple[float, float, float]] = []
    normals: list[tuple[float, float, float]] = []
    edges: dict[tuple[int, int], int] = {}
    for line in obj.read_text().splitlines():
        if line.startswith("v "):
            vertices.append(tuple(float(v) for v in line.split()[1:4]))  # type: ignore[arg-type]
        elif line.startswith("vn "):
            normals.append(tuple(float(v) for v in line.split()[1:4]))  # type: ignore[arg-type]
        elif line.startswith("f "):
            corners = [c.split("/") for c in line.split()[1:]]
            if normals[int(corners[0][2]) - 1] != (0.0, 0.0, 1.0):
                continue
            ids = [int(c[0]) - 1 for c in corners]
            for a, b in zip(ids, ids[1:] + ids[:1]):
                key = (min(a, b), max(a, b))
                edges[key] = edges.get(key, 0) + 1
    return [
        (vertices[a], vertices[b])
        for (a, b), faces in edges.items()
        if faces == 2 and vertices[a][0] != vertices[b][0] and vertices[a][1] != vertices[b][1]
    ]


def heights(world: Path) -> list[list[int]]:
    return [[int(h) for h in line.split(",")] for line in (world / "heightmap.csv").read_text().split()]


def flat_around(grid: list[list[int]], block: float, x: float, y: float, h: int) -> bool:
    """Whether every cell a sphere's width (and a margin) around (x, y) has height `h`."""
    reach = RADIUS * 1.5
    for cy in range(int((y - reach) // block), int((y + reach) // block) + 1):
        for cx in range(int((x - reach) // block), int((x + reach) // block) + 1):
            if not (0 <= cy < len(grid) and 0 <= cx < len(grid[0])) or grid[cy][cx] != h:
                return False
    return True


def places(world: Path, count: int, seed: int) -> list[tuple[float, float, float, float, float]]:
    """Up to `count` midpoints of cross-cell top diagonals, flat around, 4
    radii apart: (x, y, top, and the diagonal's unit direction)."""
    block = json.loads((world / "rse.json").read_text())["globals"]["block_size"]
    grid = heights(world)
    found = []
    for a, b in obj_diagonals(world / "gazebo-classic" / "rse_terrain" / "meshes" / "terrain.obj"):
        x, y, z = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2, a[2]
        h = grid[int(y // block)][int(x // block)]
        if z > 0 and flat_around(grid, block, x, y, h):
            length = math.dist(a[:2], b[:2])
            found.append((x, y, z, (b[0] - a[0]) / length, (b[1] - a[1]) / length))
    random.Random(seed).shuffle(found)
    chosen: list[tuple[float, float, float, float, float]] = []
    for p in found:
        if all(math.dist(p[:2], q[:2]) >= 4 * RADIUS for q in chosen):
            chosen.append(p)
        if len(chosen) == count:
            break
    return chosen


def sphere_sdf(name: str, s: Sphere) -> str:
    inertia = 0.4 * MASS * RADIUS**2
    return f"""
    <model name="{name}">
      <pose>{s.x} {s.y} {s.z} 0 0 0</pose>
      <link name="body">
        <inertial>
          <mass>{MASS}</mass>
          <inertia><ixx>{inertia}</ixx><iyy>{inertia}</iyy><izz>{inertia}</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
        </inertial>
        <collision name="collision"><geometry><sphere><radius>{RADIUS}</radius></sphere></geometry></collision>
      </link>
    </model>"""


# Gazebo logs a state only when something moved: spheres that all rest
# would leave no state to read. A body with no collider, falling far from
# the terrain, moves every step.
TICKER = """
    <model name="ticker">
      <pose>-100 -100 1000 0 0 0</pose>
      <link name="body">
        <inertial><mass>1</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial>
      </link>
    </model>"""


def final_state(log: str) -> tuple[int, float, dict[str, tuple[float, float, float]]]:
    """The last state of a Gazebo state log: its iterations, simulated
    seconds per real second, and the position of each model's first link
    (written to 0.1 mm; the model's own pose only to 1 mm)."""
    last = log[log.rfind("<state ") :]
    iterations = re.search(r"<iterations>(\d+)</iterations>", last)
    sim = re.search(r"<sim_time>(\d+) (\d+)</sim_time>", last)
    real = re.search(r"<real_time>(\d+) (\d+)</real_time>", last)
    if not (iterations and sim and real):
        return 0, 0.0, {}
    seconds = [int(m[1]) + int(m[2]) * 1e-9 for m in (sim, real)]
    poses = {
        name: (float(x), float(y), float(z))
        for name, x, y, z in re.findall(r"<model name='([^']+)'><pose>[^<]*</pose><link name='[^']+'><pose>(\S+) (\S+) (\S+) ", last)
    }
    return int(iterations[1]), seconds[0] / max(seconds[1], 1e-9), poses


def run(root: Path, world: Path, spheres: list[Sphere], wait: float = 20.0) -> tuple[list[float], float]:
    """Each sphere's displacement after SECONDS of ODE at 1 kHz, and the
    real-time factor of the run (Gazebo's own clocks). gzserver runs
    uncapped for exactly that many iterations (`--iters`) and records its
    state; it does not exit when done, so it is stopped after `wait`
    seconds, and run again with twice the wait if it had not finished."""
    target = world / "gazebo-classic"
    text = (target / "rse.world").read_text()
    text = text.replace("<real_time_update_rate>1000</real_time_update_rate>", "<real_time_update_rate>0</real_time_update_rate>")
    bodies = "".join(sphere_sdf(f"s{i}", s) for i, s in enumerate(spheres)) + TICKER
    text = text.replace("</world>", bodies + "\n  </world>")
    (target / "bench.world").write_text(text)
    iterations = round(SECONDS / 0.001)
    extra = ("--iters", str(iterations), "--record_period", "1")
    with gz11.staged(root, target) as inside:
        with gz11.Gzserver(root, inside, "bench.world", record=True, extra=extra) as server:
            time.sleep(wait)
        done, factor, poses = final_state(server.recorded())
    if done < iterations:
        if wait > 300:
            raise TimeoutError(f"gzserver ran {done} of {iterations} iterations in {wait} s:\n{server.log}")
        return run(root, world, spheres, wait * 2)
    moved = []
    for i, s in enumerate(spheres):
        x, y, z = poses[f"s{i}"]
        sideways = math.hypot(x - s.x, y - s.y)
        sank = max(0.0, s.top + RADIUS - z)
        moved.append(max(sideways, sank))
    return moved, factor
