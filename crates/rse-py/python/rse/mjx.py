"""Every world of MJX its own rse terrain, new at each of its resets
(docs/envs.md).

MJX (the JAX implementation, ``impl="jax"``) batches worlds with
``jax.vmap``, and any model field can carry a leading world axis. So the
model holds one height field of the slot shape, and its ``hfield_data`` is
batched: row ``w`` is world ``w``'s whole ``hfield_data``, with env ``w``'s
terrain in the rse field. Replacing rows keeps the array's shape, dtype and
device, so the jitted step is not traced again::

    import jax, mujoco, rse, rse.mjx
    from mujoco import mjx

    envs = rse.EnvTerrains(rse.Scheme.load("schemes/six_obstacles.csv"), nworld)
    spec = mujoco.MjSpec.from_file("robot.xml")
    rse.mjx.add_terrain(spec, envs)                  # one field of the slot shape, one geom
    mjm = spec.compile()
    m = rse.mjx.put_model(mjm, envs)                 # hfield_data: (nworld, nhfielddata)
    step = jax.jit(jax.vmap(mjx.step, in_axes=(rse.mjx.in_axes(m), 0)))
    ...
    envs.reset(done_ids)                             # new terrains for the envs that ended
    m = rse.mjx.sync(m, mjm, envs, done_ids)         # those rows only; no re-jit

Memory: the batched field holds ``nworld`` copies of the model's whole
``hfield_data`` (4096 worlds of 160 × 160 samples: 420 MB of float32).
MJX collides height fields with spheres, boxes and capsules only (not
cylinders or ellipsoids). MJX's Warp implementation keeps only row 0 of a
batched ``geom_dataid``: use ``rse.mujoco_warp`` for MuJoCo Warp.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from rse._adapters.fields import env_field, require_layout
from rse._adapters.ids import env_ids as _env_ids
from rse._adapters.pool import GEOM, POOL, add_env_geom
from rse._adapters.world_rows import world_rows
from rse._rse import EnvTerrains

__all__ = ["GEOM", "add_terrain", "hfield_rows", "in_axes", "put_model", "sync"]

"""The name of the terrain geom ``add_terrain`` adds."""


def add_terrain(spec: Any, envs: EnvTerrains, *, name: str = POOL, geom: str = GEOM) -> None:
    """Adds to ``spec`` (a ``mujoco.MjSpec``) one height field ``name`` of
    ``envs``' slot shape and size (``envs`` in the slots layout) and a geom
    ``geom`` showing it, its slot's frame at the world origin (each env's
    ``origins`` are then world coordinates). ``put_model`` gives each world
    its own samples."""
    require_layout(envs, "slots", "MJX batches a field per world")
    nrow, ncol = envs.samples.shape[1:]
    spec.add_hfield(name=name, nrow=nrow, ncol=ncol, size=list(envs.hfield_size), userdata=envs.samples[0].ravel())
    add_env_geom(spec, envs, name, name=geom)


def hfield_rows(mjm: Any, envs: EnvTerrains, env_ids: Any = None, *, name: str = POOL) -> np.ndarray:
    """World rows of ``hfield_data`` for ``env_ids`` (all when None):
    float32 ``(len(env_ids), mjm.nhfielddata)``, each ``mjm``'s own
    ``hfield_data`` with that env's samples in the field ``name``."""
    require_layout(envs, "slots", "MJX batches a field per world")
    adr, _ = env_field(mjm, envs, name, "mjm", "add it with rse.mjx.add_terrain")
    ids = _env_ids(envs.num_envs, env_ids)
    return world_rows(mjm.hfield_data, adr, envs.samples[ids])


def put_model(mjm: Any, envs: EnvTerrains, *, name: str = POOL, device: Any = None) -> Any:
    """``mjx.put_model(mjm, impl="jax")`` with ``hfield_data`` batched per
    world: row ``w`` holds env ``w``'s terrain. Step it under ``jax.vmap``
    with ``in_axes(m)``."""
    import jax
    from mujoco import mjx

    rows = hfield_rows(mjm, envs, name=name)
    m = mjx.put_model(mjm, device=device, impl="jax")
    # Committed to the model's device, as put_model's own arrays are: an
    # uncommitted array changes jit's cache key and traces the step again.
    return m.replace(hfield_data=jax.device_put(rows, m.hfield_data.devices().pop()))


def in_axes(m: Any) -> Any:
    """The ``jax.vmap`` ``in_axes`` tree for a model from ``put_model``:
    world axis 0 on ``hfield_data``, none elsewhere."""
    import jax

    return jax.tree_util.tree_map(lambda _: None, m).replace(hfield_data=0)


@functools.cache
def _scatter_donating() -> Any:
    """A jitted ``rows.at[ids].set(values)``, made once, its first
    argument donated: XLA writes the rows in place instead of copying the
    whole batched field."""
    import jax

    return jax.jit(lambda rows, ids, values: rows.at[ids].set(values), donate_argnums=0)


def sync(m: Any, mjm: Any, envs: EnvTerrains, env_ids: Any = None, *, name: str = POOL) -> Any:
    """A model like ``m`` (from ``put_model``) whose rows ``env_ids`` (all
    when None) hold those envs' current terrains; the other rows are
    untouched and ``m``'s ``hfield_data`` is consumed (donated). Call it
    after ``envs.reset(env_ids)``: same shape, dtype and device, so a
    jitted step is not traced again."""
    import jax

    ids = _env_ids(envs.num_envs, env_ids)
    if m.hfield_data.shape != (envs.num_envs, mjm.nhfielddata):
        raise ValueError(f"m: hfield_data is {m.hfield_data.shape}, expected ({envs.num_envs}, {mjm.nhfielddata}) (make it with rse.mjx.put_model)")
    if not ids:
        return m
    device = m.hfield_data.devices().pop()
    # Padded to a power of two by repeating the last id (it writes the same
    # row again): the scatter compiles once per size class, not per count.
    padded = ids + ids[-1:] * ((1 << (len(ids) - 1).bit_length()) - len(ids))
    rows = jax.device_put(hfield_rows(mjm, envs, padded, name=name), device)
    index = jax.device_put(np.asarray(padded, dtype=np.int32), device)
    return m.replace(hfield_data=_scatter_donating()(m.hfield_data, index, rows))
