"""What the sub-terrain adapters (rse.isaaclab, rse.mjlab) share: the
fields of their sub-terrain configs, the tile prologue (a scheme fitted to
a sub-terrain's size, the tile's terrain), the world index a tile draws,
flat patches in a framework's terms, the launcher's rank, and a
framework's class when it is installed. Pure Python over ``rse._rse``; no
framework is imported here."""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import math
import os
import struct
import warnings
from dataclasses import dataclass
from typing import Any, Optional, Union

import numpy as np

from rse._rse import Scheme, Terrain

SchemeLike = Union[Scheme, str, "os.PathLike[str]"]


@dataclass
class TileFields:
    """The fields rse adds to a framework's sub-terrain config, declared
    once for ``rse.isaaclab.RseTerrainCfg`` and ``rse.mjlab.RseTerrainCfg``
    (each the framework's class with these mixed in, or without the
    framework a plain dataclass with them and the framework's own)."""

    scheme: Optional[SchemeLike] = None
    """The scheme: a path to its file, or an ``rse.Scheme`` (give a path in
    Isaac Lab, which hashes the configuration)."""
    rse_seed: Optional[int] = None
    """rse's base seed (``seed`` is the framework's); default the scheme's
    ``# seed:``."""
    index: Optional[int] = None
    """A fixed world index for every tile; default one per tile."""
    spawn_radius: Optional[float] = None
    """Metres around the centre whose highest top is the origin's z;
    default ``rse.DEFAULT_SPAWN_RADIUS``."""
    ground_thickness: float = 1.0
    """Thickness of the ground slab under the tile, metres."""


def load(scheme: SchemeLike) -> Scheme:
    """A ``Scheme`` as given, or loaded from a path."""
    return scheme if isinstance(scheme, Scheme) else Scheme.load(scheme)


def fit(scheme: Scheme, size: tuple[float, float]) -> Scheme:
    """``scheme`` with its grid fitted to ``size`` metres: as many cells of
    the scheme's own block size as fit (``floor(size / block_size)``, at
    least 1), pallets off. The blocks keep their physical size (a stepfield
    is 10 cm blocks, whatever the tile); a scheme that already spans
    ``size`` exactly is returned as it is, pallet frames and all. Obstacles
    at fixed cells outside the fitted grid raise ``rse.SchemeError``."""
    s = scheme.block_size
    nx, ny = (max(1, math.floor(extent / s + 1e-9)) for extent in size)
    if scheme.grid == (nx, ny):
        return scheme
    # Every other global is kept as the scheme has it (no keyword list to
    # fall behind a new option).
    return scheme.replace(pallets=None, size=(nx, ny))


def tile_terrain(cfg: Any, difficulty: float, index: Any) -> tuple[Scheme, Terrain]:
    """The prologue of every sub-terrain function: ``cfg``'s scheme (a
    ``TileFields``; ``ValueError`` naming ``RseTerrainCfg.scheme`` when
    there is none) fitted to ``cfg.size``, and its terrain at ``difficulty``
    for world ``index`` (``cfg.index`` when set; a callable is given the
    fitted scheme) of ``cfg.rse_seed`` (default the scheme's). The library
    refuses a difficulty out of 0..1 (the framework's difficulty_range must
    stay inside it)."""
    if cfg.scheme is None:
        raise ValueError("RseTerrainCfg.scheme: give a scheme file (or rse.Scheme)")
    scheme = fit(load(cfg.scheme), tuple(cfg.size))
    if cfg.index is not None:
        index = cfg.index
    elif callable(index):
        index = index(scheme)
    return scheme, scheme.generate(seed=cfg.rse_seed, index=int(index), difficulty=float(difficulty))


def tile_index(seed: Optional[int], difficulty: float, salt: str = "") -> int:
    """The world index a tile draws when the framework gives only a seed and
    a difficulty (Isaac Lab): the first 8 bytes of SHA-256 over the seed,
    the difficulty's IEEE bits and ``salt``, below 2**63. The same
    configuration gives the same terrains; two tiles whose difficulties
    differ (Isaac Lab jitters every curriculum tile's) draw different ones."""
    key = struct.pack("<qd", -1 if seed is None else int(seed), float(difficulty)) + salt.encode()
    return int.from_bytes(hashlib.sha256(key).digest()[:8], "little") >> 1


def launcher_rank() -> int:
    """This process's rank as a launcher of one process per GPU sets it in
    ``RANK`` (``torchrun``, mjlab's torchrunx, Isaac Lab's
    ``--distributed``); 0 without one. A value that is not a rank is a
    ``ValueError`` naming ``RANK``."""
    rank = os.environ.get("RANK", "0")
    try:
        value = int(rank)
    except ValueError:
        value = -1
    if value < 0:
        raise ValueError(f"RANK: {rank!r} is not a process rank (an integer from 0)")
    return value


def max_step(scheme: Scheme, max_height_diff: float) -> int:
    """A height tolerance in metres as whole steps (rounded down)."""
    return max(0, math.floor(max_height_diff / scheme.step_height + 1e-9))


def patches_in_ranges(
    points: np.ndarray,
    count: int,
    x_range: tuple[float, float] = (-1e6, 1e6),
    y_range: tuple[float, float] = (-1e6, 1e6),
    z_range: tuple[float, float] = (-1e6, 1e6),
) -> np.ndarray:
    """The first ``count`` of ``points`` (NaN rows dropped) inside the ranges."""
    points = points[~np.isnan(points[:, 0])]
    keep = (
        (points[:, 0] >= x_range[0])
        & (points[:, 0] <= x_range[1])
        & (points[:, 1] >= y_range[0])
        & (points[:, 1] <= y_range[1])
        & (points[:, 2] >= z_range[0])
        & (points[:, 2] <= z_range[1])
    )
    return points[keep][:count]


def framework_class(module: str, name: str, adapter: str) -> Any:
    """``module.name`` from an RL framework, or ``None`` when the framework
    is not installed (the adapter then offers a plain dataclass with the
    same fields). A framework that is installed but fails to import (Isaac
    Lab without Isaac Sim, a broken torch) is not hidden: a
    ``RuntimeWarning`` says why, naming the adapter that falls back."""
    top = module.split(".")[0]
    try:
        return getattr(importlib.import_module(module), name)
    except ImportError as e:
        if importlib.util.find_spec(top) is None:
            return None
        warnings.warn(
            f"{adapter}: {top} is installed but `{module}` failed to import ({e}); "
            f"{adapter}.RseTerrainCfg is a plain dataclass, not a `{name}`",
            RuntimeWarning,
            stacklevel=3,
        )
        return None
