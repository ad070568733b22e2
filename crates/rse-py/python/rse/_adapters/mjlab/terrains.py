"""The envs' terrains of an mjlab config: the scheme or mix it names
(``scheme_of``), the ``rse.EnvTerrains`` made of it, the settings a
scene's ``EnvTerrainCfg`` holds, and where each env starts (mjlab's
levels in rse's difficulty, the launcher's env offset)."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from rse._adapters.tiles import SchemeLike, launcher_rank, load
from rse._rse import EnvTerrains


def scheme_of(scheme: Any) -> Any:
    """``scheme`` as an ``rse.Scheme``: one already, CSV text (a string
    with a line break), or a CSV file's path; a mix
    (``rse._adapters.mjlab.scene_cfg.Mix``) as it is."""
    from rse._adapters.mjlab.scene_cfg import Mix
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


def make_envs(scheme: Any, num_envs: int, **options: Any) -> EnvTerrains:
    """``rse.EnvTerrains`` of ``num_envs`` envs of a scheme (anything
    ``scheme_of`` reads) or a mix (``rse._adapters.mjlab.scene_cfg.Mix``)."""
    from rse._adapters.mjlab.scene_cfg import Mix

    scheme = scheme_of(scheme)
    if isinstance(scheme, Mix):
        return EnvTerrains(scheme.schemes, num_envs, proportions=scheme.proportions, **options)
    return EnvTerrains(scheme, num_envs, **options)


def probe_envs(scheme: SchemeLike, oversample: Optional[int]) -> EnvTerrains:
    """One env of ``scheme`` (or a mix): the slot's shape and size, which
    do not depend on the number of envs."""
    return make_envs(scheme, 1, oversample=oversample)


def terrain_settings(terrain: Any) -> dict[str, Any]:
    """The fields of an ``EnvTerrainCfg`` scene terrain as event params;
    nothing for another terrain (or none). The scheme is the text the
    config read and recorded (``scheme_csv``), not its path read again."""
    if type(terrain).__name__ != "EnvTerrainCfg":
        return {}
    from rse._adapters.mjlab.scene_cfg import env_options

    keys = ("scheme", "apart", "max_init_terrain_level", "terrain_levels")
    settings = {**{k: getattr(terrain, k) for k in keys}, **env_options(terrain)}
    settings["scheme"] = terrain.scheme_csv or terrain.scheme
    if terrain.schemes:
        from rse._adapters.mjlab.scene_cfg import Mix
        from rse._rse import Scheme

        # A mix, from the texts the config read.
        names, texts = list(terrain.schemes_csv), list(terrain.schemes_csv.values())
        schemes = [Scheme.from_csv(t, n) for n, t in zip(names, texts)]
        settings["scheme"] = Mix(names, schemes, [float(p) for p in terrain.schemes.values()], texts)
    return settings


def spread_of(params: dict[str, Any]) -> Optional[tuple[int, int]]:
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
