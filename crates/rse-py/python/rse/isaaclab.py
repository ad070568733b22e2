"""rse as an Isaac Lab sub-terrain: ``RseTerrainCfg`` for
``isaaclab.terrains.TerrainGeneratorCfg.sub_terrains``, and its function
``rse_terrain(difficulty, cfg) -> (meshes, origin)``.

Importable without Isaac Lab: with ``isaaclab`` installed, ``RseTerrainCfg``
is a ``configclass`` subclass of ``SubTerrainBaseCfg``; without it, a
dataclass with the same fields, so configurations can be written and tested
anywhere::

    from isaaclab.terrains import TerrainGeneratorCfg
    from rse.isaaclab import RseTerrainCfg

    TERRAIN = TerrainGeneratorCfg(
        size=(8.0, 8.0), num_rows=10, num_cols=20, curriculum=True,
        horizontal_scale=0.1, vertical_scale=0.005, slope_threshold=None,
        sub_terrains={"stepfield": RseTerrainCfg(scheme="schemes/six_obstacles.csv")},
    )

The contract (Isaac Lab's ``SubTerrainBaseCfg``): the meshes span
``(0, 0)``–``cfg.size`` in metres, Z up, and the origin has shape ``(3,)``.
The scheme's grid is fitted to ``cfg.size`` (``rse._fit.fit``: blocks keep
their size). Isaac Lab passes the generator-wide seed (``cfg.seed``) and a
difficulty, not a tile number, so the tile's world index is derived from the
seed, the difficulty and the scheme (``rse._fit.tile_index``): the same
configuration gives the same terrains. A difficulty outside ``[0, 1]`` is
refused, as the library refuses it (keep ``difficulty_range`` inside it).
Give the scheme as a path: Isaac Lab hashes the configuration.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Optional

import numpy as np

from rse._fit import TileFields, fit, framework_class, load, tile_index


def rse_terrain(difficulty: float, cfg: Any) -> tuple[list[Any], np.ndarray]:
    """One tile: rse's closed terrain mesh plus a ground slab under the
    whole tile (cells of height 0 have no mesh of their own), and the spawn
    origin: the tile's centre on the highest top within
    ``cfg.spawn_radius``."""
    import trimesh

    if cfg.scheme is None:
        raise ValueError("RseTerrainCfg.scheme: give a scheme file (or rse.Scheme)")
    scheme = fit(load(cfg.scheme), tuple(cfg.size))
    d = float(difficulty)
    index = tile_index(getattr(cfg, "seed", None), d, scheme.to_csv()) if cfg.index is None else cfg.index
    # The library takes the seed's default and refuses a difficulty out of
    # 0..1 (Isaac Lab's difficulty_range must stay inside it).
    terrain = scheme.generate(seed=cfg.rse_seed, index=index, difficulty=d)
    meshes = []
    vertices, faces = terrain.mesh()
    if len(faces):
        meshes.append(trimesh.Trimesh(vertices.astype(np.float64), faces, process=False))
    sx, sy = cfg.size
    ground = trimesh.creation.box(extents=(sx, sy, cfg.ground_thickness))
    ground.apply_translation((sx / 2, sy / 2, -cfg.ground_thickness / 2))
    meshes.append(ground)
    return meshes, np.asarray(terrain.spawn_origin(cfg.spawn_radius), dtype=np.float64)


_SubTerrainBaseCfg = framework_class("isaaclab.terrains", "SubTerrainBaseCfg", "rse.isaaclab")


if _SubTerrainBaseCfg is not None:  # pragma: no cover - needs Isaac Lab
    from isaaclab.utils import configclass as _configclass

    @_configclass
    class RseTerrainCfg(_SubTerrainBaseCfg, TileFields):  # type: ignore[misc,valid-type]
        """An rse stepfield tile (see the module's documentation)."""

        function = rse_terrain

else:

    @dataclass
    class RseTerrainCfg(TileFields):  # type: ignore[no-redef]
        """An rse stepfield tile with the fields of Isaac Lab's
        ``SubTerrainBaseCfg`` (see the module's documentation)."""

        function: Callable[[float, Any], tuple[list[Any], np.ndarray]] = rse_terrain
        proportion: float = 1.0
        size: tuple[float, float] = (10.0, 10.0)
        flat_patch_sampling: Optional[dict[str, Any]] = None
        seed: Optional[int] = None
        """Set by Isaac Lab's generator to its own seed."""


__all__ = ["RseTerrainCfg", "rse_terrain"]
