"""rse terrains in Genesis: one shared height field whose tiles are the
envs' terrains (``rse.EnvTerrains(layout="tiles")``), and the reset envs'
tiles rewritten in the built scene (docs/envs.md).

Genesis has no per-environment terrain: a list of ``Terrain`` morphs is
refused ("Heterogeneous morphs only support Primitive, Mesh, URDF and MJCF
types"), and its terrain is one height field shared by every env. So each
env stands on its own tile of that field (spawn it at ``envs.origins[e]``,
map coordinates = Genesis world coordinates), and ``sync`` rewrites the
field after ``envs.reset``::

    import genesis as gs, rse, rse.genesis

    envs = rse.EnvTerrains(rse.Scheme.load("schemes/six_obstacles.csv"), n_envs, layout="tiles", border=2)
    scene = gs.Scene(...)
    terrain = scene.add_entity(rse.genesis.terrain_morph(envs))
    ...
    scene.build(n_envs=n_envs)
    envs.reset(done_ids)
    rse.genesis.sync(scene, terrain, envs, done_ids)   # their tiles, no rebuild
    # or both at once, from the boolean mask a Genesis task resets by:
    rse.genesis.reset(scene, terrain, envs, reset_buf)

Genesis's own Go2 locomotion example on rse tiles is examples/genesis_go2
(docs/train.md).

The rewrite goes through Genesis's internals (``collider_info.terrain_hf``,
``terrain_xyz_maxmin`` and the entity's height-query tensor), as no public
call exists (Genesis 1.4.5). ``reset`` writes the reset envs' tiles alone,
on Genesis's device (the whole map of examples/genesis_go2's 4096 tiles
is 116 MB, which every reset wrote twice before); ``sync`` without ids
writes the whole map. Not refreshed: the
visual mesh (a viewer or camera still shows the first terrains) and the
terrain's signed-distance field, which Genesis uses against non-convex
geoms: collide robots through convex geoms (spheres, boxes, capsules,
cylinders, convex meshes) on a rewritten terrain.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import Any

import numpy as np

from rse._adapters import private
from rse._adapters.fields import require_layout
from rse._adapters.ids import env_ids as _env_ids
from rse._adapters.torch_uploads import to_device
from rse._rse import EnvTerrains

__all__ = ["heights", "reset", "sync", "terrain_morph"]


def _tiles(envs: EnvTerrains) -> None:
    require_layout(envs, "tiles", "Genesis has one terrain shared by every env")


def heights(envs: EnvTerrains) -> np.ndarray:
    """The tile map in Genesis's layout: float32 metres, indexed
    ``[x, y]`` (rse's maps are ``[y, x]``), ``(field columns, field
    rows)``."""
    _tiles(envs)
    return np.ascontiguousarray(_in_metres(envs.samples[0], envs))


def _in_metres(samples: np.ndarray, envs: EnvTerrains) -> np.ndarray:
    """``samples`` of ``envs``' map (``[y, x]``, in [0, 1]) in Genesis's
    layout and units: ``[x, y]``, float32 metres. The one conversion the
    whole map and a reset's tiles both go through, so they agree to the
    bit."""
    return samples.T * np.float32(envs.hfield_size[2])


def terrain_morph(envs: EnvTerrains, **kwargs: Any) -> Any:
    """A ``gs.morphs.Terrain`` of ``envs``' tile map, placed so that
    Genesis's world frame is the map frame (``envs.origins`` are world
    positions): ``horizontal_scale`` is the sample spacing (block size /
    oversample), heights are in metres (``vertical_scale`` 1). ``kwargs``
    go to the morph (``name``, ``visualization``, …)."""
    import genesis as gs

    _tiles(envs)
    x, y, z = envs.hfield_pos
    rx, ry = envs.hfield_size[:2]
    ncol = envs.samples.shape[2]
    return gs.morphs.Terrain(
        height_field=heights(envs),
        horizontal_scale=2 * rx / (ncol - 1),
        vertical_scale=1.0,
        pos=(x - rx, y - ry, z),
        **kwargs,
    )


def sync(scene: Any, terrain: Any, envs: EnvTerrains, env_ids: Any = None) -> None:
    """Rewrites the built ``scene``'s terrain (the entity ``terrain``
    added from ``terrain_morph(envs)``) with ``envs``' current tile map:
    the collider's height field, its bounds, and the entity's height
    queries (``get_terrain_height``). Call it after ``envs.reset``.

    ``env_ids``: the envs reset since the last sync (ids, or a boolean
    mask); only their tiles are written, on Genesis's device, where
    Genesis shares its field with torch (its zero-copy, on by default)
    and this terrain was synced whole once with these ``envs``. Else, and
    with None, the whole map is written (every tile as it stands)."""
    info = _collider_info(scene, envs)
    ids = None if env_ids is None else np.unique(_env_ids(envs.num_envs, env_ids, "env_ids"))
    state = _SYNCED.get(terrain)
    if ids is not None and state is not None and state.envs is envs and state.field is not None:
        if len(ids):
            state.write_tiles(envs, ids, info)
        return
    _SYNCED[terrain] = _MapState.write_all(info, terrain, envs)


def _collider_info(scene: Any, envs: EnvTerrains) -> Any:
    """The scene's collider state, its field checked against ``envs``' map."""
    _tiles(envs)
    # Genesis has no public call for this: its internals, as listed (with
    # the version they were checked against) in rse._adapters.private.
    info = private.getattr_checked(scene.sim.rigid_solver.collider, "collider_info", "genesis")
    rows, cols = envs.samples.shape[1:]
    if tuple(info.terrain_hf.shape) != (cols, rows):
        raise ValueError(f"terrain: the scene's field is {tuple(info.terrain_hf.shape)}, the envs' map {(cols, rows)} (build it from terrain_morph(envs))")
    return info


@dataclass
class _MapState:
    """What the last whole sync of a terrain left, so that later syncs
    write only the reset envs' tiles: the collider's field as a torch
    view of Genesis's own memory (None where Genesis gives none), the
    entity's height-query tensor (rse's own since that sync), the bounds
    Genesis keeps, each tile's corner in the map (on the host and on the
    device), and the highest and lowest height of each tile and of
    the map outside the tiles (the bounds of a partly written map, exactly
    as ``max``/``min`` over the whole of it)."""

    envs: EnvTerrains
    field: Any
    table: Any
    bounds: np.ndarray
    corners: np.ndarray
    on_device: Any
    tile_max: np.ndarray
    tile_min: np.ndarray
    rest: tuple[Any, Any]

    @classmethod
    def write_all(cls, info: Any, terrain: Any, envs: EnvTerrains) -> _MapState:
        import genesis as gs
        import torch

        new = heights(envs)
        info.terrain_hf.from_numpy(new)
        bounds = info.terrain_xyz_maxmin.to_numpy()
        bounds[2], bounds[5] = new.max(), new.min() - 1.0  # as Genesis sets them at build
        info.terrain_xyz_maxmin.from_numpy(bounds)
        table = torch.as_tensor(new, dtype=gs.tc_float, device=gs.device)
        private.setattr_checked(terrain, "_terrain_height_field", table, "genesis")
        corners = envs.field_corners
        rows, cols = envs.field_shape
        tiles = [new[c : c + cols, r : r + rows] for r, c in corners]
        outside = np.ones(new.shape, dtype=bool)
        for r, c in corners:
            outside[c : c + cols, r : r + rows] = False
        rest = new[outside]
        return cls(
            envs=envs,
            field=_shared_view(info.terrain_hf),
            table=table,
            bounds=bounds,
            corners=corners,
            on_device=torch.as_tensor(corners, device=table.device),
            tile_max=np.array([t.max() for t in tiles], dtype=new.dtype),
            tile_min=np.array([t.min() for t in tiles], dtype=new.dtype),
            rest=(rest.max(), rest.min()) if rest.size else (None, None),
        )

    def write_tiles(self, envs: EnvTerrains, ids: np.ndarray, info: Any) -> None:
        """Writes the tiles of ``ids`` (distinct) from ``envs``' map into
        the collider's field and the height-query tensor (one upload,
        which the host does not wait for on a GPU, and one scatter each)
        and the map's bounds."""
        import genesis as gs
        import torch

        rows, cols = envs.field_shape
        samples = envs.samples[0]
        block = np.empty((len(ids), cols, rows), dtype=np.float32)
        for i, (r, c) in enumerate(self.corners[ids]):
            block[i] = _in_metres(samples[r : r + rows, c : c + cols], envs)
        flat = block.reshape(len(ids), -1)
        self.tile_max[ids], self.tile_min[ids] = flat.max(axis=1), flat.min(axis=1)
        values = to_device(block, self.table)
        at = self.on_device[to_device(ids, self.on_device)]
        xs = at[:, 1, None, None] + torch.arange(cols, device=at.device)[None, :, None]
        ys = at[:, 0, None, None] + torch.arange(rows, device=at.device)[None, None, :]
        self.field[xs, ys] = values
        self.table[xs, ys] = values
        if gs.backend == gs.metal:  # as Genesis's own writes through such views (set_gravity)
            torch.mps.synchronize()
        high, low = self.tile_max.max(), self.tile_min.min()
        if self.rest[0] is not None:
            high, low = max(high, self.rest[0]), min(low, self.rest[1])
        self.bounds[2], self.bounds[5] = high, low - 1.0
        info.terrain_xyz_maxmin.from_numpy(self.bounds)


def _shared_view(field: Any) -> Any:
    """A torch tensor over the memory of Genesis's ``field`` (Genesis's
    own ``qd_to_torch``, without a copy), or None where Genesis makes
    none (its zero-copy is off, or the backend cannot share)."""
    import genesis as gs
    from genesis.utils.misc import qd_to_torch  # listed in rse._adapters.private

    try:
        return qd_to_torch(field, copy=False)
    except (gs.GenesisException, RuntimeError, TypeError, ValueError):  # what Genesis's own callers catch
        return None


_SYNCED: weakref.WeakKeyDictionary[Any, _MapState] = weakref.WeakKeyDictionary()
"""Each synced terrain entity's state, for as long as the entity lives."""


def reset(scene: Any, terrain: Any, envs: EnvTerrains, envs_idx: Any = None) -> np.ndarray:
    """Renews the terrains of ``envs_idx`` and rewrites the scene's field
    once (``envs.reset`` then ``sync``); returns the ids reset.
    ``envs_idx`` is what Genesis's tasks reset by: a boolean mask over the
    envs (a torch tensor or array), env ids, or None for every env. With
    no env to reset nothing is rewritten, so a task may call it every
    step."""
    ids = np.asarray(_env_ids(envs.num_envs, envs_idx, "envs_idx"), dtype=np.int64)
    if len(ids):
        envs.reset(ids)
        sync(scene, terrain, envs, ids)
    return ids
