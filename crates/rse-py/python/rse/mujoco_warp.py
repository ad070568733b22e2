"""Every world of MuJoCo Warp its own rse terrain, new at each of its
resets (docs/envs.md).

MuJoCo Warp shares ``hfield_data`` among its worlds, but lets each world
point its geoms at their own height field: ``put_model(...,
batch_sizes={"geom_dataid": nworld})``. So the model holds a pool of height
fields of one shape, one per world (``rse.EnvTerrains`` slots), and one
terrain geom whose data id is world ``w``'s own field::

    import mujoco, mujoco_warp as mjw, rse, rse.mujoco_warp

    envs = rse.EnvTerrains(rse.Scheme.load("schemes/six_obstacles.csv"), nworld)
    spec = mujoco.MjSpec.from_file("robot.xml")
    rse.mujoco_warp.add_terrain(spec, envs)         # the pool and the terrain geom
    mjm = spec.compile()
    m = rse.mujoco_warp.put_model(mjm, envs)        # world w stands on env w's terrain
    d = mjw.make_data(mjm, nworld=nworld)
    ...
    envs.reset(done_ids)                             # new terrains for the envs that ended
    rse.mujoco_warp.sync(m, mjm, envs, done_ids)     # copies those slots only, no recompile

What ``sync`` does not refresh: a render context builds its height-field
BVHs once from the host model (rebuild it to see new terrains); nothing
else in MuJoCo Warp caches the field.
"""

from __future__ import annotations

from typing import Any

from rse._adapters.fields import geom_id, require_layout
from rse._adapters.ids import env_ids as _env_ids
from rse._adapters.pool import GEOM, POOL, add_env_geom, add_env_hfields, env_pool, sync_env_hfields
from rse._adapters.warp_fields import copy_rows, route_per_world
from rse._rse import EnvTerrains

__all__ = ["GEOM", "add_terrain", "put_model", "route", "sync"]

"""The name of the terrain geom ``add_terrain`` adds."""


def add_terrain(spec: Any, envs: EnvTerrains, *, name: str = POOL, geom: str = GEOM) -> None:
    """Adds to ``spec`` (a ``mujoco.MjSpec``) the pool of ``envs``' height
    fields (``envs`` in the slots layout, one per world) and one geom
    ``geom`` showing the first, its slot's frame at the world origin (each
    env's ``origins`` are then world coordinates). ``put_model`` routes each
    world to its own field."""
    require_layout(envs, "slots", "MuJoCo Warp routes a field per world")
    names = add_env_hfields(spec, envs, name=name)
    add_env_geom(spec, envs, names[0], name=geom)


def _terrain_geom(mjm: Any, geom: str) -> int:
    return geom_id(mjm, geom, "mjm", "add it with rse.mujoco_warp.add_terrain")


def put_model(mjm: Any, envs: EnvTerrains, *, name: str = POOL, geom: str = GEOM, **kwargs: Any) -> Any:
    """``mujoco_warp.put_model`` of ``mjm`` (compiled from a spec that
    ``add_terrain`` built) with every env's samples in its field and the
    terrain geom's data id batched per world: world ``w`` stands on env
    ``w``'s terrain. ``kwargs`` go to ``put_model`` (``batch_sizes`` is
    merged)."""
    import mujoco_warp as mjw

    _terrain_geom(mjm, geom)
    require_layout(envs, "slots", "MuJoCo Warp routes a field per world")
    env_pool(mjm, envs, name, "mjm")
    sync_env_hfields(mjm, envs, name=name)
    batch = dict(kwargs.pop("batch_sizes", {}) or {})
    batch["geom_dataid"] = envs.num_envs
    m = mjw.put_model(mjm, batch_sizes=batch, **kwargs)
    route(m, mjm, envs, name=name, geom=geom)
    return m


def route(m: Any, mjm: Any, envs: EnvTerrains, *, name: str = POOL, geom: str = GEOM) -> None:
    """Points the terrain geom ``geom`` of world ``w`` of the device model
    ``m`` at env ``w``'s field of the pool, in ``m``'s per-world
    ``geom_dataid`` (batched by ``put_model``, or by a framework: mjlab's
    ``Simulation.expand_model_fields``). The samples are ``sync``'s job
    (``put_model`` uploads them with the host model)."""
    gid = _terrain_geom(mjm, geom)
    first, _, _ = env_pool(mjm, envs, name, "mjm")
    if m.geom_dataid.shape[0] != envs.num_envs:
        raise ValueError(f"m: geom_dataid holds {m.geom_dataid.shape[0]} worlds, expected one per env ({envs.num_envs})")
    route_per_world(m, gid, first)


def sync(m: Any, mjm: Any, envs: EnvTerrains, env_ids: Any = None, *, name: str = POOL) -> None:
    """Copies the samples of ``env_ids`` (all when None) from ``envs`` into
    the device model ``m``'s height fields, each into its own field only,
    on any device in one upload (the rows of ``env_ids``, then one kernel
    writes each at its field's address). Call it after
    ``envs.reset(env_ids)``."""
    ids = _env_ids(envs.num_envs, env_ids)
    _, adr, _ = env_pool(mjm, envs, name, "mjm")
    copy_rows(m.hfield_data, envs.samples, [(e, adr[e]) for e in ids])
