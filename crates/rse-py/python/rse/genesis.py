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
    rse.genesis.sync(scene, terrain, envs)   # the collider's field, no rebuild
    # or both at once, from the boolean mask a Genesis task resets by:
    rse.genesis.reset(scene, terrain, envs, reset_buf)

Genesis's own Go2 locomotion example on rse tiles is examples/genesis_go2
(docs/train.md).

The rewrite goes through Genesis's internals (``collider_info.terrain_hf``,
``terrain_xyz_maxmin`` and the entity's height-query tensor), as no public
call exists (Genesis 1.4.5); it copies the whole map. Not refreshed: the
visual mesh (a viewer or camera still shows the first terrains) and the
terrain's signed-distance field, which Genesis uses against non-convex
geoms: collide robots through convex geoms (spheres, boxes, capsules,
cylinders, convex meshes) on a rewritten terrain.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rse._adapters import private
from rse._adapters.fields import require_layout
from rse._adapters.ids import env_ids as _env_ids
from rse._rse import EnvTerrains

__all__ = ["heights", "reset", "sync", "terrain_morph"]


def _tiles(envs: EnvTerrains) -> None:
    require_layout(envs, "tiles", "Genesis has one terrain shared by every env")


def heights(envs: EnvTerrains) -> np.ndarray:
    """The tile map in Genesis's layout: float32 metres, indexed
    ``[x, y]`` (rse's maps are ``[y, x]``), ``(field columns, field
    rows)``."""
    _tiles(envs)
    return np.ascontiguousarray(envs.samples[0].T * np.float32(envs.hfield_size[2]))


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


def sync(scene: Any, terrain: Any, envs: EnvTerrains) -> None:
    """Rewrites the built ``scene``'s terrain (the entity ``terrain``
    added from ``terrain_morph(envs)``) with ``envs``' current tile map:
    the collider's height field, its bounds, and the entity's height
    queries (``get_terrain_height``). Call it after ``envs.reset``; tiles
    of envs not reset are written with the values they hold."""
    import genesis as gs
    import torch

    new = heights(envs)
    # Genesis has no public call for this: its internals, as listed (with
    # the version they were checked against) in rse._adapters.private.
    info = private.getattr_checked(scene.sim.rigid_solver.collider, "collider_info", "genesis")
    if tuple(info.terrain_hf.shape) != new.shape:
        raise ValueError(f"terrain: the scene's field is {tuple(info.terrain_hf.shape)}, the envs' map {new.shape} (build it from terrain_morph(envs))")
    info.terrain_hf.from_numpy(new)
    bounds = info.terrain_xyz_maxmin.to_numpy()
    bounds[2], bounds[5] = new.max(), new.min() - 1.0  # as Genesis sets them at build
    info.terrain_xyz_maxmin.from_numpy(bounds)
    private.setattr_checked(terrain, "_terrain_height_field", torch.as_tensor(new, dtype=gs.tc_float, device=gs.device), "genesis")


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
        sync(scene, terrain, envs)
    return ids
