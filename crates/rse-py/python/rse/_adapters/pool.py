"""Every environment its own height field in MuJoCo: an ``EnvTerrains``
pool (one field per env) or tile map in an ``MjSpec`` or as MJCF, the
terrain geom that shows it, and the reset envs' samples copied into a live
model. ``rse.mujoco`` re-exports the public functions; ``rse.mujoco_warp``,
``rse.mjx`` and ``rse.mjlab`` build on the helpers here (docs/envs.md).
"""

from __future__ import annotations

from typing import Any, Union

import numpy as np

from rse._adapters.fields import field_size, hfield_id
from rse._adapters.ids import env_ids as _env_ids
from rse._adapters.mjcf import field_model, floats
from rse._adapters.warp_fields import write_rows
from rse._rse import EnvTerrains

POOL = "rse_env"
"""The default name of the pool's height fields (``rse_env_0``, …) and of
the geom that shows them."""

GEOM = "rse_terrain"
"""The default name of the terrain geom whose data id is routed per world
(MuJoCo Warp, MJX)."""

FIELD_RGBA = (0.76, 0.6, 0.42, 1.0)
"""The colour of rse's height-field geoms: wood."""

FIELD_RGBA_TEXT = " ".join(f"{c:g}" for c in FIELD_RGBA)

__all__ = [
    "FIELD_RGBA",
    "GEOM",
    "POOL",
    "add_env_geom",
    "add_env_hfields",
    "copy_env_samples",
    "env_hfield_names",
    "env_hfields_mjcf",
    "env_pool",
    "sync_env_hfields",
]


def env_hfield_names(envs: EnvTerrains, name: str = POOL) -> list[str]:
    """The height-field assets ``add_env_hfields`` makes: ``name0`` …
    ``name{n-1}`` for slots, ``name`` for tiles."""
    return [env_hfield_name(envs, e, name) for e in range(pool_count(envs))]


def env_hfield_name(envs: EnvTerrains, e: int, name: str = POOL) -> str:
    """The height-field asset of field ``e`` of ``env_hfield_names``."""
    return name if envs.layout == "tiles" else f"{name}{e}"


def pool_count(envs: EnvTerrains) -> int:
    """How many height fields ``add_env_hfields`` makes: one an env for
    slots, the map for tiles."""
    return 1 if envs.layout == "tiles" else envs.num_envs


def add_env_hfields(spec: Any, envs: EnvTerrains, *, name: str = POOL) -> list[str]:
    """Adds to ``spec`` (a ``mujoco.MjSpec``) the height fields of
    ``envs`` (an ``rse.EnvTerrains``): one per environment for slots (the
    pool a batched simulator routes per world), one for the tile map; each
    sized ``envs.hfield_size`` and holding the current samples (copy them
    again after compiling: MuJoCo rescales data given before it, see
    ``sync_env_hfields``). Returns their names. Add geoms with
    ``add_env_geom``."""
    names = env_hfield_names(envs, name)
    nrow, ncol = envs.samples.shape[1:]
    for i, hfield in enumerate(names):
        spec.add_hfield(name=hfield, nrow=nrow, ncol=ncol, size=list(envs.hfield_size), userdata=envs.samples[i].ravel())
    return names


def add_env_geom(
    spec: Any,
    envs: EnvTerrains,
    hfield: str,
    *,
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0),
    name: Union[str, None] = None,
    group: int = 2,
    body: Any = None,
) -> Any:
    """Adds to ``body`` (default: the world body) of ``spec`` a geom
    showing the height field ``hfield`` (one of ``add_env_hfields``'s),
    placed at ``envs.hfield_pos`` plus ``offset``: its slot's (or the
    map's) frame moved by ``offset``. Returns the geom's spec."""
    import mujoco

    x, y, z = envs.hfield_pos
    return (body if body is not None else spec.worldbody).add_geom(
        name=name or hfield,
        type=mujoco.mjtGeom.mjGEOM_HFIELD,
        hfieldname=hfield,
        pos=[x + offset[0], y + offset[1], z + offset[2]],
        rgba=list(FIELD_RGBA),
        group=group,
    )


def env_hfields_mjcf(envs: EnvTerrains, *, name: str = POOL) -> str:
    """An MJCF model holding the height fields of ``envs`` (as
    ``add_env_hfields``: the pool for slots, the map for tiles) and a geom
    showing the first (``name0``; ``name`` for tiles) at ``hfield_pos``.
    The fields start flat (MJCF rescales given samples to span [0, 1]):
    compile, then ``sync_env_hfields(model, envs)``. Merge it into a robot
    model with ``MjSpec.attach`` or by editing the text."""
    nrow, ncol = envs.samples.shape[1:]
    names = env_hfield_names(envs, name)
    return field_model("rse_env_hfields", names, (nrow, ncol), envs.hfield_size, floats(envs.hfield_pos), FIELD_RGBA_TEXT, group=2)


def env_pool(model: Any, envs: EnvTerrains, name: str, argument: str = "model") -> tuple[int, np.ndarray, int]:
    """The height fields ``add_env_hfields`` made in the compiled ``model``
    (a ``MjModel``): the first one's id, every one's address in
    ``hfield_data`` and the samples of each. They were added one after the
    other, so the first and last names bound them; ``ValueError`` naming
    ``argument`` when they are not there, not one run, or of another size."""
    # The first and last names only: every reset asks, and a list of all
    # 4096 names took 0.37 ms.
    count = pool_count(envs)
    names = [env_hfield_name(envs, 0, name), env_hfield_name(envs, count - 1, name)]
    hint = "add them with add_env_hfields"
    first, last = (hfield_id(model, n, argument, hint) for n in (names[0], names[-1]))
    if last - first != count - 1:
        raise ValueError(f"{argument}: the height fields {names[0]} … {names[-1]} are not one pool ({hint})")
    size = field_size(model, first)
    if size != envs.samples[0].size:
        raise ValueError(f"{argument}: height field {names[0]} holds {size} samples, but the envs' field has {envs.samples[0].size}")
    return first, np.asarray(model.hfield_adr[first : last + 1], dtype=np.int64), size


def copy_env_samples(data: np.ndarray, envs: EnvTerrains, ids: list[int], adr: np.ndarray, size: int) -> None:
    """Copies the samples of ``ids`` into ``data`` (a model's
    ``hfield_data``, or a host view of a device copy of it) at ``adr``."""
    write_rows(data, envs.samples.reshape(-1, size), [(e, adr[e]) for e in ids])


def sync_env_hfields(model: Any, envs: EnvTerrains, env_ids: Any = None, *, name: str = POOL) -> None:
    """Copies the samples of ``env_ids`` (all when None) from ``envs`` into
    the compiled ``model``'s height fields made by ``add_env_hfields``
    (slots: each env's own; tiles: the map, whole). Call it after
    ``envs.reset(env_ids)``; the model is not recompiled."""
    ids = [0] if envs.layout == "tiles" else _env_ids(envs.num_envs, env_ids)
    _, adr, size = env_pool(model, envs, name)
    copy_env_samples(model.hfield_data, envs, ids, adr, size)
