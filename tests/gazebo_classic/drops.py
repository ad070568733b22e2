"""Spheres on the terrain's top-face diagonals in Gazebo classic 11: where
the single mesh's triangulation puts an interior edge across cells (and the
top is flat a sphere's width around it), spheres are placed, simulated in
the chroot's gzserver (gz11.py) and their displacement read back. Used by
tests/gazebo_classic/test_gzserver.py and bench/gazebo_classic_contacts.py."""

from __future__ import annotations

import json
import math
import random
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


def run(root: Path, world: Path, spheres: list[Sphere]) -> tuple[list[float], float]:
    """Each sphere's displacement after SECONDS, and the real-time factor."""
    target = world / "gazebo-classic"
    text = (target / "rse.world").read_text()
    text = text.replace("<real_time_update_rate>1000</real_time_update_rate>", "<real_time_update_rate>0</real_time_update_rate>")
    text = text.replace("</world>", "".join(sphere_sdf(f"s{i}", s) for i, s in enumerate(spheres)) + "\n  </world>")
    (target / "bench.world").write_text(text)
    with gz11.staged(root, target) as inside, gz11.Gzserver(root, inside, "bench.world", paused=True) as server:
        server.wait_loaded()
        start = time.monotonic()
        server.gz("world", "-p", "0")
        while (server.sim_time() or 0.0) < SECONDS:
            time.sleep(0.2)
        server.gz("world", "-p", "1")
        sim = server.sim_time() or 0.0
        factor = sim / (time.monotonic() - start)
        moved = []
        for i, s in enumerate(spheres):
            x, y, z = (float(v) for v in server.gz("model", "-m", f"s{i}", "-p", timeout=10).split()[:3])
            sideways = math.hypot(x - s.x, y - s.y)
            sank = max(0.0, s.top + RADIUS - z)
            moved.append(max(sideways, sank))
    return moved, factor
