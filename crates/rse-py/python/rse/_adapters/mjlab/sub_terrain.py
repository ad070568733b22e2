"""``RseTerrainCfg``: rse as an mjlab sub-terrain (``rse.mjlab``'s
documentation says how it is used): each tile rse's box set and ramp
wedges on a ground slab, with its spawn origin and flat patches."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

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
