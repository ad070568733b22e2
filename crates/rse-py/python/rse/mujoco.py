"""A new rse terrain in a live MuJoCo model, without recompiling it.

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

from rse._rse import DEFAULT_OVERSAMPLE, EnvTerrains, Scheme, Terrain

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
        rgba=[0.76, 0.6, 0.42, 1.0],
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
    (nrow, ncol), (rx, ry, top, s), (cx, cy) = _field(scheme, oversample, elevation)
    return f"""<mujoco model="rse_hfield">
  <asset>
    <hfield name="{name}" nrow="{nrow}" ncol="{ncol}" size="{rx!r} {ry!r} {top!r} {s!r}"/>
  </asset>
  <worldbody>
    <light pos="{cx!r} {cy!r} 5" dir="0 0 -1"/>
    <geom name="{name}" type="hfield" hfield="{name}" pos="{cx!r} {cy!r} 0" rgba="0.76 0.6 0.42 1"/>
  </worldbody>
</mujoco>
"""


def env_hfield_names(envs: EnvTerrains, name: str = "rse_env") -> list[str]:
    """The height-field assets ``add_env_hfields`` makes: ``name0`` …
    ``name{n-1}`` for slots, ``name`` for tiles."""
    if envs.layout == "tiles":
        return [name]
    return [f"{name}{e}" for e in range(envs.num_envs)]


def add_env_hfields(spec: Any, envs: EnvTerrains, *, name: str = "rse_env") -> list[str]:
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
) -> Any:
    """Adds to the world body of ``spec`` a geom showing the height field
    ``hfield`` (one of ``add_env_hfields``'s), placed at ``envs.hfield_pos``
    plus ``offset``: its slot's (or the map's) frame moved by ``offset``.
    Returns the geom's spec."""
    import mujoco

    x, y, z = envs.hfield_pos
    return spec.worldbody.add_geom(
        name=name or hfield,
        type=mujoco.mjtGeom.mjGEOM_HFIELD,
        hfieldname=hfield,
        pos=[x + offset[0], y + offset[1], z + offset[2]],
        rgba=[0.76, 0.6, 0.42, 1.0],
        group=group,
    )


def env_hfields_mjcf(envs: EnvTerrains, *, name: str = "rse_env") -> str:
    """An MJCF model holding the height fields of ``envs`` (as
    ``add_env_hfields``: the pool for slots, the map for tiles) and a geom
    showing the first (``name0``; ``name`` for tiles) at ``hfield_pos``.
    The fields start flat (MJCF rescales given samples to span [0, 1]):
    compile, then ``sync_env_hfields(model, envs)``. Merge it into a robot
    model with ``MjSpec.attach`` or by editing the text."""
    nrow, ncol = envs.samples.shape[1:]
    rx, ry, top, base = envs.hfield_size
    x, y, z = envs.hfield_pos
    names = env_hfield_names(envs, name)
    fields = "\n".join(
        f'    <hfield name="{n}" nrow="{nrow}" ncol="{ncol}" size="{rx!r} {ry!r} {top!r} {base!r}"/>' for n in names
    )
    return f"""<mujoco model="rse_env_hfields">
  <asset>
{fields}
  </asset>
  <worldbody>
    <geom name="{names[0]}" type="hfield" hfield="{names[0]}" pos="{x!r} {y!r} {z!r}" rgba="0.76 0.6 0.42 1" group="2"/>
  </worldbody>
</mujoco>
"""


def _env_ids(envs: EnvTerrains, env_ids: Any) -> list[int]:
    """``env_ids`` (all when None) as ints, or ``ValueError`` naming it."""
    ids = np.arange(envs.num_envs) if env_ids is None else np.asarray(env_ids, dtype=np.int64).ravel()
    bad = ids[(ids < 0) | (ids >= envs.num_envs)]
    if bad.size:
        raise ValueError(f"env_ids: {int(bad[0])} is not an environment (0 to {envs.num_envs - 1})")
    return ids.tolist()


def _env_pool(model: Any, envs: EnvTerrains, name: str, argument: str = "model") -> tuple[int, np.ndarray, int]:
    """The height fields ``add_env_hfields`` made in the compiled ``model``
    (a ``MjModel``): the first one's id, every one's address in
    ``hfield_data`` and the samples of each. They were added one after the
    other, so the first and last names bound them; ``ValueError`` naming
    ``argument`` when they are not there, not one run, or of another size."""
    import mujoco

    names = env_hfield_names(envs, name)

    def hfield(n: str) -> int:
        hid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_HFIELD, n)
        if hid < 0:
            raise ValueError(f"{argument}: no height field named {n!r} (add them with add_env_hfields)")
        return hid

    first, last = hfield(names[0]), hfield(names[-1])
    if last - first != len(names) - 1:
        raise ValueError(f"{argument}: the height fields {names[0]} … {names[-1]} are not one pool (add them with add_env_hfields)")
    size = int(model.hfield_nrow[first]) * int(model.hfield_ncol[first])
    if size != envs.samples[0].size:
        raise ValueError(f"{argument}: height field {names[0]} holds {size} samples, but the envs' field has {envs.samples[0].size}")
    return first, np.asarray(model.hfield_adr[first : last + 1], dtype=np.int64), size


def _copy_env_samples(data: np.ndarray, envs: EnvTerrains, ids: list[int], adr: np.ndarray, size: int) -> None:
    """Copies the samples of ``ids`` into ``data`` (a model's
    ``hfield_data``, or a host view of a device copy of it) at ``adr``."""
    flat = envs.samples.reshape(-1)
    for e in ids:
        data[adr[e] : adr[e] + size] = flat[e * size : (e + 1) * size]


def sync_env_hfields(model: Any, envs: EnvTerrains, env_ids: Any = None, *, name: str = "rse_env") -> None:
    """Copies the samples of ``env_ids`` (all when None) from ``envs`` into
    the compiled ``model``'s height fields made by ``add_env_hfields``
    (slots: each env's own; tiles: the map, whole). Call it after
    ``envs.reset(env_ids)``; the model is not recompiled."""
    ids = [0] if envs.layout == "tiles" else _env_ids(envs, env_ids)
    _, adr, size = _env_pool(model, envs, name)
    _copy_env_samples(model.hfield_data, envs, ids, adr, size)
