"""A new rse terrain in a live MuJoCo model, without recompiling it.

(The per-environment pool, ``add_env_hfields`` and the rest, lives in
``rse._adapters.pool`` and is re-exported here.)

A MuJoCo height field keeps its samples in ``model.hfield_data``; MuJoCo
reads them at every collision check, so overwriting them changes the ground
under the robot at once. ``set_hfield`` writes a terrain there::

    import mujoco, rse, rse.mujoco

    scheme = rse.Scheme.load("schemes/six_obstacles.csv")
    model = mujoco.MjModel.from_xml_string(rse.mujoco.hfield_mjcf(scheme))  # starts flat
    data = mujoco.MjData(model)
    for episode in range(1000):
        rse.mujoco.set_hfield(model, "terrain", scheme.generate(index=episode))
        mujoco.mj_resetData(model, data)
        ...

After ``set_hfield``:

- the OpenGL renderer keeps its own copy of the field: call
  ``mujoco.mjr_uploadHField(model, context, hfield_id)`` (``mujoco.viewer``:
  ``viewer.update_hfield(hfield_id)``);
- MJX keeps the model on the accelerator: ``mjx.put_model(model)`` again, or
  ``mjx_model.replace(hfield_data=jax.numpy.asarray(model.hfield_data))``;
- MuJoCo Warp keeps it in a warp array: copy ``model.hfield_data`` into
  ``warp_model.hfield_data`` (``wp.copy`` of a ``wp.array`` made from it), or
  ``mujoco_warp.put_model(model)`` again.

The field's geometry is fixed when the model is compiled: its size, its
geom's place, its elevation. Every terrain written into it must have the
same grid and fit that elevation; ``hfield_mjcf`` sizes the elevation for
every world of a scheme.
"""

from __future__ import annotations

from typing import Any, Union

import numpy as np

from rse._adapters.mjcf import field_model, floats
from rse._adapters.pool import (
    FIELD_RGBA,
    FIELD_RGBA_TEXT,
    add_env_geom,
    add_env_hfields,
    env_hfield_names,
    env_hfields_mjcf,
    sync_env_hfields,
)
from rse._rse import DEFAULT_OVERSAMPLE, Scheme, Terrain

__all__ = [
    "HFieldSlot",
    "add_env_geom",
    "add_env_hfields",
    "add_hfield",
    "env_hfield_names",
    "env_hfields_mjcf",
    "hfield_mjcf",
    "max_top",
    "set_hfield",
    "sync_env_hfields",
]


def _hfield_id(model: Any, hfield: Union[int, str]) -> int:
    import mujoco

    if isinstance(hfield, str):
        hid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_HFIELD, hfield)
        if hid < 0:
            names = [model.hfield(i).name for i in range(model.nhfield)]
            raise KeyError(f"the model has no height field named {hfield!r} (it has {names})")
        return hid
    if not 0 <= int(hfield) < model.nhfield:
        raise KeyError(f"height field {hfield} does not exist: the model has {model.nhfield}")
    return int(hfield)


def _geom_z(model: Any, hid: int) -> float:
    """The world z of the geom(s) that show height field ``hid``: its own z
    plus its bodies' (static bodies, no rotation)."""
    import mujoco

    # An int, not the enum: numpy compares an array to a pybind11 enum one
    # element at a time, in Python (20 us for 15 geoms).
    hfield_type = int(mujoco.mjtGeom.mjGEOM_HFIELD)
    (geoms,) = np.nonzero((model.geom_type == hfield_type) & (model.geom_dataid == hid))
    if len(geoms) == 0:
        raise ValueError(f"no geom uses height field {model.hfield(hid).name or hid}")
    zs = set()
    for g in geoms:
        z, body = float(model.geom_pos[g, 2]), int(model.geom_bodyid[g])
        while body > 0:
            z += float(model.body_pos[body, 2])
            body = int(model.body_parentid[body])
        zs.add(round(z, 9))
    if len(zs) > 1:
        raise ValueError(f"the geoms of height field {hid} stand at different heights {sorted(zs)}")
    return zs.pop()


class HFieldSlot:
    """A live model's height field, checked once, for writing terrain after
    terrain into it: ``slot.write(terrain)`` costs only the write (a loop of
    episodes should keep one slot; ``set_hfield`` makes one per call).

    The field must have ``terrain.hfield_shape(oversample)`` samples and the
    size of the terrain's grid; every terrain written must fit its
    elevation. ``model`` must outlive the slot: it holds a view of
    ``model.hfield_data``."""

    def __init__(self, model: Any, hfield: Union[int, str], oversample: int = DEFAULT_OVERSAMPLE) -> None:
        self.model = model
        self.id = _hfield_id(model, hfield)
        self.oversample = int(oversample)
        self.shape = (int(model.hfield_nrow[self.id]), int(model.hfield_ncol[self.id]))
        self.radii = tuple(model.hfield_size[self.id, :2].tolist())
        self.elevation = float(model.hfield_size[self.id, 2])
        self.z0 = _geom_z(model, self.id)
        adr, n = int(model.hfield_adr[self.id]), self.shape[0] * self.shape[1]
        self.view = model.hfield_data[adr : adr + n].reshape(self.shape)
        self._checked_block_size: Union[float, None] = None

    def write(self, terrain: Terrain) -> None:
        """Writes ``terrain`` into the field (see ``set_hfield``)."""
        want = terrain.hfield_shape(self.oversample)
        if want != self.shape:
            raise ValueError(
                f"height field {self.id} of the model has shape {self.shape}, but the terrain at "
                f"oversample {self.oversample} has {want}"
            )
        # With the shape checked, the radii depend on the block size alone:
        # checked once per block size, not on every write (the layout scans
        # the terrain's tops).
        if terrain.block_size != self._checked_block_size:
            _, (*expect, _, _), _ = terrain.hfield_layout(self.oversample)
            if abs(self.radii[0] - expect[0]) > 1e-6 or abs(self.radii[1] - expect[1]) > 1e-6:
                raise ValueError(
                    f"height field {self.id} spans radii {self.radii} m, but the terrain's samples need {expect}"
                )
            self._checked_block_size = terrain.block_size
        terrain.hfield_into(self.view, self.oversample, self.z0, self.elevation)


def set_hfield(model: Any, hfield: Union[int, str], terrain: Terrain, oversample: int = DEFAULT_OVERSAMPLE) -> None:
    """Writes ``terrain`` into the live ``model``'s height field ``hfield``
    (its name or number): no recompile, no new model; the only allocation is
    numpy's view of ``model.hfield_data``. The field must have the terrain's
    ``hfield_shape(oversample)`` and size, and its elevation must reach the
    terrain's highest top; otherwise ``ValueError`` naming both, and the
    model is left as it was. In a loop, keep an ``HFieldSlot``."""
    HFieldSlot(model, hfield, oversample).write(terrain)


def max_top(scheme: Scheme) -> float:
    """The highest top any world of ``scheme`` can have, metres:
    ``scheme.max_top`` (``base + H·step_height`` with ``H`` the largest
    obstacle height the scheme allows; at least 1 step for frames)."""
    return scheme.max_top


def _field(
    scheme: Scheme, oversample: int, elevation: Union[float, None]
) -> tuple[tuple[int, int], tuple[float, float, float, float], tuple[float, float]]:
    """A field for every world of ``scheme``: its shape, MuJoCo's size
    (radii from rse-core's layout, elevation ``scheme.max_top`` unless
    given, base one block) and the grid's centre."""
    first = scheme.generate(index=0)
    shape, (rx, ry, _, _), (cx, cy, _) = first.hfield_layout(oversample)
    top = scheme.max_top if elevation is None else float(elevation)
    return shape, (rx, ry, top, first.block_size), (cx, cy)


def add_hfield(
    spec: Any,
    scheme: Scheme,
    oversample: int = DEFAULT_OVERSAMPLE,
    *,
    name: str = "terrain",
    elevation: Union[float, None] = None,
    centre: tuple[float, float] = (0.0, 0.0),
    group: int = 2,
) -> None:
    """Adds to ``spec`` (a ``mujoco.MjSpec``) a height field for every world
    of ``scheme`` and its geom in the world body, both named ``name``: the
    grid's centre at ``centre``, surface from z = 0 to ``elevation``
    (default ``max_top(scheme)``), in geom group ``group`` (2: drawn by
    default, and rays can select it alone). The field starts flat:
    ``set_hfield`` a terrain into the compiled model."""
    import mujoco

    (nrow, ncol), size, _ = _field(scheme, oversample, elevation)
    spec.add_hfield(
        name=name,
        nrow=nrow,
        ncol=ncol,
        size=list(size),
        userdata=[0.0] * (nrow * ncol),
    )
    spec.worldbody.add_geom(
        name=name,
        type=mujoco.mjtGeom.mjGEOM_HFIELD,
        hfieldname=name,
        pos=[centre[0], centre[1], 0.0],
        rgba=list(FIELD_RGBA),
        conaffinity=1,
        condim=3,
        group=group,
    )


def hfield_mjcf(
    scheme: Scheme,
    oversample: int = DEFAULT_OVERSAMPLE,
    *,
    name: str = "terrain",
    elevation: Union[float, None] = None,
) -> str:
    """An MJCF model of a ground for every world of ``scheme``: a height
    field named ``name`` sized for its grid at ``oversample``, its geom
    (also ``name``) with the grid's corner at the origin and its surface
    from z = 0 up to ``elevation`` (default ``max_top(scheme)``), and a
    light. The field starts flat: compile the model, then ``set_hfield`` a
    terrain into it (MuJoCo rescales samples given in MJCF to span [0, 1],
    so they cannot carry a terrain's true heights). Add a robot with
    ``mujoco.MjSpec.from_string(...)`` or by editing the text."""
    (nrow, ncol), size, (cx, cy) = _field(scheme, oversample, elevation)
    return field_model("rse_hfield", [name], (nrow, ncol), size, f"{floats((cx, cy))} 0", FIELD_RGBA_TEXT, light=(cx, cy))
