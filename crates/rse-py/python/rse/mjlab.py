"""rse as an mjlab sub-terrain: ``RseTerrainCfg`` for
``mjlab.terrains.TerrainGeneratorCfg.sub_terrains``.

Its ``function(difficulty, spec, rng)`` adds rse's box set (one static
box geom per rectangle of equal height, the collider MuJoCo handles best)
and a ground slab under the tile to ``spec.body("terrain")``, in the tile's
frame (corner at the origin, Z up; mjlab moves the geoms into place), and
returns mjlab's ``TerrainOutput`` with the spawn origin and flat patches.

Importable without mjlab: with ``mjlab`` installed, ``RseTerrainCfg`` is a
subclass of ``mjlab.terrains.SubTerrainCfg``; without it, a dataclass with
the same fields (``function`` then needs mjlab)::

    from mjlab.terrains import TerrainGeneratorCfg
    from rse.mjlab import RseTerrainCfg

    TERRAIN = TerrainGeneratorCfg(
        size=(8.0, 8.0), num_rows=10, num_cols=2, curriculum=True,
        sub_terrains={"stepfield": RseTerrainCfg(scheme="schemes/six_obstacles.csv")},
    )

The scheme's grid is fitted to the tile's ``size`` (blocks keep their size;
``rse._fit.fit``). mjlab hands each tile its generator's seeded ``rng``: the
tile's world index is drawn from it, so the same configuration and seed
give the same terrains. Flat patches are rse's (deterministic, spread out,
flat within ``max_height_diff`` rounded down to whole steps), filtered by
the ranges of each ``FlatPatchSamplingCfg``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from rse._fit import SchemeLike, fit, framework_class, load, max_step, patches_in_ranges
from rse._rse import EnvTerrains
from rse._env_pool import POOL, add_env_geom, sync_env_hfields


TERM = "rse_terrain"
"""The default name of rse's reset event term in an mjlab env config (its
difficulty curriculum term is ``TERM + "_difficulty"``)."""

def _function(cfg: Any, difficulty: float, spec: Any, rng: np.random.Generator) -> Any:
    import mujoco
    from mjlab.terrains.terrain_generator import TerrainGeometry, TerrainOutput

    if cfg.scheme is None:
        raise ValueError("RseTerrainCfg.scheme: give a scheme file (or rse.Scheme)")
    scheme = fit(load(cfg.scheme), tuple(cfg.size))
    index = int(rng.integers(0, 2**62)) if cfg.index is None else cfg.index
    # The library takes the seed's default and refuses a difficulty out of
    # 0..1 (mjlab's difficulty_range must stay inside it).
    terrain = scheme.generate(seed=cfg.rse_seed, index=index, difficulty=float(difficulty))
    body = spec.body("terrain")
    geometries = []
    sx, sy = cfg.size
    t = cfg.ground_thickness
    ground = body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=(sx / 2, sy / 2, t / 2), pos=(sx / 2, sy / 2, -t / 2))
    geometries.append(TerrainGeometry(geom=ground, color=(0.5, 0.5, 0.5, 1.0)))
    top = max(float(terrain.elevation.max()), 1e-9)
    for cx, cy, cz, hx, hy, hz in terrain.boxes():
        geom = body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=(hx, hy, hz), pos=(cx, cy, cz))
        shade = 0.3 + 0.6 * (cz + hz) / top
        geometries.append(TerrainGeometry(geom=geom, color=(shade, 0.45, 1.0 - shade, 1.0)))
    flat_patches = None
    if cfg.flat_patch_sampling:
        flat_patches = {}
        for name, p in cfg.flat_patch_sampling.items():
            # A margin of candidates, so that the ranges can drop some.
            found = terrain.flat_patches(4 * p.num_patches, p.patch_radius, max_step(scheme, p.max_height_diff))
            flat_patches[name] = patches_in_ranges(found, p.num_patches, p.x_range, p.y_range, p.z_range)
    origin = np.asarray(terrain.spawn_origin(cfg.spawn_radius), dtype=np.float64)
    return TerrainOutput(origin=origin, geometries=geometries, flat_patches=flat_patches)


_SubTerrainCfg = framework_class("mjlab.terrains.terrain_generator", "SubTerrainCfg", "rse.mjlab")


if _SubTerrainCfg is not None:  # pragma: no cover

    @dataclass(kw_only=True)
    class RseTerrainCfg(_SubTerrainCfg):  # type: ignore[misc,valid-type]
        """An rse stepfield tile (see the module's documentation)."""

        scheme: Optional[SchemeLike] = None
        rse_seed: Optional[int] = None
        index: Optional[int] = None
        spawn_radius: Optional[float] = None
        ground_thickness: float = 1.0

        def function(self, difficulty: float, spec: Any, rng: np.random.Generator) -> Any:
            return _function(self, difficulty, spec, rng)

else:

    @dataclass
    class RseTerrainCfg:  # type: ignore[no-redef]
        """An rse stepfield tile with the fields of mjlab's ``SubTerrainCfg``
        (see the module's documentation)."""

        proportion: float = 1.0
        size: tuple[float, float] = (10.0, 10.0)
        flat_patch_sampling: Optional[dict[str, Any]] = None
        scheme: Optional[SchemeLike] = None
        """The scheme: a path to its file, or an ``rse.Scheme``."""
        rse_seed: Optional[int] = None
        """The base seed of the rse worlds; default the scheme's ``# seed:``."""
        index: Optional[int] = None
        """A fixed world index for every tile; default drawn from mjlab's rng."""
        spawn_radius: Optional[float] = None
        """Metres around the centre whose highest top is the origin's z;
        default ``rse.DEFAULT_SPAWN_RADIUS``."""
        ground_thickness: float = 1.0
        """Thickness of the ground slab under the tile, metres."""

        def function(self, difficulty: float, spec: Any, rng: np.random.Generator) -> Any:
            return _function(self, difficulty, spec, rng)


# --- Every environment its own terrain, new every episode -------------------


def _probe(scheme: SchemeLike, oversample: Optional[int]) -> EnvTerrains:
    """One env of ``scheme``: the slot's shape and size, which do not
    depend on the number of envs."""
    return EnvTerrains(load(scheme), 1, oversample=oversample)


def add_pool(spec: Any, scheme: SchemeLike, num_envs: int, *, oversample: Optional[int] = None, name: str = POOL) -> None:
    """Adds to an mjlab scene's ``spec`` the pool of ``num_envs`` height
    fields of ``scheme``'s slot shape (zeros until ``EnvTerrainsEvent``
    fills them), the terrain geom that shows one (``rse.mujoco_warp.GEOM``)
    and a ground plane at the terrain's foot, so that a robot walking off
    its slot keeps a floor."""
    import mujoco

    from rse.mujoco_warp import GEOM

    probe = _probe(scheme, oversample)
    nrow, ncol = probe.field_shape
    zeros = np.zeros(nrow * ncol, dtype=np.float32)
    for e in range(num_envs):
        spec.add_hfield(name=f"{name}{e}", nrow=nrow, ncol=ncol, size=list(probe.hfield_size), userdata=zeros)
    add_env_geom(spec, probe, f"{name}0", name=GEOM)
    spec.worldbody.add_geom(name=f"{name}_ground", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05], rgba=[0.5, 0.5, 0.5, 1])


class EnvTerrainsEvent:
    """mjlab reset event term (``EventTermCfg(func=EnvTerrainsEvent,
    mode="reset", params=...)``, before the terms that place the robots):
    every env its own ``rse.EnvTerrains`` slot, a new terrain each time it
    resets, spawned at its env's origin.

    ``params``: ``scheme`` (a path or ``rse.Scheme``), and optionally
    ``oversample``, ``seed``, ``difficulty``, ``spawn_radius``,
    ``env_offset``, ``name`` as ``rse.EnvTerrains`` takes them. The scene
    must hold the pool (``add_pool``; ``use_env_terrains`` wires both).

    At construction it makes the ``EnvTerrains`` (``.envs``), expands the
    model's ``geom_dataid`` per world (mjlab's ``expand_model_fields``) and
    points each world's terrain geom at its env's field; each call resets
    the named envs, copies their samples into the simulation's model (and
    the host model, which mjlab's viewer draws) and writes their origins
    into ``env.scene.env_origins``.
    """

    def __init__(self, cfg: Any, env: Any) -> None:
        from rse.mujoco_warp import route

        p = dict(cfg.params)
        self.name = p.get("name", POOL)
        self.envs = EnvTerrains(
            load(p["scheme"]),
            env.num_envs,
            oversample=p.get("oversample"),
            seed=p.get("seed"),
            difficulty=p.get("difficulty"),
            env_offset=p.get("env_offset"),
            spawn_radius=p.get("spawn_radius"),
        )
        self._env = env
        sim = env.sim
        sim.expand_model_fields(("geom_dataid",))
        route(sim.wp_model, sim.mj_model, self.envs, name=self.name)
        self._copy_out(list(range(env.num_envs)))

    def _copy_out(self, ids: list[int]) -> None:
        """Copies the terrains of ``ids`` into the simulation's model and
        the host model, and their origins into ``env_origins``."""
        import torch

        from rse.mujoco_warp import sync

        sim = self._env.sim
        sync(sim.wp_model, sim.mj_model, self.envs, ids, name=self.name)
        sync_env_hfields(sim.mj_model, self.envs, ids, name=self.name)
        origins = self._env.scene.env_origins
        index = torch.as_tensor(ids, dtype=torch.long, device=origins.device)
        origins[index] = torch.as_tensor(self.envs.origins[ids], dtype=origins.dtype, device=origins.device)

    def __call__(self, env: Any, env_ids: Any, **params: Any) -> None:
        ids = _ids(env, env_ids)
        self.envs.reset(ids)
        self._copy_out(ids)


def _ids(env: Any, env_ids: Any) -> list[int]:
    """mjlab's env ids (a tensor, a slice or None: all) as a list."""
    if env_ids is None:
        return list(range(env.num_envs))
    if isinstance(env_ids, slice):
        return list(range(env.num_envs)[env_ids])
    return [int(e) for e in env_ids.tolist()]


def env_terrains(env: Any, term: str = TERM) -> EnvTerrains:
    """The ``rse.EnvTerrains`` of a running mjlab ``env`` (its event term
    ``term``): episodes, difficulties, origins, ``heights_at`` for height
    scans."""
    func = env.event_manager.get_term_cfg(term).func
    if not isinstance(func, EnvTerrainsEvent):
        raise ValueError(f"term: event term {term!r} is not an rse.mjlab.EnvTerrainsEvent")
    return func.envs


def terrain_difficulty(
    env: Any,
    env_ids: Any,
    term: str = TERM,
    asset_name: str = "robot",
    step: float = 0.1,
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
    spawn points). Returns the mean and max difficulty for mjlab's log."""
    import torch

    envs = env_terrains(env, term)
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
    return {"mean": float(envs.difficulty.mean()), "max": float(envs.difficulty.max())}


def use_env_terrains(
    env_cfg: Any,
    scheme: SchemeLike,
    *,
    oversample: Optional[int] = None,
    seed: Optional[int] = None,
    difficulty: Optional[float] = None,
    spawn_radius: Optional[float] = None,
    env_offset: Optional[int] = None,
    curriculum: bool = False,
    term: str = TERM,
) -> None:
    """Gives every env of an mjlab ``ManagerBasedRlEnvCfg`` its own rse
    terrain, new every episode: the pool in the scene (through its
    ``spec_fn``, sized by ``env_cfg.scene.num_envs`` when the scene is
    built), ``EnvTerrainsEvent`` as the first reset event ``term``, and
    with ``curriculum`` the ``terrain_difficulty`` curriculum term. The
    scene must have no terrain of its own (``scene.terrain = None``)."""
    from mjlab.managers.curriculum_manager import CurriculumTermCfg
    from mjlab.managers.event_manager import EventTermCfg

    if env_cfg.scene.terrain is not None:
        raise ValueError("env_cfg.scene.terrain: rse's pool is the terrain: set it to None")
    load(scheme)  # a bad scheme fails here, not when the scene is built
    scene = env_cfg.scene
    earlier = scene.spec_fn

    def spec_fn(spec: Any) -> None:
        if earlier is not None:
            earlier(spec)
        add_pool(spec, scheme, scene.num_envs, oversample=oversample)

    scene.spec_fn = spec_fn
    params = dict(scheme=scheme, oversample=oversample, seed=seed, difficulty=difficulty, spawn_radius=spawn_radius, env_offset=env_offset)
    event = EventTermCfg(func=EnvTerrainsEvent, mode="reset", params=params)
    env_cfg.events = {term: event, **{k: v for k, v in env_cfg.events.items() if k != term}}
    if curriculum:
        env_cfg.curriculum[f"{term}_difficulty"] = CurriculumTermCfg(func=terrain_difficulty, params={"term": term})


__all__ = ["EnvTerrainsEvent", "RseTerrainCfg", "add_pool", "env_terrains", "terrain_difficulty", "use_env_terrains"]
