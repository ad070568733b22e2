"""rse as an mjlab sub-terrain: ``RseTerrainCfg`` for
``mjlab.terrains.TerrainGeneratorCfg.sub_terrains``.

Its ``function(difficulty, spec, rng)`` adds rse's box set (one static
box geom per rectangle of equal height, the collider MuJoCo handles best)
and a ground slab under the tile to ``spec.body("terrain")``, in the tile's
frame (corner at the origin, Z up; mjlab moves the geoms into place), and
returns mjlab's ``TerrainOutput`` with the spawn origin and flat patches.

Importable without mjlab: with ``mjlab`` installed, ``RseTerrainCfg`` is a
subclass of ``mjlab.terrains.SubTerrainCfg``; without it, a dataclass with
the same fields (``function`` then needs mjlab)::

    from mjlab.terrains import TerrainGeneratorCfg
    from rse.mjlab import RseTerrainCfg

    TERRAIN = TerrainGeneratorCfg(
        size=(8.0, 8.0), num_rows=10, num_cols=2, curriculum=True,
        sub_terrains={"stepfield": RseTerrainCfg(scheme="schemes/six_obstacles.csv")},
    )

The scheme's grid is fitted to the tile's ``size`` (blocks keep their size;
``rse._adapters.tiles.fit``). mjlab hands each tile its generator's seeded ``rng``: the
tile's world index is drawn from it, so the same configuration and seed
give the same terrains. Flat patches are rse's (deterministic, spread out,
flat within ``max_height_diff`` rounded down to whole steps), filtered by
the ranges of each ``FlatPatchSamplingCfg``.

Every env its own terrain, new every episode (``use_env_terrains`` and its
terms) lives in ``rse._adapters.mjlab``, one module a job, and is
re-exported here.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from rse._adapters.mjlab.config import use_env_terrains
from rse._adapters.mjlab.curriculum import terrain_difficulty
from rse._adapters.mjlab.event import TERM, EnvTerrainsEvent, contact_sheet, env_terrains
from rse._adapters.mjlab.pool import BODY, add_pool
from rse._adapters.mjlab.terms import bound_near_robots, exact_height_scan, out_of_slot
from rse._adapters.tiles import TileFields, framework_class, max_step, patches_in_ranges, tile_terrain


def _function(cfg: Any, difficulty: float, spec: Any, rng: np.random.Generator) -> Any:
    import mujoco
    from mjlab.terrains.terrain_generator import TerrainGeometry, TerrainOutput

    scheme, terrain = tile_terrain(cfg, difficulty, lambda _: rng.integers(0, 2**62))
    body = spec.body("terrain")
    geometries = []
    sx, sy = cfg.size
    t = cfg.ground_thickness
    ground = body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=(sx / 2, sy / 2, t / 2), pos=(sx / 2, sy / 2, -t / 2))
    geometries.append(TerrainGeometry(geom=ground, color=(0.5, 0.5, 0.5, 1.0)))
    top = max(float(terrain.elevation.max()), 1e-9)
    for cx, cy, cz, hx, hy, hz in terrain.boxes():
        geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=(hx, hy, hz), pos=(cx, cy, cz))
        shade = 0.3 + 0.6 * (cz + hz) / top
        geometries.append(TerrainGeometry(geom=geom, color=(shade, 0.45, 1.0 - shade, 1.0)))
    # Each ramp's wedge over its staircase of boxes: convex, so MuJoCo
    # collides with it exactly as a mesh geom (as the world files do).
    for corners in terrain.wedges():
        mesh = spec.add_mesh(name=f"rse_ramp_{len(spec.meshes)}", uservert=corners.ravel().tolist())
        geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=mesh.name)
        geometries.append(TerrainGeometry(geom=geom, color=(0.9, 0.45, 0.1, 1.0)))
    flat_patches = None
    if cfg.flat_patch_sampling:
        flat_patches = {}
        for name, p in cfg.flat_patch_sampling.items():
            # A margin of candidates, so that the ranges can drop some.
            found = terrain.flat_patches(4 * p.num_patches, p.patch_radius, max_step(scheme, p.max_height_diff))
            flat_patches[name] = patches_in_ranges(found, p.num_patches, p.x_range, p.y_range, p.z_range)
    origin = np.asarray(terrain.spawn_origin(cfg.spawn_radius), dtype=np.float64)
    return TerrainOutput(origin=origin, geometries=geometries, flat_patches=flat_patches)


_SubTerrainCfg = framework_class("mjlab.terrains.terrain_generator", "SubTerrainCfg", "rse.mjlab")


if _SubTerrainCfg is not None:  # pragma: no cover

    @dataclass(kw_only=True)
    class RseTerrainCfg(_SubTerrainCfg, TileFields):  # type: ignore[misc,valid-type]
        """An rse stepfield tile (see the module's documentation)."""

        def function(self, difficulty: float, spec: Any, rng: np.random.Generator) -> Any:
            return _function(self, difficulty, spec, rng)

else:

    @dataclass
    class RseTerrainCfg(TileFields):  # type: ignore[no-redef]
        """An rse stepfield tile with the fields of mjlab's ``SubTerrainCfg``
        (see the module's documentation)."""

        proportion: float = 1.0
        size: tuple[float, float] = (10.0, 10.0)
        flat_patch_sampling: Optional[dict[str, Any]] = None

        def function(self, difficulty: float, spec: Any, rng: np.random.Generator) -> Any:
            return _function(self, difficulty, spec, rng)


__all__ = [
    "BODY",
    "TERM",
    "EnvTerrainsEvent",
    "RseTerrainCfg",
    "add_pool",
    "bound_near_robots",
    "contact_sheet",
    "env_terrains",
    "exact_height_scan",
    "out_of_slot",
    "terrain_difficulty",
    "use_env_terrains",
]
