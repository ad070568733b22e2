"""Rays on each env's own field. mjlab's ray sensors that see the terrain
cast through MuJoCo Warp's direct ray test (``DirectRays``), which reads
the height field each world's terrain geom points at, in place: nothing
per env. Camera sensors render through the render context's BVHs, which
MuJoCo Warp builds only for the field the host model shows; for them each
env's field gets a Warp mesh of its own (``RayMeshes``), refitted in place
when a reset moves its samples."""

from __future__ import annotations

from typing import Any

import numpy as np

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


def cast_on_each_worlds_field(scene: Any, group: int) -> int:
    """Makes every ray sensor of an mjlab ``scene`` that can see geom
    ``group`` (its ``include_geom_groups`` holds it, or is None) cast with
    ``DirectRays``; returns how many do. Call it before the simulation
    captures its sense graph (``Simulation.create_graph``, which
    ``expand_model_fields`` calls)."""
    ctx = scene.sensor_context
    if ctx is None:
        return 0
    count = 0
    for sensor in ctx.raycast_sensors:
        groups = sensor.cfg.include_geom_groups
        if groups is not None and group not in groups:
            continue
        if not isinstance(sensor.raycast_kernel, DirectRays):
            sensor.raycast_kernel = DirectRays(sensor.raycast_kernel)
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
