"""The reset event term: every env its own ``rse.EnvTerrains`` slot, a new
terrain each time it resets, copied into the simulation (device model in
one upload, host model, coarse pool, camera meshes where cameras are) and
its origin into the scene."""

from __future__ import annotations

import weakref
from typing import Any, Optional

from rse._adapters.fields import geom_id
from rse._adapters.ids import env_ids as _env_ids
from rse._adapters.mjlab import terrain_bounds
from rse._adapters.mjlab.device_tops import DeviceTops
from rse._adapters.mjlab.large_geom_fields import CoarsePool
from rse._adapters.mjlab.near_bounds import NearRobotBounds, free_root, reach, terrain_colliders
from rse._adapters.mjlab.ray_sensors import RayMeshes, cast_on_each_worlds_field
from rse._adapters.mjlab.scene_pool import GEOM_GROUP, device_bytes
from rse._adapters.mjlab.terrains import (
    initial_difficulty,
    launcher_env_offset,
    make_envs,
    scheme_of,
    spread_of,
    terrain_settings,
)
from rse._adapters.mjlab.watch_layout import Apart
from rse._adapters.pool import GEOM, POOL, env_pool
from rse._adapters.torch_uploads import to_device
from rse._adapters.uploads import Filled, Uploads
from rse._rse import EnvTerrains, _env_keywords

TERM = "rse_terrain"
"""The default name of rse's reset event term in an mjlab env config (its
difficulty curriculum term is ``TERM + "_difficulty"``)."""


class EnvTerrainsEvent:
    """mjlab reset event term (``EventTermCfg(func=EnvTerrainsEvent,
    mode="reset", params=...)``, before the terms that place the robots):
    every env its own ``rse.EnvTerrains`` slot, a new terrain each time it
    resets, spawned at its env's origin.

    ``params``: ``scheme`` (a path, CSV text or ``rse.Scheme``), and
    optionally ``oversample``, ``seed``, ``difficulty``, ``spawn_radius``,
    ``env_offset``, ``name`` as ``rse.EnvTerrains`` takes them, and
    ``initial_levels`` (``(max_init_terrain_level, terrain_levels)``). Where
    the scene's terrain is an ``EnvTerrainCfg`` (``use_env_terrains``), its
    fields win: ``train``'s command line sets them. The scene must hold the
    pool (``add_pool``; ``use_env_terrains`` wires both).

    At construction it makes the ``EnvTerrains`` (``.envs``), makes the
    ray sensors that see the terrain cast on each world's own field
    (``DirectRays``), expands the model's ``geom_dataid`` and ``geom_aabb``
    per world (mjlab's ``expand_model_fields``, which captures the sense
    graph anew with them), points each world's terrain geom at its env's
    field and bounds it by that terrain's tops (``TerrainBounds``); each
    call resets the named envs, copies their samples into the simulation's
    model (and the host model, which mjlab's viewer draws) and writes their
    origins into ``env.scene.env_origins``.
    """

    def __init__(self, cfg: Any, env: Any) -> None:
        from rse.mujoco_warp import route

        p = {**dict(cfg.params), **terrain_settings(env.cfg.scene.terrain)}
        self.name = p.get("name", POOL)
        scheme = scheme_of(p["scheme"])
        offset = launcher_env_offset(env.num_envs) if p.get("env_offset") is None else p["env_offset"]
        self.env_offset = int(offset)
        spread = spread_of(p) if p.get("difficulty") is None else None
        self.terrain_levels: Optional[int] = p.get("terrain_levels")
        """The curriculum's levels (the scene's ``EnvTerrainCfg``), if any."""
        self.names: list[str] = list(getattr(scheme, "names", []))
        """A mix's scheme names, in order (empty for one scheme)."""
        # Every per-env option the scene's config (or the event) gives, by
        # its name in rse-core's table.
        options = {name: p[name] for name, *_ in _env_keywords() if name in p}
        options.update(env_offset=offset, difficulty=0.0 if spread is not None else p.get("difficulty"))
        self.envs = make_envs(scheme, env.num_envs, **options)
        if spread is not None:
            # Every env's first terrain at its own starting level.
            seed = self.envs.schemes[0].seed if p.get("seed") is None else p["seed"]
            self.envs.reset(list(range(env.num_envs)), difficulty=initial_difficulty(spread, env.num_envs, offset, seed))
        self._env = env
        self._rays_of: Any = None
        self._ray_meshes: Optional[RayMeshes] = None
        sim = env.sim
        self.direct_rays = cast_on_each_worlds_field(env.scene, GEOM_GROUP)
        """How many ray sensors cast on each world's own field."""
        sim.expand_model_fields(("geom_dataid", terrain_bounds.FIELD))
        route(sim.wp_model, sim.mj_model, self.envs, name=self.name)
        self._coarse = CoarsePool(sim.wp_model, sim.mj_model, self.envs, self.name)
        # The pool's addresses, read once: the host model and the device's
        # hold the fields at the same addresses.
        _, self._adr, self._size = env_pool(sim.mj_model, self.envs, self.name, "env.sim.mj_model")
        self._uploads = Uploads()
        self._bounds = terrain_bounds.TerrainBounds(
            sim.wp_model, sim.mj_model, [geom_id(sim.mj_model, GEOM, "env.scene", "add_pool adds it"), self._coarse.gid], self.envs
        )
        self.apart = Apart(sim, self.envs, self.name, bool(p.get("apart")))
        self._tops: Any = None
        self._halves: dict[Any, Any] = {}
        self._read: Optional[tuple[Any, int, list[int]]] = None
        self.near_robot = self._near_robot(env)
        """The terrain's bounds around each robot, renewed every step
        (``bound_near_robots``), or None where the scene's geoms that may
        touch the terrain are not all on one free body's tree."""
        self._copy_out(list(range(env.num_envs)))

    def exact_tops(self) -> DeviceTops:
        """The exact tops of every env on the simulation's device
        (``DeviceTops``), made on first use."""
        if self._tops is None:
            self._tops = DeviceTops(self._env.sim, self.envs, self.name)
        return self._tops

    def _near_robot(self, env: Any) -> Optional[NearRobotBounds]:
        """The bounds around the robot, or None where they cannot help: the
        geoms that may touch the terrain on several trees or on none that
        moves freely, or a reach without bound (an unlimited slide) or as
        wide as the terrain."""
        import math

        mjm = env.sim.mj_model
        colliders = terrain_colliders(mjm, self._bounds.gids)
        root = free_root(mjm, colliders)
        if root is None:
            return None
        far = reach(mjm, root, colliders)
        if not math.isfinite(far) or 2.0 * far >= float(min(self.apart.size)):
            return None
        horizon = env.step_dt + env.physics_dt
        return NearRobotBounds(env.sim, self._bounds.gids, root, far, horizon, self.exact_tops(), self.apart)

    def bound_near_robots(self) -> None:
        """Bounds each world's terrain by the square its robot can reach
        before the next step (``NearRobotBounds``), where the scene allows;
        the envs that reset after it in a step get their whole terrain's
        bounds back from the reset."""
        if self.near_robot is not None:
            self.near_robot.update(self._env.sim)

    def device_bytes(self) -> dict[str, int]:
        """What rse's terrains hold on the simulation's device, bytes, by
        part, counted from the arrays (``pool.device_bytes``), and the
        buffers a reset's rows go up through (``Uploads``; none on the CPU
        device)."""
        sim = self._env.sim
        parts = device_bytes(sim.mj_model, sim.wp_model, self.envs, self.name, cameras=self._ray_meshes is not None)
        return {**parts, "upload staging": self._uploads.device_bytes()}

    def _copy_out(self, ids: list[int], index: Any = None) -> None:
        """Copies the terrains of ``ids`` into the simulation's model (their
        exact and coarse samples and their geoms' boxes, in one upload:
        ``Uploads``; the fields copied from the pool a thread an env,
        ``EnvTerrains._copy_fields``) and the host model, their meshes into the cameras'
        render context (if any), and their origins into ``env_origins``
        (at ``index``, ``ids`` on the origins' device, made if None)."""
        import torch

        sim = self._env.sim
        m = sim.wp_model
        starts = self._adr[ids]
        self.envs._copy_fields(ids, sim.mj_model.hfield_data, starts)
        exact = Filled(self._size, lambda data, at, part: self.envs._copy_fields(ids[part], data, at))
        blocks = [(0, starts, exact, None), *self._coarse.blocks(sim.mj_model, self.envs, ids, 0), *self._bounds.blocks(self.envs, ids, 1)]
        self._uploads.write([m.hfield_data, terrain_bounds.flat_boxes(m)], blocks)
        self._refresh_rays(ids)
        origins = self._env.scene.env_origins
        if index is None:
            index = torch.as_tensor(ids, dtype=torch.long, device=origins.device)
        at = self.envs.origins[ids].copy()
        at[:, :2] += self.apart.offsets[ids]
        origins[index] = to_device(at, origins)
        self.apart.place(sim, ids, index)

    def _refresh_rays(self, ids: list[int]) -> None:
        """Brings the camera meshes of the fields of ``ids`` up to date in
        the render context of mjlab's camera sensors, where the scene has
        any. MuJoCo Warp's context holds a BVH per height field, built once
        from the host model and only for the fields the host model's geoms
        show (``pool0``): without this every other world's camera would see
        the first terrain as it was built. Each env's field gets a mesh of
        its own, the field's grid as MuJoCo triangulates it, made once; a
        reset moves its points and refits its BVH in place (a rebuild by
        MuJoCo Warp's own ``build_hfield_bvh`` took 72 ms a field). A
        context made anew (mjlab recreates it when an event expands a model
        field) gets the same meshes. Ray sensors need none
        (``DirectRays``)."""
        ctx = self._env.scene.sensor_context
        if ctx is None or not ctx.has_cameras:
            return
        rc = ctx.render_context
        if self._ray_meshes is None:
            self._rays_of = rc
            self._ray_meshes = RayMeshes(self._env.sim.mj_model, rc, self.envs, self.name)
            return
        if rc is not self._rays_of:
            self._rays_of = rc
            self._ray_meshes.attach(rc)
        self._ray_meshes.update(self.envs, ids)

    def __call__(self, env: Any, env_ids: Any, **params: Any) -> None:
        ids = self.ids(env_ids)
        self.envs.reset(ids)
        self._copy_out(ids, index_of(env_ids, ids, env.scene.env_origins.device))

    def ids(self, env_ids: Any) -> list[int]:
        """mjlab's ``env_ids`` as a list (``ids_of``), read once a reset:
        mjlab hands the curriculum term and this event the same tensor in
        a step's reset, changed by neither, and on a GPU each read waits
        for the device. Kept while that very tensor is handed over again
        in the same step (``common_step_counter``)."""
        import torch

        if not isinstance(env_ids, torch.Tensor):
            return ids_of(self._env, env_ids)
        step = self._env.common_step_counter
        if self._read is not None:
            tensor, seen, ids = self._read
            if tensor() is env_ids and seen == step:
                return list(ids)
        ids = ids_of(self._env, env_ids)
        self._read = (weakref.ref(env_ids), step, ids)
        return list(ids)

    def halves(self, like: Any) -> Any:
        """Half of each env's own terrain's shorter side (a mix may hold
        smaller grids), metres, from its scheme's grid (no terrain is
        read): a tensor of ``like``'s device and dtype, made once each."""
        import numpy as np
        import torch

        key = (like.device, like.dtype)
        if key not in self._halves:
            halves = np.array([0.5 * s.block_size * min(s.grid) for s in self.envs.schemes])
            self._halves[key] = torch.as_tensor(halves[self.envs.scheme_ids], dtype=like.dtype, device=like.device)
        return self._halves[key]


def ids_of(env: Any, env_ids: Any) -> list[int]:
    """mjlab's env ids (a tensor, a slice or None: all) as a list."""
    return _env_ids(env.num_envs, env_ids)


def index_of(env_ids: Any, ids: list[int], device: Any) -> Any:
    """``ids`` as an index tensor on ``device``: mjlab's own ``env_ids``
    where it is one already (a tensor of ints there, as a step's resets
    hand it over), so no copy goes up for it; else made from ``ids``."""
    import torch

    given = isinstance(env_ids, torch.Tensor) and env_ids.dim() == 1 and env_ids.device == torch.device(device)
    if given and env_ids.dtype in (torch.int64, torch.int32):
        return env_ids.long()
    return torch.as_tensor(ids, dtype=torch.long, device=device)


def env_terrains(env: Any, term: str = TERM) -> EnvTerrains:
    """The ``rse.EnvTerrains`` of a running mjlab ``env`` (its event term
    ``term``): episodes, difficulties, origins, ``heights_at`` for height
    scans."""
    return event_of(env, term).envs


def contact_sheet(env: Any, path: Optional[str] = None, term: str = TERM, **options: Any) -> bytes:
    """The contact sheet of a running mjlab ``env``'s terrains
    (``EnvTerrains.contact_sheet``: ``env_ids``, ``cols``,
    ``cell_pixels``), written to ``path`` when given; a mix's tiles name
    their scheme."""
    event = event_of(env, term)
    return event.envs.contact_sheet(path, names=event.names or None, **options)


def event_of(env: Any, term: str) -> EnvTerrainsEvent:
    """The ``EnvTerrainsEvent`` of ``env``'s event term ``term``."""
    func = env.event_manager.get_term_cfg(term).func
    if not isinstance(func, EnvTerrainsEvent):
        raise ValueError(f"term: event term {term!r} is not an rse.mjlab.EnvTerrainsEvent")
    return func
