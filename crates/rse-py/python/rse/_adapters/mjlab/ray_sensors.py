"""Rays on each env's own field. mjlab's ray sensors that see the terrain
cast through MuJoCo Warp's direct ray test, which reads the height field
each world's terrain geom points at, in place: nothing per env. One thread
a ray tests the few geoms the sensor sees (``FieldRays``); a sensor that
sees many geoms runs MuJoCo Warp's own kernel (``DirectRays``). Camera sensors render through the render context's BVHs, which
MuJoCo Warp builds only for the field the host model shows; for them each
env's field gets a Warp mesh of its own (``RayMeshes``), refitted in place
when a reset moves its samples."""

from __future__ import annotations

from typing import Any

import numpy as np

from rse._adapters import private
from rse._rse import EnvTerrains

RAY_LEAF = 4
"""Triangles per leaf of the ray meshes' BVHs."""


RAY_BYTES_PER_SAMPLE = 116
"""What a camera mesh (``RayMeshes``) costs per height-field sample: its
points (12 bytes) and its BVH (SAH, ``RAY_LEAF`` triangles a leaf),
measured with Warp 1.19 on a 160 × 160 field (2.94 MB)."""


class DirectRays:
    """A ray sensor's ``raycast_kernel`` (mjlab calls it with the render
    context, inside the sense graph it captures) that casts with no render
    context: ``mujoco_warp.rays``' direct test, whose ``ray_hfield`` reads
    the field that world ``w``'s terrain geom points at (``geom_dataid``
    per world) and tests the few cells under a ray. The context's BVH path
    needs a BVH per field, which MuJoCo Warp builds only for the field the
    host model shows: one mesh per env took 2.9 MB (11.8 GiB at 4096 envs)
    and a refit at each reset. The rays hit the same surface as before:
    MuJoCo's triangles of the same samples."""

    def __init__(self, kernel: Any) -> None:
        self.kernel = kernel

    def __call__(self, rc: Any = None) -> None:
        self.kernel(rc=None)


FIELD_RAY_GEOMS = 8
"""The most geoms a sensor may see for ``FieldRays`` to cast its rays; one
that sees more casts with MuJoCo Warp's kernel (``DirectRays``)."""


class FieldRays:
    """A ray sensor's ``raycast_kernel`` that casts one thread a ray over
    the geoms the sensor's groups can see (its ``candidates``: for the
    task's ``terrain_scan`` and ``foot_height_scan``, the terrain's geoms
    alone), each with MuJoCo Warp's own per-geom test, which reads the
    field world ``w``'s geom points at. MuJoCo Warp's direct kernel spends
    a block of 64 threads a ray on every geom of the scene and reduces
    them in shared memory: on an H200 at 4096 envs the Go1's two sensors
    took 15.9 ms a step that way against 2.5 ms for mjlab's BVH on its one
    terrain (2026-11-28). The hits are the same, bit for bit (a test
    compares them): the same test on the same geoms, the lowest geom id
    first at a tie as in MuJoCo Warp's reduction. The sensor's private
    buffers are listed in ``rse._adapters.private`` and checked here."""

    def __init__(self, sensor: Any, candidates: list[int]) -> None:
        import warp as wp

        from rse._adapters.mjlab.ray_kernel import cast_on_candidates, geom_model

        self._geom_model = geom_model
        self.sensor = sensor
        self.candidates = list(candidates)
        self._kernel = cast_on_candidates
        pnt = self._get("_ray_pnt")
        self._ids: Any = wp.array(np.asarray(candidates, dtype=np.int32), dtype=wp.int32, device=pnt.device)
        # Compiled now: mjlab launches it inside the sense graph it captures.
        wp.load_module(cast_on_candidates.module, device=pnt.device)

    def _get(self, name: str) -> Any:
        """The sensor's private ``name`` (one of ``SENSOR_BUFFERS``), read
        at each cast: mjlab may replace a buffer."""
        return private.getattr_checked(self.sensor, name, "mjlab")

    def __call__(self, rc: Any = None) -> None:
        import warp as wp

        b = {name: self._get(name) for name in SENSOR_BUFFERS if name != "_mj_model"}
        m, d, pnt = b["_model"].struct, b["_data"].struct, b["_ray_pnt"]
        wp.launch(
            self._kernel,
            dim=(d.nworld, pnt.shape[1]),
            inputs=[
                self._geom_model(m),
                d.geom_xpos,
                d.geom_xmat,
                self._ids,
                pnt,
                b["_ray_vec"],
                b["_geomgroup"],
                True,  # mjlab's sensors hit static geoms (flg_static)
                b["_ray_bodyexclude"],
            ],
            outputs=[b["_ray_dist"], b["_ray_geomid"], b["_ray_normal"]],
            device=pnt.device,
        )


SENSOR_BUFFERS = ("_model", "_data", "_mj_model", "_ray_pnt", "_ray_vec", "_geomgroup", "_ray_bodyexclude", "_ray_dist", "_ray_geomid", "_ray_normal")
"""The private names of mjlab's ``RayCastSensor`` that ``FieldRays`` reads
(each through ``private.getattr_checked``)."""

FIELD_RAY_TEST = ("_ray_geom_mesh", "MJ_MAXVAL", "vec6")
"""MuJoCo Warp's private names ``FieldRays``' kernel calls."""


def seen_geoms(model: Any, geomgroup: Any) -> list[int]:
    """The geoms of host ``model`` a ray with MuJoCo Warp's ``geomgroup``
    (six floats: -1 includes a group, 0 excludes it; all -1: every geom)
    may hit, by group alone, as MuJoCo Warp's ``_ray_eliminate`` decides
    (groups above 5 count as 5)."""
    groups = [float(geomgroup[i]) for i in range(6)]
    if all(g == -1.0 for g in groups):
        return list(range(model.ngeom))
    return [g for g in range(model.ngeom) if groups[min(5, max(0, int(model.geom_group[g])))] != 0.0]


def terrain_rays(sensor: Any) -> Any:
    """The ``raycast_kernel`` for an mjlab ray ``sensor`` that sees the
    terrain: ``FieldRays`` over the geoms it can see, or ``DirectRays``
    where it sees more than ``FIELD_RAY_GEOMS`` or this MuJoCo Warp lacks
    the per-geom test ``FieldRays`` calls (``FIELD_RAY_TEST``)."""
    kernel = sensor.raycast_kernel
    if isinstance(kernel, (FieldRays, DirectRays)):
        return kernel
    seen = seen_geoms(private.getattr_checked(sensor, "_mj_model", "mjlab"), private.getattr_checked(sensor, "_geomgroup", "mjlab"))
    test_there = not any(private.missing(u) for u in private.uses("mujoco_warp") if u.attribute in FIELD_RAY_TEST)
    if len(seen) <= FIELD_RAY_GEOMS and test_there:
        return FieldRays(sensor, seen)
    return DirectRays(kernel)


def cast_on_each_worlds_field(scene: Any, group: int) -> int:
    """Makes every ray sensor of an mjlab ``scene`` that can see geom
    ``group`` (its ``include_geom_groups`` holds it, or is None) cast on
    each world's own field (``terrain_rays``); returns how many do. Call it
    before the simulation captures its sense graph
    (``Simulation.create_graph``, which ``expand_model_fields`` calls)."""
    ctx = scene.sensor_context
    if ctx is None:
        return 0
    count = 0
    for sensor in ctx.raycast_sensors:
        groups = sensor.cfg.include_geom_groups
        if groups is not None and group not in groups:
            continue
        sensor.raycast_kernel = terrain_rays(sensor)
        count += 1
    return count


class RayMeshes:
    """For camera sensors: one Warp mesh per env's height field in a
    render context, the field's sample grid as MuJoCo triangulates it (two
    triangles a quad, split from its first corner to its opposite one),
    registered where the context keeps its height-field BVHs."""

    def __init__(self, model: Any, rc: Any, envs: EnvTerrains, name: str) -> None:
        import mujoco
        import warp as wp

        nrow, ncol = envs.field_shape
        self.hids = [mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_HFIELD, f"{name}{e}") for e in range(envs.num_envs)]
        sx, sy, self.sz, _ = model.hfield_size[self.hids[0]]
        c, r = np.meshgrid(np.arange(ncol), np.arange(nrow))
        self.xy = np.stack([sx * (c / (0.5 * max(ncol - 1, 1)) - 1.0), sy * (r / (0.5 * max(nrow - 1, 1)) - 1.0)], axis=-1).reshape(-1, 2)
        quad = (r[:-1, :-1] * ncol + c[:-1, :-1]).ravel()
        a, b, d, e = quad, quad + 1, quad + ncol, quad + ncol + 1
        indices = np.stack([a, b, e, a, e, d], axis=1).ravel().astype(np.int32)
        device = rc.hfield_bvh_id.device
        self.meshes = []
        # One index array for every env (the grids are alike), and the BVH
        # MuJoCo Warp builds for its own fields (SAH): 2.9 MB an env of
        # 160² samples, where a copy of the indices each and cuBQL's BVH
        # took 6.0 MB (4096 envs: 24 GB).
        shared: Any = wp.array(indices, dtype=wp.int32, device=device)
        for env in range(len(self.hids)):
            points: Any = wp.array(self._points(envs, env), dtype=wp.vec3, device=device)
            self.meshes.append(wp.Mesh(points=points, indices=shared, bvh_constructor="sah", bvh_leaf_size=RAY_LEAF))
        self.half = (sx, sy)
        self.attach(rc)

    def attach(self, rc: Any) -> None:
        """Registers the meshes in the render context ``rc`` in place of
        the BVHs it built for the pool's fields: the same meshes for a
        context made anew (mjlab recreates it when an event expands a model
        field), not a second set (1024 envs: 2.6 GB more)."""
        bvh_ids = rc.hfield_bvh_id.numpy()
        bounds = rc.hfield_bounds_size.numpy()
        for hid, mesh in zip(self.hids, self.meshes):
            rc.hfield_registry.pop(int(bvh_ids[hid]), None)
            rc.hfield_registry[mesh.id] = mesh
            bvh_ids[hid] = mesh.id
            # The box that holds every possible top: [0, elevation] in z.
            bounds[hid] = (*self.half, 0.5 * self.sz)
        rc.hfield_bvh_id.assign(bvh_ids)
        rc.hfield_bounds_size.assign(bounds)

    def _points(self, envs: EnvTerrains, e: int) -> np.ndarray:
        z = envs.samples[e].reshape(-1, 1).astype(np.float64) * self.sz
        return np.concatenate([self.xy, z], axis=1).astype(np.float32)

    def update(self, envs: EnvTerrains, ids: list[int]) -> None:
        """The meshes of ``ids`` to their fields' new samples."""
        for e in ids:
            mesh = self.meshes[e]
            mesh.points.assign(self._points(envs, e))
            mesh.refit()
