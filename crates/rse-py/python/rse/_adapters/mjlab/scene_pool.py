"""rse's pool in an mjlab scene: the envs' height fields, the terrain
geom that shows one per world, the ground at their foot, the coarse pool
and the view geom, added to the scene's ``MjSpec``; and what a pool of
``num_envs`` costs, checked before it is built."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from rse._adapters import contacts
from rse._adapters.mjlab.ray_sensors import RAY_BYTES_PER_SAMPLE
from rse._adapters.mjlab.terrains import probe_envs
from rse._adapters.pool import GEOM, POOL, add_env_geom
from rse._adapters.tiles import SchemeLike
from rse._adapters.uploads import staging
from rse._rse import EnvTerrains

BODY = "terrain"
"""The body rse's terrain geoms go in: the name mjlab's terrain importer
gives its terrain, which the velocity tasks' contact sensors
(``ContactMatch(mode="body", pattern="terrain")``) and rewards look for."""


GEOM_GROUP = 0
"""The geom group of the terrain: mjlab's ray sensors (``terrain_scan``,
the feet's ``TerrainHeightSensorCfg``) see group 0 only ("terrain only")."""


COARSE_GROUP = 3
"""The geom group of the coarse field the robot's large geoms collide
with: one the ray sensors do not see and MuJoCo's viewer hides."""


VIEW_GROUP = GEOM_GROUP
"""The geom group of the view geom (``apart``): the terrain's, which
mjlab's viewer draws and its ray sensors see. Where the envs are laid out
apart the exact geom is hidden (alpha 0), and MuJoCo Warp's rays skip a
hidden geom: they land on the view geom, the same field in the same
place."""


VIEW = "_view"
"""Suffix of the body and geom that show each env's terrain in its own
place when the envs are laid out apart."""


GROUND_DROP = 0.05
"""Metres the ground plane lies below the terrain's lowest top (0): it
catches a robot that walks off its slot, and no foot standing on the
terrain reaches it. Level with the terrain (as it was), every foot on a
top at height 0 touched both the field and the plane at one point: twice
the contacts, and the solver took twice the time (bench/mjlab_tasks.py)."""


def add_pool(spec: Any, scheme: SchemeLike, num_envs: int, *, oversample: Optional[int] = None, name: str = POOL, apart: bool = False) -> None:
    """Adds to an mjlab scene's ``spec`` the pool of ``num_envs`` height
    fields of ``scheme``'s slot shape (zeros until ``EnvTerrainsEvent``
    fills them), the terrain geom that shows one (``GEOM``, which
    ``rse.mujoco_warp`` routes per world) and a ground plane at the
    terrain's foot, so that a robot walking off its slot keeps a floor
    (mjlab's own plane where the scene has one: ``EnvTerrainCfg``).

    With more than one sample a cell, the robot's geoms too large for the
    exact field (a trunk, a thigh: ``rse._adapters.contacts``) collide with
    a coarse pool instead (``name + "_coarse"``, one sample a cell, geom
    ``GEOM + "_coarse"`` in group 3, unseen by the ray sensors), so that no
    pair passes MuJoCo's 50 prisms.

    ``apart``: for watching the envs laid out apart (``EnvTerrainCfg.apart``),
    a mocap body ``BODY + VIEW`` with a geom showing each world's field
    (no contacts, group ``VIEW_GROUP``) in place of the exact geom, which
    is hidden: a body mjlab's viewer draws for every env, not only the one
    it follows."""
    import mujoco

    probe = probe_envs(scheme, oversample)
    nrow, ncol = probe.field_shape
    zeros = np.zeros(nrow * ncol, dtype=np.float32)
    spec.add_hfield(name=f"{name}0", nrow=nrow, ncol=ncol, size=list(probe.hfield_size), userdata=zeros)
    # In a body named as mjlab's importer names its terrain, in the group
    # its ray sensors see: the tasks' sensors, rewards and terms find it.
    # Where mjlab built the scene's terrain as a plane (``EnvTerrainCfg``),
    # its body and plane are the pool's body and ground.
    body = spec.body(BODY)
    ground = spec.geom(BODY) if body is not None else None
    if body is None:
        body = spec.worldbody.add_body(name=BODY)
    exact = add_env_geom(spec, probe, f"{name}0", name=GEOM, group=GEOM_GROUP, body=body)
    if ground is None:
        ground = body.add_geom(name=f"{name}_ground", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05], rgba=[0.5, 0.5, 0.5, 1], group=GEOM_GROUP)
    ground.pos = [ground.pos[0], ground.pos[1], ground.pos[2] - GROUND_DROP]
    if apart:
        view = spec.worldbody.add_body(name=BODY + VIEW, mocap=True)
        shown = add_env_geom(spec, probe, f"{name}0", name=GEOM + VIEW, group=VIEW_GROUP, body=view)
        shown.contype, shown.conaffinity = 0, 0
        exact.rgba = [*exact.rgba[:3], 0.0]
    k = contacts.oversample_of(probe)
    # With one field in it, so that compiling it (the sensors name the
    # terrain body) stays cheap.
    small, large = contacts.split_geoms(spec, {exact.name, ground.name}, probe.terrain(0).block_size / k) if k > 1 else ([], [])
    for e in range(1, num_envs):
        spec.add_hfield(name=f"{name}{e}", nrow=nrow, ncol=ncol, size=list(probe.hfield_size), userdata=zeros)
    if not large:
        return
    cy, cx = contacts.slot_cells(probe)
    coarse_zeros = np.zeros(cy * cx, dtype=np.float32)
    for e in range(num_envs):
        spec.add_hfield(name=f"{name}{contacts.COARSE}{e}", nrow=cy, ncol=cx, size=contacts.coarse_size(probe), userdata=coarse_zeros)
    coarse = add_env_geom(spec, probe, f"{name}{contacts.COARSE}0", name=GEOM + contacts.COARSE, group=COARSE_GROUP, body=body)
    contacts.route_geoms(small, large, exact, coarse, ground)


def field_sizes(probe: EnvTerrains) -> tuple[int, int]:
    """The samples of an env's field of ``probe``'s shape and of its
    coarse field (0 without one: an oversample of 1)."""
    nrow, ncol = probe.field_shape
    cells = int(np.prod(contacts.slot_cells(probe))) if contacts.oversample_of(probe) > 1 else 0
    return nrow * ncol, cells


def pool_memory(probe: EnvTerrains, num_envs: int, device: str = "cpu", *, geoms: int = 0, cameras: bool = False) -> tuple[int, int]:
    """What ``num_envs`` envs of ``probe``'s shape cost in an mjlab scene,
    bytes, in host memory and on ``device`` (0 for "cpu", where it is all
    host memory): the samples (``EnvTerrains``) and the host model's fields
    (exact and coarse); on the device MuJoCo Warp's copy of the fields and
    each world's routing and bounds (its rows of ``geom_dataid`` and
    ``geom_aabb``, 28 bytes for each of the scene's ``geoms``, which mjlab
    expands per world for rse), and with camera sensors (``cameras``) their
    meshes (``RAY_BYTES_PER_SAMPLE``); on a GPU also the buffers a reset's
    rows go up through (``staging_bytes``, a few MiB whatever the envs).
    ``device_bytes`` counts the same from the arrays."""
    samples, cells = field_sizes(probe)
    host = num_envs * 4 * (2 * samples + cells)
    on_device = num_envs * (4 * (samples + cells) + 28 * geoms + (RAY_BYTES_PER_SAMPLE * samples if cameras else 0))
    if str(device).startswith("cpu"):
        return host + on_device, 0
    return host, on_device + staging_bytes(probe, num_envs)


def staging_bytes(probe: EnvTerrains, num_envs: int) -> int:
    """The device's buffers of a reset's upload (``Uploads``: its values
    and their places, bytes) once the scene's first write, every env's
    fields and boxes, has sized them: twice one send, up to
    ``Uploads.LIMIT`` values. As many bytes on the host, pinned; none on
    the CPU device, where the rows go straight into the model."""
    samples, cells = field_sizes(probe)
    # Each env's exact samples, its coarse ones, and a box (6 floats) for
    # each of its terrain geoms (the exact field's and the coarse one's).
    blocks = [(samples, num_envs), (cells, num_envs), (6, num_envs * (2 if cells else 1))]
    values, runs = staging(blocks)
    return 4 * values + 4 * 4 * runs  # float32 values, four int32 a run


def device_bytes(mjm: Any, m: Any, envs: EnvTerrains, name: str = POOL, *, cameras: bool = False) -> dict[str, int]:
    """What the pool ``name`` of ``envs`` holds on the device of ``m`` (a
    MuJoCo Warp model compiled from ``mjm``), bytes, by part, counted from
    the arrays themselves: the pool's fields and the coarse fields (their
    share of ``hfield_data``), each world's routing and bounds
    (``geom_dataid`` and ``geom_aabb`` expanded per world) and, with camera
    sensors (``cameras``), their meshes (``RAY_BYTES_PER_SAMPLE``: their
    points and BVHs). ``pool_memory`` estimates the same before the scene
    is built."""
    import mujoco

    n = envs.num_envs

    def fields(prefix: str) -> int:
        first = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_HFIELD, f"{prefix}0")
        if first < 0:
            return 0
        sizes = mjm.hfield_nrow[first : first + n].astype(np.int64) * mjm.hfield_ncol[first : first + n]
        return 4 * int(sizes.sum())  # float32 samples

    worlds, geoms = int(m.geom_dataid.shape[0]) - 1, int(m.geom_dataid.shape[1])
    return {
        "fields": fields(name),
        "coarse fields": fields(name + contacts.COARSE),
        # geom_dataid (an int) and geom_aabb (two vec3) a geom, per world.
        "routing and bounds": worlds * geoms * (4 + 24),
        "camera meshes": n * int(np.prod(envs.field_shape)) * RAY_BYTES_PER_SAMPLE if cameras else 0,
    }


def available_memory() -> Optional[int]:
    """``MemAvailable`` of ``/proc/meminfo``, bytes; None where there is none."""
    try:
        with open("/proc/meminfo") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None
