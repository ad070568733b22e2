"""``use_env_terrains``: rse's terrains wired into an mjlab
``ManagerBasedRlEnvCfg`` (its scene terrain, spec_fn, reset event,
curriculum and termination terms), and what it reads of the task."""

from __future__ import annotations

from typing import Any, Optional, Union

from rse._adapters.mjlab.curriculum import initial_levels, terrain_difficulty
from rse._adapters.mjlab.event import TERM, EnvTerrainsEvent
from rse._adapters.mjlab.pool import BODY
from rse._adapters.mjlab.spec_fn import PoolScene, pool_scene
from rse._adapters.mjlab.terms import bound_near_robots, out_of_slot
from rse._adapters.mjlab.terrains import scheme_of, scheme_setting
from rse._adapters.tiles import SchemeLike
from rse._rse import EnvTerrains

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


def terrain_colliders(scene: Any) -> int:
    """How many geoms of the scene's entities collide with a plain terrain
    geom (``contype`` or ``conaffinity`` bit 1), from their specs."""
    count = 0
    for entity in (getattr(scene, "entities", None) or {}).values():
        spec = entity.spec_fn()
        count += sum(1 for g in spec.geoms if (g.contype | g.conaffinity) & 1)
    return count


def spawn_radius_of(env_cfg: Any) -> Optional[float]:
    """The spawn radius that covers where the task's ``reset_base`` event
    may put a robot around its env's origin (``pose_range`` x and y: the
    velocity tasks' ±0.5 m give 0.71 m, the square's half diagonal), so no
    robot starts below a top it may be moved over; None (rse's default)
    for a task without one."""
    import math

    for term in env_cfg.events.values():
        pose = (getattr(term, "params", None) or {}).get("pose_range")
        if func_name(term) == "reset_root_state_uniform" and pose:
            reach = [max(abs(lo), abs(hi)) for lo, hi in (pose.get("x", (0.0, 0.0)), pose.get("y", (0.0, 0.0)))]
            radius = math.hypot(*reach)
            return radius if radius > 0 else None
    return None


def func_name(term: Any) -> str:
    return getattr(getattr(term, "func", None), "__name__", "")


NEAR = "_near"
"""The suffix of the step event term's name (``bound_near_robots``)."""


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

    and adds ``EnvTerrainsEvent`` as the first reset event ``term``, and
    ``bound_near_robots`` as the step event ``term + "_near"`` (each
    world's terrain bounded, every step, by the square its robot can reach:
    fewer broadphase pairs, the same contacts). Every other term is kept.

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
            f"env_cfg.scene.terrain: a {type(scene.terrain).__name__} is not mjlab's TerrainEntityCfg: rse replaces mjlab's terrain only; set it to None"
        )
    if BODY in (getattr(scene, "entities", None) or {}):
        raise ValueError(f"env_cfg.scene.entities[{BODY!r}]: rse's terrain body is named {BODY!r}; rename the entity")
    if isinstance(scene, PoolScene):
        raise ValueError("env_cfg: has rse's terrains already (use_env_terrains was called on it once)")
    if spawn_radius is None:
        spawn_radius = spawn_radius_of(env_cfg)
    # Bad arguments fail here, not when the env is built: the same
    # arguments on one env.
    # A dict is a mix, {scheme: proportion}, checked by EnvTerrainCfg below.
    mix = {str(k): float(v) for k, v in scheme.items()} if isinstance(scheme, dict) else {}
    if not mix:
        EnvTerrains(scheme_of(scheme), 1, oversample=oversample, seed=seed, difficulty=difficulty, spawn_radius=spawn_radius, env_offset=env_offset)
    spread = initial_levels(scene.terrain, max_init_terrain_level, terrain_levels)
    if env_cfg.sim.nconmax is not None:
        env_cfg.sim.nconmax = terrain_nconmax(env_cfg.sim.nconmax, terrain_colliders(scene))
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
    # The scene becomes a copy whose spec_fn adds the pool of whatever
    # config mjlab builds from it (the command line's included).
    env_cfg.scene = pool_scene(scene)
    # The scheme, seed and levels are the scene's EnvTerrainCfg's (which the
    # command line sets): none is copied here, where it would go stale.
    params = dict(env_offset=env_offset)
    event = EventTermCfg(func=EnvTerrainsEvent, mode="reset", params=params)
    near = EventTermCfg(func=bound_near_robots, mode="step", params={"term": term})
    kept = {k: v for k, v in env_cfg.events.items() if k not in (term, f"{term}{NEAR}")}
    env_cfg.events = {term: event, f"{term}{NEAR}": near, **kept}
    levels = {k: c for k, c in env_cfg.curriculum.items() if func_name(c) == "terrain_levels_vel"}
    for k in levels:
        del env_cfg.curriculum[k]
    if curriculum is None:
        curriculum = bool(levels)
    if curriculum:
        command = next((c.params.get("command_name") for c in levels.values()), None)
        # The step, one level, follows the scene's terrain_levels when run.
        env_cfg.curriculum[f"{term}_difficulty"] = CurriculumTermCfg(func=terrain_difficulty, params={"term": term, "command_name": command})
    for k, t in list(env_cfg.terminations.items()):
        if func_name(t) == "out_of_terrain_bounds":
            margin = t.params.get("margin", 0.3)
            env_cfg.terminations[k] = TerminationTermCfg(func=out_of_slot, time_out=t.time_out, params={"term": term, "margin": margin})
