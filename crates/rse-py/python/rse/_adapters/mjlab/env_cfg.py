"""``use_env_terrains``: rse's terrains wired into an mjlab
``ManagerBasedRlEnvCfg`` (its scene terrain, spec_fn, reset event,
curriculum and termination terms), and what it reads of the task."""

from __future__ import annotations

from typing import Any, Optional, Union

from rse._adapters.mjlab.curriculum import initial_levels, terrain_difficulty
from rse._adapters.mjlab.reset_event import TERM, EnvTerrainsEvent
from rse._adapters.mjlab.scene_pool import BODY
from rse._adapters.mjlab.spec_fn import PoolScene, pool_scene
from rse._adapters.mjlab.step_terms import bound_near_robots, out_of_slot
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
    is (docs/train.md). It replaces the scene's terrain by an
    ``EnvTerrainCfg`` (mjlab's plane with rse's settings as fields, which
    ``train`` and ``play`` set from their command line:
    ``--env.scene.terrain.scheme my.csv``, ``.seed``, ``.difficulty``, …)
    and rse's pool, added through the scene's ``spec_fn`` into mjlab's body
    named ``terrain``; ``terrain_levels_vel`` by ``terrain_difficulty`` (the
    same rule, continuous; ``curriculum=True`` adds it, ``False`` leaves it
    out); ``out_of_terrain_bounds`` by ``out_of_slot``. It adds
    ``EnvTerrainsEvent`` as the first reset event ``term`` and
    ``bound_near_robots`` as the step event ``term + "_near"``.

    ``scheme`` is one scheme (an ``rse.Scheme``, a CSV file's path or its
    text) or a mix, ``{scheme: proportion}``. Without a ``difficulty``, the
    envs start as mjlab's do: at levels 0 … ``max_init_terrain_level`` of
    ``terrain_levels``, read from the terrain it replaces unless given.
    Without a ``spawn_radius``, the radius covers the task's
    ``reset_root_state_uniform`` ``pose_range``. ``apart=True`` lays the
    terrains out on a grid, for watching. A config rse cannot serve is a
    ``ValueError`` naming the field."""
    scene = env_cfg.scene
    _check_scene(scene)
    if spawn_radius is None:
        spawn_radius = spawn_radius_of(env_cfg)
    # Bad arguments fail here, not when the env is built: the same
    # arguments on one env. A mix is checked by EnvTerrainCfg below.
    mix = {str(k): float(v) for k, v in scheme.items()} if isinstance(scheme, dict) else {}
    if not mix:
        EnvTerrains(scheme_of(scheme), 1, oversample=oversample, seed=seed, difficulty=difficulty, spawn_radius=spawn_radius, env_offset=env_offset)
    if env_cfg.sim.nconmax is not None:
        env_cfg.sim.nconmax = terrain_nconmax(env_cfg.sim.nconmax, terrain_colliders(scene))
    spread = initial_levels(scene.terrain, max_init_terrain_level, terrain_levels)
    settings = dict(seed=seed, difficulty=difficulty, oversample=oversample, spawn_radius=spawn_radius, apart=apart)
    setting = "" if isinstance(scheme, dict) else scheme_setting(scheme)
    scene.terrain = _scene_terrain(scene.terrain, setting, mix, spread, settings)
    # The scene becomes a copy whose spec_fn adds the pool of whatever
    # config mjlab builds from it (the command line's included).
    env_cfg.scene = pool_scene(scene)
    _set_events(env_cfg, term, env_offset)
    _set_curriculum(env_cfg, term, curriculum)
    _set_terminations(env_cfg, term)


def _check_scene(scene: Any) -> None:
    """Refuses a scene rse's terrains cannot go into, naming the field."""
    from mjlab.terrains import TerrainEntityCfg

    if scene.terrain is not None and not isinstance(scene.terrain, TerrainEntityCfg):
        raise ValueError(
            f"env_cfg.scene.terrain: a {type(scene.terrain).__name__} is not mjlab's TerrainEntityCfg: rse replaces mjlab's terrain only; set it to None"
        )
    if BODY in (getattr(scene, "entities", None) or {}):
        raise ValueError(f"env_cfg.scene.entities[{BODY!r}]: rse's terrain body is named {BODY!r}; rename the entity")
    if isinstance(scene, PoolScene):
        raise ValueError("env_cfg: has rse's terrains already (use_env_terrains was called on it once)")


def _scene_terrain(replaced: Any, scheme: str, mix: dict[str, float], spread: Optional[tuple[int, int]], settings: dict[str, Any]) -> Any:
    """The scene's ``EnvTerrainCfg`` in place of the terrain ``replaced``."""
    from rse._adapters.mjlab.scene_cfg import EnvTerrainCfg

    spacing = getattr(replaced, "env_spacing", None)
    return EnvTerrainCfg(
        terrain_type="plane",
        env_spacing=2.0 if spacing is None else spacing,
        max_init_terrain_level=None if spread is None else spread[0],
        terrain_levels=None if spread is None else spread[1],
        scheme=scheme,
        schemes=mix,
        **settings,
    )


def _set_events(env_cfg: Any, term: str, env_offset: Optional[int]) -> None:
    """The reset event ``term`` first, and the step event ``term`` + ``_near``."""
    from mjlab.managers.event_manager import EventTermCfg

    # The scheme, seed and levels are the scene's EnvTerrainCfg's (which the
    # command line sets): none is copied here, where it would go stale.
    params = dict(env_offset=env_offset)
    event = EventTermCfg(func=EnvTerrainsEvent, mode="reset", params=params)
    near = EventTermCfg(func=bound_near_robots, mode="step", params={"term": term})
    kept = {k: v for k, v in env_cfg.events.items() if k not in (term, f"{term}{NEAR}")}
    env_cfg.events = {term: event, f"{term}{NEAR}": near, **kept}


def _set_curriculum(env_cfg: Any, term: str, curriculum: Optional[bool]) -> None:
    """``terrain_levels_vel`` replaced by ``terrain_difficulty`` (added
    with ``curriculum=True``, left out with ``False``)."""
    from mjlab.managers.curriculum_manager import CurriculumTermCfg

    levels = {k: c for k, c in env_cfg.curriculum.items() if func_name(c) == "terrain_levels_vel"}
    for k in levels:
        del env_cfg.curriculum[k]
    if curriculum is None:
        curriculum = bool(levels)
    if curriculum:
        command = next((c.params.get("command_name") for c in levels.values()), None)
        # The step, one level, follows the scene's terrain_levels when run.
        env_cfg.curriculum[f"{term}_difficulty"] = CurriculumTermCfg(func=terrain_difficulty, params={"term": term, "command_name": command})


def _set_terminations(env_cfg: Any, term: str) -> None:
    """``out_of_terrain_bounds`` replaced by ``out_of_slot``, its margin kept."""
    from mjlab.managers.termination_manager import TerminationTermCfg

    for k, t in list(env_cfg.terminations.items()):
        if func_name(t) == "out_of_terrain_bounds":
            margin = t.params.get("margin", 0.3)
            env_cfg.terminations[k] = TerminationTermCfg(func=out_of_slot, time_out=t.time_out, params={"term": term, "margin": margin})
