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
The scheme's grid is fitted to ``cfg.size`` (``rse._adapters.tiles.fit``: blocks keep
their size). Isaac Lab passes the generator-wide seed (``cfg.seed``) and a
difficulty, not a tile number, so the tile's world index is derived from the
seed, the difficulty and the scheme (``rse._adapters.tiles.tile_index``): the same
configuration gives the same terrains. A difficulty outside ``[0, 1]`` is
refused, as the library refuses it (keep ``difficulty_range`` inside it).
Give the scheme as a path: Isaac Lab hashes the configuration.

``use_stepfield(env_cfg, scheme)`` puts a registered Isaac Lab task (e.g.
``Isaac-Velocity-Rough-UnitreeGo2``'s config) on rse tiles in one call: the
task's terrain generator keeps its grid, curriculum and importer, and its
sub-terrains become rse's. Many processes (``torchrun``, Isaac Lab's
``--distributed``): each process's tiles differ by its rank, read from
``RANK`` (explicit ``rank`` wins); rank 0 draws what one process draws.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Callable, Optional

import numpy as np

from rse._adapters.tiles import TileFields, framework_class, launcher_rank, tile_index, tile_terrain


def rse_terrain(difficulty: float, cfg: Any) -> tuple[list[Any], np.ndarray]:
    """One tile: rse's closed terrain mesh plus a ground slab under the
    whole tile (cells of height 0 have no mesh of their own), and the spawn
    origin: the tile's centre on the highest top within
    ``cfg.spawn_radius``."""
    import trimesh

    d = float(difficulty)
    rank_salt = _rank_salt(getattr(cfg, "rank", None))
    _, terrain = tile_terrain(cfg, d, lambda scheme: tile_index(getattr(cfg, "seed", None), d, scheme.to_csv() + rank_salt))
    meshes = []
    vertices, faces = terrain.mesh()
    if len(faces):
        meshes.append(trimesh.Trimesh(vertices.astype(np.float64), faces, process=False))
    sx, sy = cfg.size
    ground = trimesh.creation.box(extents=(sx, sy, cfg.ground_thickness))
    ground.apply_translation((sx / 2, sy / 2, -cfg.ground_thickness / 2))
    meshes.append(ground)
    return meshes, np.asarray(terrain.spawn_origin(cfg.spawn_radius), dtype=np.float64)


def _rank_salt(rank: Optional[int]) -> str:
    """What a rank adds to a tile's world index: nothing for rank 0 (one
    process draws as it always did), the rank otherwise. ``None``: the
    launcher's."""
    rank = launcher_rank() if rank is None else int(rank)
    if rank < 0:
        raise ValueError(f"RseTerrainCfg.rank: {rank} is not a process rank (an integer from 0)")
    return "" if rank == 0 else f"#rank {rank}"


def use_stepfield(env_cfg: Any, scheme: Any, *, rank: Optional[int] = None, **tile: Any) -> Any:
    """Puts an Isaac Lab task on rse tiles: the terrain generator of
    ``env_cfg.scene.terrain`` keeps its grid (``size``, ``num_rows``,
    ``num_cols``), its seed, its curriculum and ``terrain_levels``, and its
    sub-terrains become one ``RseTerrainCfg`` of ``scheme`` (a path;
    ``tile`` sets its other fields, e.g. ``spawn_radius``). Every other
    term of the task is kept. ``rank`` (default: ``RANK``, as ``torchrun``
    and ``--distributed`` launch) makes each process draw other tiles.
    Returns ``env_cfg``, changed in place; a task without a generated
    terrain is a ``ValueError`` naming the field."""
    terrain = getattr(getattr(env_cfg, "scene", None), "terrain", None)
    if terrain is None:
        raise ValueError("env_cfg.scene.terrain: the task has no terrain to replace (give it a TerrainImporterCfg)")
    if getattr(terrain, "terrain_type", None) != "generator" or getattr(terrain, "terrain_generator", None) is None:
        raise ValueError(
            f"env_cfg.scene.terrain.terrain_type: {getattr(terrain, 'terrain_type', None)!r}; rse's tiles come "
            'through a terrain generator: set terrain_type="generator" and a terrain_generator (TerrainGeneratorCfg)'
        )
    if not isinstance(scheme, (str, os.PathLike)):
        raise ValueError("scheme: give a path to the scheme file (Isaac Lab hashes the configuration)")
    rank = launcher_rank() if rank is None else rank
    # Either class of the two below (mypy sees the first only).
    tile_cfg: Any = RseTerrainCfg
    terrain.terrain_generator.sub_terrains = {"stepfield": tile_cfg(proportion=1.0, scheme=os.fspath(scheme), rank=rank, **tile)}
    return env_cfg


_SubTerrainBaseCfg = framework_class("isaaclab.terrains", "SubTerrainBaseCfg", "rse.isaaclab")


if _SubTerrainBaseCfg is not None:  # pragma: no cover - needs Isaac Lab
    from isaaclab.utils import configclass as _configclass

    @_configclass
    class RseTerrainCfg(_SubTerrainBaseCfg, TileFields):  # type: ignore[misc,valid-type]
        """An rse stepfield tile (see the module's documentation)."""

        function = rse_terrain
        rank: Optional[int] = None
        """The process's rank, mixed into the tiles' world indices (0 or
        None without a launcher: as one process draws)."""

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
        rank: Optional[int] = None
        """The process's rank, mixed into the tiles' world indices (0 or
        None without a launcher: as one process draws)."""


__all__ = ["RseTerrainCfg", "launcher_rank", "rse_terrain", "use_stepfield"]
