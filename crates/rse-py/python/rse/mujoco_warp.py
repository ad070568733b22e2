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

import numpy as np

from rse._rse import EnvTerrains
from rse.mujoco import add_env_geom, add_env_hfields, env_hfield_names, sync_env_hfields

__all__ = ["GEOM", "add_terrain", "put_model", "sync"]

GEOM = "rse_terrain"
"""The name of the terrain geom ``add_terrain`` adds."""


def add_terrain(spec: Any, envs: EnvTerrains, *, name: str = "rse_env", geom: str = GEOM) -> None:
    """Adds to ``spec`` (a ``mujoco.MjSpec``) the pool of ``envs``' height
    fields (``envs`` in the slots layout, one per world) and one geom
    ``geom`` showing the first, its slot's frame at the world origin (each
    env's ``origins`` are then world coordinates). ``put_model`` routes each
    world to its own field."""
    if envs.layout != "slots":
        raise ValueError('envs: MuJoCo Warp routes a field per world: make them with layout="slots"')
    names = add_env_hfields(spec, envs, name=name)
    add_env_geom(spec, envs, names[0], name=geom)


def _terrain_geom(mjm: Any, geom: str) -> int:
    import mujoco

    gid = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, geom)
    if gid < 0:
        raise ValueError(f"mjm: no geom named {geom!r} (add it with rse.mujoco_warp.add_terrain)")
    return gid


def put_model(mjm: Any, envs: EnvTerrains, *, name: str = "rse_env", geom: str = GEOM, **kwargs: Any) -> Any:
    """``mujoco_warp.put_model`` of ``mjm`` (compiled from a spec that
    ``add_terrain`` built) with every env's samples in its field and the
    terrain geom's data id batched per world: world ``w`` stands on env
    ``w``'s terrain. ``kwargs`` go to ``put_model`` (``batch_sizes`` is
    merged)."""
    import mujoco_warp as mjw
    import warp as wp

    gid = _terrain_geom(mjm, geom)
    names = env_hfield_names(envs, name)
    if len(names) != envs.num_envs or envs.layout != "slots":
        raise ValueError("envs: expected the slots layout, one field per world")
    sync_env_hfields(mjm, envs, name=name)
    batch = dict(kwargs.pop("batch_sizes", {}) or {})
    batch["geom_dataid"] = envs.num_envs
    m = mjw.put_model(mjm, batch_sizes=batch, **kwargs)
    dataid = np.tile(np.asarray(mjm.geom_dataid, dtype=np.int32), (envs.num_envs, 1))
    dataid[:, gid] = [_hfield(mjm, n) for n in names]
    wp.copy(m.geom_dataid, wp.array(dataid, dtype=int, device=m.geom_dataid.device))
    return m


def _hfield(mjm: Any, name: str) -> int:
    import mujoco

    hid = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_HFIELD, name)
    if hid < 0:
        raise ValueError(f"mjm: no height field named {name!r} (add them with rse.mujoco_warp.add_terrain)")
    return hid


def _pool(mjm: Any, envs: EnvTerrains, name: str) -> tuple[np.ndarray, int]:
    """The address in ``hfield_data`` of every env's field, and its size:
    ``add_env_hfields`` adds them one after the other, so the first and
    last names bound them."""
    names = env_hfield_names(envs, name)
    first, last = _hfield(mjm, names[0]), _hfield(mjm, names[-1])
    if last - first != len(names) - 1:
        raise ValueError(f"mjm: the height fields {names[0]} … {names[-1]} are not one pool (add them with add_terrain)")
    n = int(mjm.hfield_nrow[first]) * int(mjm.hfield_ncol[first])
    if n != envs.samples[0].size:
        raise ValueError(f"m: height field {names[0]} holds {n} samples, but the envs' field has {envs.samples[0].size}")
    return np.asarray(mjm.hfield_adr[first : last + 1], dtype=np.int64), n


def sync(m: Any, mjm: Any, envs: EnvTerrains, env_ids: Any = None, *, name: str = "rse_env") -> None:
    """Copies the samples of ``env_ids`` (all when None) from ``envs`` into
    the device model ``m``'s height fields, each into its own field only
    (on the CPU device a copy into a numpy view of the warp array; on a
    GPU one ``wp.copy`` per env from the host samples, wrapped without a
    copy).
    Call it after ``envs.reset(env_ids)``."""
    import warp as wp

    ids = np.arange(envs.num_envs) if env_ids is None else np.asarray(env_ids, dtype=np.int64).ravel()
    bad = ids[(ids < 0) | (ids >= envs.num_envs)]
    if bad.size:
        raise ValueError(f"env_ids: {int(bad[0])} is not an environment (0 to {envs.num_envs - 1})")
    adr, n = _pool(mjm, envs, name)
    flat = envs.samples.reshape(-1)
    if m.hfield_data.device.is_cpu:
        # On the CPU device the warp array is host memory: a numpy view
        # of it takes a plain copy, without a kernel launch per env.
        view = m.hfield_data.numpy()
        for e in ids.tolist():
            view[adr[e] : adr[e] + n] = flat[e * n : (e + 1) * n]
        return
    source = wp.array(flat, dtype=float, device="cpu", copy=False)
    for e in ids.tolist():
        wp.copy(m.hfield_data, source, dest_offset=int(adr[e]), src_offset=e * n, count=n)
