"""Every Newton world its own rse terrain, new every episode (docs/envs.md):
Newton holds height fields per world natively (``ModelBuilder.begin_world``
/ ``add_shape_heightfield``), so each world gets its env's field as a shape,
and a reset rewrites the reset worlds' elevations in place — in
``model.heightfield_elevations`` (Newton's own collision pipeline) and, with
``SolverMuJoCo``, in the solver's MuJoCo Warp model too (Newton does not copy
one into the other).

::

    envs = rse.EnvTerrains(scheme, num_worlds)
    builder = newton.ModelBuilder()
    for w in range(num_worlds):
        builder.begin_world()
        rse.newton.add_heightfield(builder, envs, w)
        ...                                   # the world's robot or bodies
        builder.end_world()
    model = builder.finalize(device="cpu")
    ...
    envs.reset(done)
    rse.newton.sync(model, envs, done)        # solver=... with SolverMuJoCo
"""

from __future__ import annotations

import weakref
from typing import Any, Optional

from rse._adapters import private
from rse._adapters.fields import require_layout
from rse._adapters.ids import env_ids as _env_ids
from rse._adapters.warp_fields import copy_rows
from rse._rse import EnvTerrains

__all__ = ["add_heightfield", "sync"]


def _check_slots(envs: EnvTerrains) -> None:
    require_layout(envs, "slots", "rse.newton gives each world its own field")


def add_heightfield(builder: Any, envs: EnvTerrains, env: int, **shape_options: Any) -> int:
    """Adds env ``env``'s field to the world being built (between
    ``begin_world`` and ``end_world``) as a Newton height-field shape: its
    samples (normalised to [0, 1], rows along y), spanning the env's slot
    (its terrain's corner at the origin, as ``envs.origins`` and
    ``heights_at`` use) from 0 to the scheme's highest top. Returns the
    shape's index. ``shape_options`` (``cfg``, ``label``, ...) go to
    ``add_shape_heightfield``; the field is static (Newton's height fields
    belong to no body)."""
    import newton
    import warp as wp

    _check_slots(envs)
    (env,) = _env_ids(envs.num_envs, [env], "env")
    nrow, ncol = envs.field_shape
    rx, ry, elevation, _ = envs.hfield_size
    x, y, z = envs.hfield_pos
    samples = envs.samples[env].copy()
    field = newton.Heightfield(data=samples, nrow=nrow, ncol=ncol, hx=rx, hy=ry, min_z=0.0, max_z=elevation)
    # Newton rescales the data to span [0, 1] between its own lowest and
    # highest value; rse's samples are already [0, 1] of [min_z, max_z]
    # (0 and the scheme's highest top), the range a reset's samples share.
    # Kept as they are, so the field is right before any `sync`.
    private.setattr_checked(field, "_data", samples, "newton")
    private.setattr_checked(field, "_cached_hash", None, "newton")
    return builder.add_shape_heightfield(
        xform=wp.transform(p=wp.vec3(x, y, z), q=wp.quat_identity()), heightfield=field, **shape_options
    )


_OFFSETS: dict[int, tuple[Any, list[int]]] = {}
"""Each model's and solver's field starts by ``id``, with a weak reference
to the object they were read from: read from the device once, so a reset
copies the new samples up and reads nothing back."""


def _once(owner: Any, read: Any) -> list[int]:
    """``read()``, kept for ``owner`` while it lives."""
    key = id(owner)
    kept = _OFFSETS.get(key)
    if kept is not None and kept[0]() is owner:
        return kept[1]
    value = read()
    _OFFSETS[key] = (weakref.ref(owner, lambda _: _OFFSETS.pop(key, None)), value)
    return value


def _world_offsets(model: Any, envs: EnvTerrains) -> list[int]:
    """Where each world's field starts in ``model.heightfield_elevations``:
    the fields in the order their shapes were added, one per world (read
    once per model: they are fixed when it is finalized)."""
    offsets = _once(model, lambda: _read_world_offsets(model, envs))
    if len(offsets) != envs.num_envs:
        raise ValueError(f"model: height fields in {len(offsets)} worlds, expected one in each of the {envs.num_envs} worlds")
    return offsets


def _read_world_offsets(model: Any, envs: EnvTerrains) -> list[int]:
    data = model.heightfield_data.numpy()
    index = model.shape_heightfield_index.numpy()
    worlds = model.shape_world.numpy()
    offsets: dict[int, int] = {}
    for shape, h in enumerate(index):
        if h >= 0:
            world = int(worlds[shape])
            if world in offsets:
                raise ValueError(f"model: world {world} holds two height fields; rse.newton expects one per world")
            offsets[world] = int(data[h]["data_offset"])
    if sorted(offsets) != list(range(envs.num_envs)):
        raise ValueError(
            f"model: height fields in worlds {sorted(offsets)}, expected one in each of the {envs.num_envs} worlds "
            "(add_heightfield in every world)"
        )
    return [offsets[w] for w in range(envs.num_envs)]


def sync(model: Any, envs: EnvTerrains, env_ids: Any = None, *, solver: Optional[Any] = None) -> None:
    """Writes the samples of ``env_ids`` (all when None) into their worlds'
    fields in place: ``model.heightfield_elevations`` and, given a
    ``SolverMuJoCo``, its MuJoCo Warp model's ``hfield_data``. No rebuild,
    no recompilation."""
    _check_slots(envs)
    ids = _env_ids(envs.num_envs, env_ids)
    offsets = _world_offsets(model, envs)
    copy_rows(model.heightfield_elevations, envs.samples, [(e, offsets[e]) for e in ids])
    if solver is not None:
        starts = _mujoco_offsets(solver, envs)
        copy_rows(solver.mjw_model.hfield_data, envs.samples, [(e, starts[e]) for e in ids])


def _mujoco_offsets(solver: Any, envs: EnvTerrains) -> list[int]:
    """Where each world's field starts in ``SolverMuJoCo``'s ``hfield_data``
    (the per-world ``geom_dataid`` Newton sets; read once per solver)."""
    starts = _once(solver, lambda: _read_mujoco_offsets(solver, envs))
    if len(starts) != envs.num_envs:
        raise ValueError(f"solver: {len(starts)} worlds, expected {envs.num_envs}")
    return starts


def _read_mujoco_offsets(solver: Any, envs: EnvTerrains) -> list[int]:
    import mujoco
    import numpy as np

    mjm = solver.mj_model
    geoms = np.flatnonzero(mjm.geom_type == mujoco.mjtGeom.mjGEOM_HFIELD)
    if len(geoms) != 1:
        raise ValueError(f"solver: {len(geoms)} height-field geoms in its MuJoCo model, expected one per world")
    ids = solver.mjw_model.geom_dataid.numpy()[:, int(geoms[0])]
    if len(ids) != envs.num_envs:
        raise ValueError(f"solver: {len(ids)} worlds, expected {envs.num_envs}")
    return [int(mjm.hfield_adr[h]) for h in ids]
