"""Every mjlab env its own rse terrain, new every episode (docs/envs.md):
the pool of height fields added to the scene through its ``spec_fn``, a
reset event term that renews the reset envs' terrains and copies them into
the simulation, a difficulty curriculum term, and ``use_env_terrains``,
which wires them into an ``ManagerBasedRlEnvCfg``. ``rse.mjlab`` re-exports
them beside its sub-terrain config."""

from __future__ import annotations

from typing import Any, Optional, Union

import numpy as np

from rse._adapters import contacts, private
from rse._adapters.ids import env_ids as _env_ids
from rse._adapters.pool import GEOM, POOL, add_env_geom, sync_env_hfields
from rse._adapters.tiles import SchemeLike, launcher_rank, load
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

VIEW_GROUP = 1
"""The geom group of the view geom (``apart``): one mjlab's viewer draws
and its ray sensors (group 0 only) do not see."""

VIEW = "_view"
"""Suffix of the body and geom that show each env's terrain in its own
place when the envs are laid out apart."""

APART_GAP = 1.0
"""Metres between two envs' slots when they are laid out apart."""

RAY_LEAF = 4
"""Triangles per leaf of the ray meshes' BVHs."""

RAY_BYTES_PER_SAMPLE = 116
"""What a ray mesh costs per height-field sample: its points (12 bytes)
and its BVH (SAH, ``RAY_LEAF`` triangles a leaf), measured with Warp 1.19
on a 160 × 160 field (2.94 MB)."""

GROUND_DROP = 0.05
"""Metres the ground plane lies below the terrain's lowest top (0): it
catches a robot that walks off its slot, and no foot standing on the
terrain reaches it. Level with the terrain (as it was), every foot on a
top at height 0 touched both the field and the plane at one point: twice
the contacts, and the solver took twice the time (bench/mjlab_tasks.py)."""

TERM = "rse_terrain"
"""The default name of rse's reset event term in an mjlab env config (its
difficulty curriculum term is ``TERM + "_difficulty"``)."""

def make_envs(scheme: Any, num_envs: int, **options: Any) -> EnvTerrains:
    """``rse.EnvTerrains`` of ``num_envs`` envs of a scheme (anything
    ``scheme_of`` reads) or a mix (``rse._mjlab_scene.Mix``)."""
    from rse._mjlab_scene import Mix

    scheme = scheme_of(scheme)
    if isinstance(scheme, Mix):
        return EnvTerrains(scheme.schemes, num_envs, proportions=scheme.proportions, **options)
    return EnvTerrains(scheme, num_envs, **options)


def _probe(scheme: SchemeLike, oversample: Optional[int]) -> EnvTerrains:
    """One env of ``scheme`` (or a mix): the slot's shape and size, which
    do not depend on the number of envs."""
    return make_envs(scheme, 1, oversample=oversample)


def add_pool(
    spec: Any, scheme: SchemeLike, num_envs: int, *, oversample: Optional[int] = None, name: str = POOL, apart: bool = False
) -> None:
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

    probe = _probe(scheme, oversample)
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
    cy, cx = probe.terrain(0).heights.shape
    coarse_zeros = np.zeros(cy * cx, dtype=np.float32)
    for e in range(num_envs):
        spec.add_hfield(name=f"{name}{contacts.COARSE}{e}", nrow=cy, ncol=cx, size=contacts.coarse_size(probe), userdata=coarse_zeros)
    coarse = add_env_geom(spec, probe, f"{name}{contacts.COARSE}0", name=GEOM + contacts.COARSE, group=COARSE_GROUP, body=body)
    contacts.route_geoms(small, large, exact, coarse, ground)


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

    At construction it makes the ``EnvTerrains`` (``.envs``), expands the
    model's ``geom_dataid`` per world (mjlab's ``expand_model_fields``) and
    points each world's terrain geom at its env's field; each call resets
    the named envs, copies their samples into the simulation's model (and
    the host model, which mjlab's viewer draws) and writes their origins
    into ``env.scene.env_origins``.
    """

    def __init__(self, cfg: Any, env: Any) -> None:
        from rse.mujoco_warp import route

        p = {**dict(cfg.params), **_terrain_settings(env.cfg.scene.terrain)}
        self.name = p.get("name", POOL)
        scheme = scheme_of(p["scheme"])
        offset = launcher_env_offset(env.num_envs) if p.get("env_offset") is None else p["env_offset"]
        self.env_offset = int(offset)
        spread = _spread(p) if p.get("difficulty") is None else None
        self.terrain_levels: Optional[int] = p.get("terrain_levels")
        """The curriculum's levels (the scene's ``EnvTerrainCfg``), if any."""
        self.names: list[str] = list(getattr(scheme, "names", []))
        """A mix's scheme names, in order (empty for one scheme)."""
        self.envs = make_envs(
            scheme,
            env.num_envs,
            oversample=p.get("oversample"),
            seed=p.get("seed"),
            difficulty=0.0 if spread is not None else p.get("difficulty"),
            env_offset=offset,
            spawn_radius=p.get("spawn_radius"),
        )
        if spread is not None:
            # Every env's first terrain at its own starting level.
            seed = self.envs.schemes[0].seed if p.get("seed") is None else p["seed"]
            self.envs.reset(list(range(env.num_envs)), difficulty=initial_difficulty(spread, env.num_envs, offset, seed))
        self._env = env
        self._rays_of: Any = None
        self._ray_meshes: Optional[_RayMeshes] = None
        sim = env.sim
        sim.expand_model_fields(("geom_dataid",))
        route(sim.wp_model, sim.mj_model, self.envs, name=self.name)
        self._coarse = _CoarsePool(sim.wp_model, sim.mj_model, self.envs, self.name)
        self.apart = _Apart(sim, self.envs, self.name, bool(p.get("apart")))
        self._copy_out(list(range(env.num_envs)))

    def _copy_out(self, ids: list[int]) -> None:
        """Copies the terrains of ``ids`` into the simulation's model and
        the host model, their ray-cast meshes into the sensors' render
        context, and their origins into ``env_origins``."""
        import torch

        from rse.mujoco_warp import sync

        sim = self._env.sim
        sync(sim.wp_model, sim.mj_model, self.envs, ids, name=self.name)
        sync_env_hfields(sim.mj_model, self.envs, ids, name=self.name)
        self._coarse.sync(sim.wp_model, sim.mj_model, self.envs, ids)
        self._refresh_rays(ids)
        origins = self._env.scene.env_origins
        index = torch.as_tensor(ids, dtype=torch.long, device=origins.device)
        at = self.envs.origins[ids].copy()
        at[:, :2] += self.apart.offsets[ids]
        origins[index] = torch.as_tensor(at, dtype=origins.dtype, device=origins.device)
        self.apart.place(sim, ids)

    def _refresh_rays(self, ids: list[int]) -> None:
        """Brings the ray-cast meshes of the fields of ``ids`` up to date in
        the render context of mjlab's ray sensors (``terrain_scan``, the
        feet's height sensors). MuJoCo Warp's context holds a BVH per height
        field, built once from the host model and only for the fields the
        host model's geoms show (``pool0``): without this every other
        world's rays would miss its terrain, and all would see the first
        terrain as it was built. Each env's field gets a mesh of its own,
        the field's grid as MuJoCo triangulates it, made once; a reset moves
        its points and refits its BVH in place (a rebuild by MuJoCo Warp's
        own ``build_hfield_bvh`` took 72 ms a field). A context made anew
        (mjlab recreates it when an event expands a model field) gets the
        same meshes."""
        ctx = private.getattr_checked(self._env.sim, "_sensor_context", "mjlab")
        if ctx is None or not ctx.has_raycasts:
            return
        rc = ctx.render_context
        if self._ray_meshes is None:
            self._rays_of = rc
            self._ray_meshes = _RayMeshes(self._env.sim.mj_model, rc, self.envs, self.name)
            return
        if rc is not self._rays_of:
            self._rays_of = rc
            self._ray_meshes.attach(rc)
        self._ray_meshes.update(self.envs, ids)

    def __call__(self, env: Any, env_ids: Any, **params: Any) -> None:
        ids = _ids(env, env_ids)
        self.envs.reset(ids)
        self._copy_out(ids)


def _route_per_world(m: Any, gid: int, first: int) -> None:
    """Points geom ``gid`` of world ``w`` of the device model ``m`` at
    height field ``first + w`` (``geom_dataid`` batched per world), leaving
    every other geom's routing as it is."""
    import warp as wp

    dataid = m.geom_dataid.numpy()
    dataid[:, gid] = first + np.arange(dataid.shape[0])
    wp.copy(m.geom_dataid, wp.array(dataid, dtype=int, device=m.geom_dataid.device))


class _CoarsePool:
    """The coarse fields ``add_pool`` made for the robot's large geoms, if
    any: their geom routed to env ``w``'s coarse field in world ``w``, and
    the reset envs' coarse samples copied in beside the exact ones."""

    def __init__(self, m: Any, mjm: Any, envs: EnvTerrains, name: str) -> None:
        import mujoco

        self.gid = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, GEOM + contacts.COARSE)
        if self.gid < 0:
            return
        first = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_HFIELD, f"{name}{contacts.COARSE}0")
        self.adr = np.asarray(mjm.hfield_adr[first : first + envs.num_envs], dtype=np.int64)
        _route_per_world(m, self.gid, first)

    def sync(self, m: Any, mjm: Any, envs: EnvTerrains, ids: list[int]) -> None:
        import warp as wp

        if self.gid < 0:
            return
        # Gathered once, for the host model and the device's.
        samples = contacts.coarse_samples(envs, ids)
        contacts.copy_coarse(mjm.hfield_data, samples, ids, self.adr)
        if m.hfield_data.device.is_cpu:
            contacts.copy_coarse(m.hfield_data.numpy(), samples, ids, self.adr)
            return
        size = samples[0].size if len(ids) else 0
        source: Any = wp.array(samples.reshape(-1), dtype=float, device="cpu", copy=False)
        for i, e in enumerate(ids):
            wp.copy(m.hfield_data, source, dest_offset=int(self.adr[e]), src_offset=i * size, count=size)


class _Apart:
    """Where each env's terrain is in its world: all at one place (the
    default: every env in a world of its own), or laid out on a grid,
    ``APART_GAP`` between slots, as mjlab's own terrain lays its envs out,
    so that a viewer drawing every world at once shows each robot on its
    own terrain. ``offsets[e]`` is env ``e``'s xy shift: its terrain geoms
    (per-world ``geom_pos``), its origin and its view body (``mocap_pos``)
    move by it."""

    def __init__(self, sim: Any, envs: EnvTerrains, name: str, on: bool) -> None:
        import mujoco
        import warp as wp

        n = envs.num_envs
        self.offsets = np.zeros((n, 2))
        self.mocap = -1
        if not on:
            return
        self.offsets = apart_offsets(envs)
        mjm, m = sim.mj_model, sim.wp_model
        if "geom_pos" not in sim.expanded_fields:
            sim.expand_model_fields(("geom_pos",))
            m = sim.wp_model
        pos = m.geom_pos.numpy()
        for geom in (GEOM, GEOM + contacts.COARSE):
            gid = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, geom)
            if gid >= 0:
                pos[:, gid, :2] = mjm.geom_pos[gid, :2] + self.offsets
        wp.copy(m.geom_pos, wp.array(pos, dtype=wp.vec3, device=m.geom_pos.device))
        view = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, GEOM + VIEW)
        if view < 0:
            raise ValueError("apart: the scene has no view geom (add_pool(..., apart=True) makes it)")
        _route_per_world(m, view, mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_HFIELD, f"{name}0"))
        self.mocap = int(mjm.body_mocapid[mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_BODY, BODY + VIEW)])

    def slot_xy(self, xy: Any) -> Any:
        """World xy (torch, ``[num_envs, ..., 2]``) in each env's slot
        frame: less its env's offset."""
        import torch

        if not self.offsets.any():
            return xy
        shift = torch.as_tensor(self.offsets, dtype=xy.dtype, device=xy.device)
        return xy - shift.view(shift.shape[0], *([1] * (xy.dim() - 2)), 2)

    def place(self, sim: Any, ids: list[int]) -> None:
        """Puts the view bodies of ``ids`` at their envs' places (a reset
        may have put them back)."""
        import torch

        if self.mocap < 0 or not ids:
            return
        mocap = sim.data.mocap_pos
        index = torch.as_tensor(ids, dtype=torch.long, device=mocap.device)
        at = torch.zeros((len(ids), 3), dtype=mocap.dtype, device=mocap.device)
        at[:, :2] = torch.as_tensor(self.offsets[ids], dtype=mocap.dtype, device=mocap.device)
        mocap[index, self.mocap] = at


def apart_offsets(envs: EnvTerrains) -> np.ndarray:
    """The xy shift of each env's slot laid out apart: a grid of
    ``ceil(sqrt(num_envs))`` columns, ``APART_GAP`` metres between slots,
    env ``e`` in row ``e // cols``, column ``e % cols``."""
    x, y, _ = envs.hfield_pos
    n = envs.num_envs
    cols = max(int(np.ceil(np.sqrt(n))), 1)
    e = np.arange(n)
    return np.stack([(e % cols) * (2.0 * x + APART_GAP), (e // cols) * (2.0 * y + APART_GAP)], axis=1)


class _RayMeshes:
    """One Warp mesh per env's height field in a render context, the
    field's sample grid as MuJoCo triangulates it (two triangles a quad,
    split from its first corner to its opposite one), registered where the
    context keeps its height-field BVHs."""

    def __init__(self, model: Any, rc: Any, envs: EnvTerrains, name: str) -> None:
        import mujoco
        import warp as wp

        nrow, ncol = envs.field_shape
        self.hids = [mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_HFIELD, f"{name}{e}") for e in range(envs.num_envs)]
        sx, sy, self.sz, _ = model.hfield_size[self.hids[0]]
        c, r = np.meshgrid(np.arange(ncol), np.arange(nrow))
        self.xy = np.stack(
            [sx * (c / (0.5 * max(ncol - 1, 1)) - 1.0), sy * (r / (0.5 * max(nrow - 1, 1)) - 1.0)], axis=-1
        ).reshape(-1, 2)
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


def initial_difficulty(spread: tuple[int, int], num_envs: int, env_offset: int, seed: int) -> np.ndarray:
    """mjlab's start (``TerrainEntityCfg.max_init_terrain_level``) in rse's
    difficulty: ``spread`` is ``(max_init_level, levels)``; each env starts
    at a level drawn uniformly from 0 … ``max_init_level``, level ``i``
    being difficulty ``i / (levels - 1)``, as mjlab's rows are. Drawn by
    global env id (``env_offset`` on) from ``seed``: the same on every
    machine and for any split of the envs over processes."""
    max_init, levels = spread
    drawn = np.random.default_rng([seed, 0x52534531]).integers(0, max_init + 1, size=env_offset + num_envs)
    return drawn[env_offset:] / max(levels - 1, 1)


def launcher_env_offset(num_envs: int) -> int:
    """The first global env id of this process when a launcher started one
    process per GPU (mjlab's ``train`` through torchrunx, ``torchrun``):
    ``RANK · num_envs``, so every process draws other terrains and the
    whole run is the terrains of one process with all the envs. 0 outside
    such a launch. An explicit ``env_offset`` wins."""
    return launcher_rank() * num_envs


def _ids(env: Any, env_ids: Any) -> list[int]:
    """mjlab's env ids (a tensor, a slice or None: all) as a list."""
    return _env_ids(env.num_envs, env_ids)


def env_terrains(env: Any, term: str = TERM) -> EnvTerrains:
    """The ``rse.EnvTerrains`` of a running mjlab ``env`` (its event term
    ``term``): episodes, difficulties, origins, ``heights_at`` for height
    scans."""
    return _event(env, term).envs


def contact_sheet(env: Any, path: Optional[str] = None, term: str = TERM, **options: Any) -> bytes:
    """The contact sheet of a running mjlab ``env``'s terrains
    (``EnvTerrains.contact_sheet``: ``env_ids``, ``cols``,
    ``cell_pixels``), written to ``path`` when given; a mix's tiles name
    their scheme."""
    event = _event(env, term)
    return event.envs.contact_sheet(path, names=event.names or None, **options)


def _event(env: Any, term: str) -> EnvTerrainsEvent:
    """The ``EnvTerrainsEvent`` of ``env``'s event term ``term``."""
    func = env.event_manager.get_term_cfg(term).func
    if not isinstance(func, EnvTerrainsEvent):
        raise ValueError(f"term: event term {term!r} is not an rse.mjlab.EnvTerrainsEvent")
    return func


def terrain_difficulty(
    env: Any,
    env_ids: Any,
    term: str = TERM,
    asset_name: str = "robot",
    step: Optional[float] = None,
    command_name: Optional[str] = None,
) -> dict[str, float]:
    """mjlab curriculum term: mjlab's terrain-levels rule (as its velocity
    task's ``terrain_levels_vel``), continuous. An env whose robot walked
    farther than half its slot's shorter side from its origin gets
    ``step`` more difficulty, one that walked less than half of what its
    command asked (``command_name``; without one, a quarter of the slot)
    ``step`` less, clamped to [0, 1]; ``EnvTerrainsEvent``, which runs
    after the curriculum at a reset, then draws their new terrains at it.
    Frozen on the first reset, before any step (the robots stand at their
    spawn points). ``step`` None: one level of the scene's
    ``EnvTerrainCfg.terrain_levels`` (``1 / (levels - 1)``), else 0.1.
    Returns the mean and max difficulty for mjlab's log."""
    import torch

    event = _event(env, term)
    envs = event.envs
    if step is None:
        step = 1.0 / (event.terrain_levels - 1) if event.terrain_levels else 0.1
    ids = _ids(env, env_ids)
    if env.common_step_counter > 0 and ids:
        index = torch.as_tensor(ids, dtype=torch.long, device=env.device)
        walked = torch.norm(env.scene[asset_name].data.root_link_pos_w[index, :2] - env.scene.env_origins[index, :2], dim=1)
        t = envs.terrain(0)
        half = 0.5 * t.block_size * min(t.heights.shape)
        up = walked > half
        if command_name is None:
            down = walked < half / 2
        else:
            command = env.command_manager.get_command(command_name)
            down = walked < torch.norm(command[index, :2], dim=1) * env.max_episode_length_s * 0.5
        moves = (up.int() - (down & ~up).int()).cpu().numpy()
        d = envs.difficulty
        d[ids] = np.clip(d[ids] + step * moves, 0.0, 1.0)
    logged = {"mean": float(envs.difficulty.mean()), "max": float(envs.difficulty.max())}
    # A mix: each scheme's mean, as mjlab logs each sub-terrain's level.
    if event.names:
        drawn = envs.scheme_ids
        for j, name in enumerate(event.names):
            mine = drawn == j
            if mine.any():
                logged[name] = float(envs.difficulty[mine].mean())
    return logged


def exact_height_scan(
    env: Any,
    sensor_name: str = "terrain_scan",
    term: str = TERM,
    offset: float = 0.0,
    miss_value: Optional[float] = None,
) -> Any:
    """mjlab observation term: the height scan of the ray sensor
    ``sensor_name`` (its pattern, frames and shape, as mjlab's
    ``height_scan`` gives it: each ray's frame height above the terrain
    under it, ``[B, F·N]``), from ``heights_at`` instead of the rays: the
    exact tops, also within a sample of a step edge, where the height
    field is MuJoCo's slope between two samples. Off an env's terrain the
    top is the ground plane at its foot (0); a point farther below its
    frame than the sensor's ``max_distance`` is a miss (``miss_value``,
    default ``max_distance``), as for the rays. The sensor must cast its
    rays straight down (a grid pattern), as the velocity tasks' does.
    Use it in place of ``height_scan``:
    ``ObservationTermCfg(func=exact_height_scan, params={"sensor_name": "terrain_scan"})``."""
    import torch

    sensor = env.scene[sensor_name]
    event = _event(env, term)
    envs = event.envs
    origins = private.getattr_checked(sensor, "_cached_world_origins", "mjlab")
    if origins is None:
        raise ValueError(f"sensor_name: {sensor_name!r} has cast no rays yet (step or reset the env first)")
    B = origins.shape[0]
    xy = event.apart.slot_xy(origins[..., :2].detach()).to("cpu", torch.float64).numpy()
    tops = envs.heights_at(np.arange(B), xy)
    tops = torch.as_tensor(np.nan_to_num(tops, nan=0.0), device=origins.device, dtype=origins.dtype)
    F, N = sensor.num_frames, sensor.num_rays_per_frame
    frame_z = sensor.data.frame_pos_w[:, :, 2:3]
    heights = (frame_z - tops.view(B, F, N) - offset).view(B, F * N)
    if miss_value is None:
        miss_value = sensor.cfg.max_distance
    reach = (frame_z - tops.view(B, F, N)).view(B, F * N)
    return torch.where(reach > sensor.cfg.max_distance, torch.full_like(heights, miss_value), heights)


def scheme_of(scheme: Any) -> Any:
    """``scheme`` as an ``rse.Scheme``: one already, CSV text (a string
    with a line break), or a CSV file's path; a mix
    (``rse._mjlab_scene.Mix``) as it is."""
    from rse._mjlab_scene import Mix
    from rse._rse import Scheme

    if isinstance(scheme, Mix):
        return scheme
    if isinstance(scheme, str) and "\n" in scheme:
        return Scheme.from_csv(scheme, "env.scene.terrain.scheme")
    return load(scheme)


def scheme_setting(scheme: SchemeLike) -> str:
    """``scheme`` as ``EnvTerrainCfg.scheme`` holds it: a path as text, CSV
    text as it is, an ``rse.Scheme`` as its CSV (so the run's logged
    config holds the whole scheme)."""
    from rse._rse import Scheme

    if isinstance(scheme, Scheme):
        return scheme.to_csv()
    return str(scheme)


def _terrain_settings(terrain: Any) -> dict[str, Any]:
    """The fields of an ``EnvTerrainCfg`` scene terrain as event params;
    nothing for another terrain (or none). The scheme is the text the
    config read and recorded (``scheme_csv``), not its path read again."""
    if type(terrain).__name__ != "EnvTerrainCfg":
        return {}
    keys = ("scheme", "seed", "difficulty", "oversample", "spawn_radius", "apart", "max_init_terrain_level", "terrain_levels")
    settings = {k: getattr(terrain, k) for k in keys}
    settings["scheme"] = terrain.scheme_csv or terrain.scheme
    if terrain.schemes:
        from rse._mjlab_scene import Mix
        from rse._rse import Scheme

        # A mix, from the texts the config read.
        names, texts = list(terrain.schemes_csv), list(terrain.schemes_csv.values())
        schemes = [Scheme.from_csv(t, n) for n, t in zip(names, texts)]
        settings["scheme"] = Mix(names, schemes, [float(p) for p in terrain.schemes.values()], texts)
    return settings


def _spread(params: dict[str, Any]) -> Optional[tuple[int, int]]:
    """The envs' starting levels, ``(max_init_terrain_level,
    terrain_levels)``: the scene's ``EnvTerrainCfg`` fields where it has
    them (clamped to the levels, as mjlab clamps it), else the event's
    ``initial_levels`` param; None without levels."""
    given = params.get("initial_levels")
    levels = params.get("terrain_levels")
    max_init = params.get("max_init_terrain_level")
    if levels is None and given is not None:
        levels = given[1]
    if max_init is None and given is not None:
        max_init = given[0]
    if levels is None or max_init is None:
        return None
    if max_init < 0:
        raise ValueError(f"env.scene.terrain.max_init_terrain_level: {max_init}; expected 0 or more")
    return (min(int(max_init), int(levels) - 1), int(levels))


class _PoolSpec:
    """The scene's ``spec_fn``: the earlier one, then rse's pool, one field
    per env of the scene being built. Everything is read from the ``Scene``
    mjlab is building (the caller of ``spec_fn``): its env count and its
    ``EnvTerrainCfg``, as mjlab's ``train`` and ``play`` rebuilt it from the
    registered config with the command line's overrides
    (``--env.scene.num-envs 4096``, ``--env.scene.terrain.scheme``). It
    holds no settings of its own, so a run's logged config (``env.yaml``)
    has the scheme once, where it was set."""

    def __init__(self, earlier: Any) -> None:
        self.earlier = earlier

    def __call__(self, spec: Any) -> None:
        if self.earlier is not None:
            self.earlier(spec)
        scene, device = _scene_being_built()
        if type(scene.terrain).__name__ != "EnvTerrainCfg":
            raise ValueError(
                "env_cfg.scene.terrain: rse's pool needs the EnvTerrainCfg use_env_terrains set; "
                f"the scene's terrain is a {type(scene.terrain).__name__}"
            )
        from rse._mjlab_scene import check

        _play_the_runs_scheme(scene.terrain)
        # Fields set by assignment after the config was made (and the
        # run's, in play) were not checked: checked and recorded now, once,
        # before anything is built.
        check(scene.terrain)
        settings = _terrain_settings(scene.terrain)
        scheme = scheme_of(settings["scheme"])
        oversample = settings["oversample"]
        n = int(scene.num_envs)
        host, on_device = pool_memory(_probe(scheme, oversample), n, device)
        print(
            f"[INFO] rse terrains: {n} envs, {(host + on_device) / n / 2**20:.2f} MiB an env, "
            f"{host / 2**30:.2f} GiB in host memory" + (f" and {on_device / 2**30:.2f} GiB on {device}" if on_device else "")
        )
        available = _available_memory()
        if available is not None and host > available:
            raise MemoryError(
                f"env.scene.num_envs: {n} envs of this scheme take about {host / 2**30:.1f} GiB of host memory "
                f"and {available / 2**30:.1f} GiB is available; use fewer envs, a smaller scheme or "
                "--env.scene.terrain.oversample 1"
            )
        add_pool(spec, scheme, n, oversample=oversample, apart=bool(settings.get("apart")))


def pool_memory(probe: EnvTerrains, num_envs: int, device: str = "cpu") -> tuple[int, int]:
    """What ``num_envs`` envs of ``probe``'s shape cost in an mjlab scene,
    bytes, in host memory and on ``device`` (0 for "cpu", where it is all
    host memory): the samples (``EnvTerrains``), the host model's fields
    (exact and coarse), MuJoCo Warp's copy of them, and the ray sensors'
    meshes (``RAY_BYTES_PER_SAMPLE``)."""
    nrow, ncol = probe.field_shape
    samples = nrow * ncol
    cells = probe.terrain(0).heights.size if contacts.oversample_of(probe) > 1 else 0
    host = num_envs * 4 * (2 * samples + cells)
    on_device = num_envs * (4 * (samples + cells) + RAY_BYTES_PER_SAMPLE * samples)
    if str(device).startswith("cpu"):
        return host + on_device, 0
    return host, on_device


def _available_memory() -> Optional[int]:
    """``MemAvailable`` of ``/proc/meminfo``, bytes; None where there is none."""
    try:
        with open("/proc/meminfo") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def _play_the_runs_scheme(terrain: Any) -> None:
    """In mjlab's ``play`` of a checkpoint whose run recorded its terrains
    (``rse._mjlab_run``), the terrain's scheme and seed become the run's,
    and it says so: ``play`` takes no terrain flags, and would show the
    task's registered scheme. Found as ``run_play``'s ``resume_path`` on
    the call stack (``play`` builds the env inside it); elsewhere nothing
    changes."""
    from rse._mjlab_run import run_terrain

    def resume_path(frame: Any) -> Any:
        if frame.f_code.co_name == "run_play" and frame.f_globals.get("__name__", "").startswith("mjlab."):
            return frame.f_locals.get("resume_path")
        return None

    resume = _on_the_stack(resume_path)
    recorded = run_terrain(str(resume)) if resume is not None else None
    if recorded is None:
        return
    for name, value in recorded.items():
        setattr(terrain, name, value)
    shown = recorded["scheme"] or ", ".join(recorded["schemes"])
    print(f"[INFO] rse: playing on what the run trained on: {shown} (seed {terrain.seed})")


def _on_the_stack(pick: Any) -> Any:
    """The first value ``pick(frame)`` gives that is not None, walking up
    the call stack from the caller; None if none does."""
    import inspect

    frame = inspect.currentframe()
    try:
        while frame is not None:
            found = pick(frame)
            if found is not None:
                return found
            frame = frame.f_back
    finally:
        del frame
    return None


def _scene_being_built() -> tuple[Any, str]:
    """The ``SceneCfg`` and device of the mjlab ``Scene`` whose construction
    called this (through ``spec_fn``)."""
    from mjlab.scene import Scene

    def scene(frame: Any) -> Any:
        owner = frame.f_locals.get("self")
        if isinstance(owner, Scene):
            return private.getattr_checked(owner, "_cfg", "mjlab"), str(owner.device)
        return None

    found = _on_the_stack(scene)
    if found is None:
        raise ValueError("env_cfg.scene.spec_fn: rse's pool is added while mjlab's Scene builds the scene (ManagerBasedRlEnv)")
    return found


def out_of_slot(env: Any, term: str = TERM, asset_name: str = "robot", margin: float = 0.3) -> Any:
    """mjlab termination term (time-out kind), as the velocity tasks'
    ``out_of_terrain_bounds`` for rse's pool: true where the robot's base
    is more than ``margin`` metres outside its env's terrain (its slot:
    ``[0, nx·s] × [0, ny·s]`` in its own world, twice the field's centre,
    ``hfield_pos``: no terrain is copied out in a step)."""
    import torch

    event = _event(env, term)
    x, y, _ = event.envs.hfield_pos
    xy = event.apart.slot_xy(env.scene[asset_name].data.root_link_pos_w[:, :2])
    size = torch.tensor([2.0 * x, 2.0 * y], device=xy.device, dtype=xy.dtype)
    return ((xy < -margin) | (xy > size + margin)).any(dim=1)


def _initial_levels(terrain: Any, max_init: Optional[int], levels: Optional[int]) -> Optional[tuple[int, int]]:
    """``(max_init_terrain_level, terrain_levels)``: the arguments, else
    the replaced mjlab terrain's (``max_init_terrain_level``, clamped to
    its generator's ``num_rows`` as mjlab clamps it); None when neither
    says. Arguments out of range are refused."""
    if levels is not None and levels < 2:
        raise ValueError(f"terrain_levels: {levels}; expected 2 or more levels")
    if max_init is not None and not 0 <= max_init < (levels or 2**31):
        raise ValueError(f"max_init_terrain_level: {max_init}; expected 0 … terrain_levels - 1")
    generator = getattr(terrain, "terrain_generator", None)
    if levels is None and generator is not None:
        levels = max(int(generator.num_rows), 2)
    if max_init is None:
        max_init = getattr(terrain, "max_init_terrain_level", None)
        if max_init is not None and levels is not None:
            max_init = min(max_init, levels - 1)
    if max_init is None or levels is None:
        return None
    if max_init >= levels:
        raise ValueError(f"max_init_terrain_level: {max_init}; expected 0 … {levels - 1} (terrain_levels - 1)")
    return (max_init, levels)


NCON_HEADROOM = 5
"""Broadphase pairs per world beyond the field's, in ``terrain_nconmax``:
the plane's with a foot off the slot, the robot's own."""


def terrain_nconmax(nconmax: int, colliders: int) -> int:
    """The ``sim.nconmax`` (per world, shared by all: MuJoCo Warp sizes its
    broadphase pairs and its contacts by ``nconmax · num_envs``) of a task
    whose ``colliders`` geoms can touch the terrain, given the task's own
    ``nconmax``. Each such geom is a broadphase pair with its env's field,
    which spans the slot, every step; the plane, below the terrain
    (``GROUND_DROP``), pairs only with what leaves the slot. So the task's
    own figure where it covers those pairs and ``NCON_HEADROOM`` more, else
    just that: on the CPU every solver iteration of MuJoCo Warp (its
    elliptic cones' ``JTCJ``) runs over the whole ``nconmax · num_envs``,
    so each unused slot costs time (``bench/mjlab_tasks.py``)."""
    return max(int(nconmax), colliders + NCON_HEADROOM)


def _terrain_colliders(scene: Any) -> int:
    """How many geoms of the scene's entities collide with a plain terrain
    geom (``contype`` or ``conaffinity`` bit 1), from their specs."""
    count = 0
    for entity in (getattr(scene, "entities", None) or {}).values():
        spec = entity.spec_fn()
        count += sum(1 for g in spec.geoms if (g.contype | g.conaffinity) & 1)
    return count


def _spawn_radius_of(env_cfg: Any) -> Optional[float]:
    """The spawn radius that covers where the task's ``reset_base`` event
    may put a robot around its env's origin (``pose_range`` x and y: the
    velocity tasks' ±0.5 m give 0.71 m, the square's half diagonal), so no
    robot starts below a top it may be moved over; None (rse's default)
    for a task without one."""
    import math

    for term in env_cfg.events.values():
        pose = (getattr(term, "params", None) or {}).get("pose_range")
        if _func_name(term) == "reset_root_state_uniform" and pose:
            reach = [max(abs(lo), abs(hi)) for lo, hi in (pose.get("x", (0.0, 0.0)), pose.get("y", (0.0, 0.0)))]
            radius = math.hypot(*reach)
            return radius if radius > 0 else None
    return None


def _func_name(term: Any) -> str:
    return getattr(getattr(term, "func", None), "__name__", "")


def use_env_terrains(
    env_cfg: Any,
    scheme: Union[SchemeLike, dict[str, float]],
    *,
    oversample: Optional[int] = None,
    seed: Optional[int] = None,
    difficulty: Optional[float] = None,
    spawn_radius: Optional[float] = None,
    env_offset: Optional[int] = None,
    curriculum: Optional[bool] = None,
    max_init_terrain_level: Optional[int] = None,
    terrain_levels: Optional[int] = None,
    apart: bool = False,
    term: str = TERM,
) -> None:
    """Gives every env of an mjlab ``ManagerBasedRlEnvCfg`` its own rse
    terrain, new every episode — a registered velocity task's config as it
    is. It replaces:

    - the scene's terrain (``scene.terrain``, mjlab's generator or plane) by
      an ``EnvTerrainCfg`` (``rse._mjlab_scene``: mjlab's plane with rse's
      settings as fields, which ``train`` and ``play`` set from their command
      line: ``--env.scene.terrain.scheme my.csv``, ``.seed``,
      ``.difficulty``, ``.max-init-terrain-level``, ``.oversample``,
      ``.spawn-radius``) and rse's pool, added through the scene's
      ``spec_fn`` (sized by ``scene.num_envs`` when the scene is built)
      into mjlab's body named ``terrain``, in geom group 0, as mjlab's
      importer makes it: the tasks' contact sensors, ``terrain_scan`` and
      the feet's height sensors, and the rewards that read them, find it;
    - the terrain-level curriculum (``terrain_levels_vel``) by
      ``terrain_difficulty``, the same rule, continuous, with the same
      ``command_name`` (``curriculum=True`` adds it to a config without
      one; ``False`` leaves it out);
    - ``out_of_terrain_bounds`` by ``out_of_slot`` (the robot left its
      env's terrain);

    and adds ``EnvTerrainsEvent`` as the first reset event ``term``. Every
    other term is kept.

    ``scheme`` is one scheme (an ``rse.Scheme``, a CSV file's path or its
    text) or a mix, ``{scheme: proportion}`` (paths or CSV text), as
    mjlab's ``sub_terrains``: each env draws one by its global id and the
    seed, for the whole run, and the curriculum is logged per scheme
    (``Curriculum/rse_terrain_difficulty/<name>``, by file name). A config rse cannot serve is refused with a
    ``ValueError`` naming the field.

    Without a ``difficulty``, the envs start as mjlab's do: each at a level
    drawn from 0 … ``max_init_terrain_level`` of ``terrain_levels`` (level
    ``i`` is difficulty ``i / (terrain_levels - 1)``), both read from the
    terrain it replaces (the velocity tasks: 5 of 10) unless given; the
    curriculum then moves an env one level (``1 / (terrain_levels - 1)``)
    at a time. With neither, every env starts at difficulty 1.

    Without a ``spawn_radius``, the radius covers where the task's
    ``reset_root_state_uniform`` event may move a robot (its ``pose_range``
    x and y: 0.71 m for the velocity tasks' ±0.5 m), so no robot starts
    below a top it may be moved over.

    ``apart=True`` lays the envs' terrains out on a grid (``apart_offsets``),
    each robot on its own terrain in its own place, as mjlab's own terrain
    lays out its envs: for watching (the registered tasks' play configs set
    it). By default every env's terrain is at one place in its own world,
    where float32 positions are most precise."""
    from mjlab.managers.curriculum_manager import CurriculumTermCfg
    from mjlab.managers.event_manager import EventTermCfg
    from mjlab.managers.termination_manager import TerminationTermCfg
    from mjlab.terrains import TerrainEntityCfg

    scene = env_cfg.scene
    if scene.terrain is not None and not isinstance(scene.terrain, TerrainEntityCfg):
        raise ValueError(
            f"env_cfg.scene.terrain: a {type(scene.terrain).__name__} is not mjlab's TerrainEntityCfg: "
            "rse replaces mjlab's terrain only; set it to None"
        )
    if BODY in (getattr(scene, "entities", None) or {}):
        raise ValueError(f"env_cfg.scene.entities[{BODY!r}]: rse's terrain body is named {BODY!r}; rename the entity")
    if isinstance(scene.spec_fn, _PoolSpec):
        raise ValueError("env_cfg: has rse's terrains already (use_env_terrains was called on it once)")
    if spawn_radius is None:
        spawn_radius = _spawn_radius_of(env_cfg)
    # Bad arguments fail here, not when the env is built: the same
    # arguments on one env.
    # A dict is a mix, {scheme: proportion}, checked by EnvTerrainCfg below.
    mix = {str(k): float(v) for k, v in scheme.items()} if isinstance(scheme, dict) else {}
    if not mix:
        EnvTerrains(scheme_of(scheme), 1, oversample=oversample, seed=seed, difficulty=difficulty, spawn_radius=spawn_radius, env_offset=env_offset)
    spread = _initial_levels(scene.terrain, max_init_terrain_level, terrain_levels)
    if env_cfg.sim.nconmax is not None:
        env_cfg.sim.nconmax = terrain_nconmax(env_cfg.sim.nconmax, _terrain_colliders(scene))
    from rse._mjlab_scene import EnvTerrainCfg

    spacing = getattr(scene.terrain, "env_spacing", None)
    scene.terrain = EnvTerrainCfg(
        terrain_type="plane",
        env_spacing=2.0 if spacing is None else spacing,
        max_init_terrain_level=None if spread is None else spread[0],
        terrain_levels=None if spread is None else spread[1],
        scheme="" if isinstance(scheme, dict) else scheme_setting(scheme),
        schemes=mix,
        seed=seed,
        difficulty=difficulty,
        oversample=oversample,
        spawn_radius=spawn_radius,
        apart=apart,
    )
    earlier = scene.spec_fn
    scene.spec_fn = _PoolSpec(earlier)
    # The scheme, seed and levels are the scene's EnvTerrainCfg's (which the
    # command line sets): none is copied here, where it would go stale.
    params = dict(env_offset=env_offset)
    event = EventTermCfg(func=EnvTerrainsEvent, mode="reset", params=params)
    env_cfg.events = {term: event, **{k: v for k, v in env_cfg.events.items() if k != term}}
    levels = {k: c for k, c in env_cfg.curriculum.items() if _func_name(c) == "terrain_levels_vel"}
    for k in levels:
        del env_cfg.curriculum[k]
    if curriculum is None:
        curriculum = bool(levels)
    if curriculum:
        command = next((c.params.get("command_name") for c in levels.values()), None)
        # The step, one level, follows the scene's terrain_levels when run.
        env_cfg.curriculum[f"{term}_difficulty"] = CurriculumTermCfg(
            func=terrain_difficulty, params={"term": term, "command_name": command}
        )
    for k, t in list(env_cfg.terminations.items()):
        if _func_name(t) == "out_of_terrain_bounds":
            margin = t.params.get("margin", 0.3)
            env_cfg.terminations[k] = TerminationTermCfg(func=out_of_slot, time_out=t.time_out, params={"term": term, "margin": margin})
