"""mjlab's scene terrain as rse's: ``EnvTerrainCfg``, the ``scene.terrain``
of an mjlab config that ``use_env_terrains`` has given every env its own
terrain. A dataclass of mjlab's own ``TerrainEntityCfg`` family, so mjlab's
``train`` and ``play`` set its fields from their command line, named as
mjlab names its own terrain settings::

    train Rse-Velocity-Rough-Unitree-Go1 --env.scene.terrain.scheme my.csv \\
        --env.scene.terrain.seed 7 --env.scene.terrain.difficulty 0.3

Every field is checked when the config is made (``__post_init__``, which
tyro runs on the command line's values): a missing scheme, a bad row, a
difficulty past 1 are refused there, naming the flag, before any scene is
built. The config also records what a run trains on — the scheme's whole
text and its SHA-256, rse's version, the difficulty rule — so mjlab's
``params/env.yaml`` holds them.

mjlab builds it as a ground plane (``terrain_type="plane"``: a body and
plane geom named ``terrain``, its checker texture and sun light), and rse's
pool of height fields goes into that body. Imports mjlab: the rest of rse
imports this module only where mjlab is in use."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from typing import Any, Literal, Optional

from mjlab.terrains import TerrainEntityCfg
from tyro.conf import Suppress

FLAG = "--env.scene.terrain."
"""How mjlab's ``train`` and ``play`` name this config's fields."""


def flag(name: str) -> str:
    """The command-line flag of field ``name`` (tyro writes ``-`` for ``_``)."""
    return FLAG + name.replace("_", "-")


@dataclass(kw_only=True)
class EnvTerrainCfg(TerrainEntityCfg):
    """Every env its own rse terrain, new every episode; mjlab's terrain
    fields keep their meaning (``max_init_terrain_level``: envs start at
    levels 0 … it)."""

    # mjlab's fields that rse's terrain fixes: kept off the command line,
    # where they could only fail or do nothing.
    terrain_type: Suppress[Literal["plane"]] = "plane"  # type: ignore[assignment]
    terrain_generator: Suppress[Optional[Any]] = None
    env_spacing: Suppress[Optional[float]] = 2.0  # the scene's own wins
    num_envs: Suppress[int] = 1  # the scene's own wins

    scheme: str = ""
    """The scheme: a CSV file's path, or the CSV text itself."""
    seed: Optional[int] = None
    """The base seed of every env's terrains; None: the scheme's ``# seed:``."""
    difficulty: Optional[float] = None
    """Every env's starting difficulty (0 to 1); None: each env at a level
    drawn from 0 … ``max_init_terrain_level``, as mjlab starts its envs."""
    terrain_levels: Optional[int] = None
    """The curriculum's levels (mjlab's generator rows: 10), level ``i``
    being difficulty ``i / (terrain_levels - 1)``; None: continuous steps
    of 0.1."""
    oversample: Optional[int] = None
    """Height-field samples per cell; None: rse's default for envs."""
    spawn_radius: Optional[float] = None
    """Radius of the disc around an env's centre whose highest top the
    robot spawns above, metres; None: rse's default."""
    apart: bool = False
    """Lay the envs' terrains out on a grid, each robot on its own terrain in
    its own place (for watching: the play configs set it); else every env's
    terrain is at one place in its own world."""

    # The record of what a run trains on, filled from the fields above
    # (not settable: tyro leaves ``init=False`` fields out).
    scheme_csv: str = field(init=False, default="")
    """The scheme's whole text, as read."""
    scheme_sha256: str = field(init=False, default="")
    """SHA-256 of ``scheme_csv`` (UTF-8), as ``sha256sum`` prints it for the file."""
    rse_version: str = field(init=False, default="")
    difficulty_rule: str = field(init=False, default="")
    """How difficulty scales heights (``rse.json``'s ``difficulty_rule``)."""

    def __post_init__(self) -> None:
        check(self)


def scheme_text(scheme: str) -> str:
    """The text of ``EnvTerrainCfg.scheme``: itself when it is CSV text (it
    has a line break), else the file it names. Refused naming the flag."""
    if "\n" in scheme:
        return scheme
    if not scheme:
        raise ValueError(f"{flag('scheme')}: no scheme given; a scheme CSV file's path, or its text")
    try:
        with open(scheme, encoding="utf-8") as f:
            return f.read()
    except OSError as e:
        raise ValueError(f"{flag('scheme')} {scheme}: cannot read it ({e.strerror or e})") from None
    except UnicodeDecodeError:
        raise ValueError(f"{flag('scheme')} {scheme}: not a text file (a scheme is a CSV file)") from None


def check(cfg: EnvTerrainCfg) -> None:
    """Checks every rse field of ``cfg`` as the terrains will use it (one env
    of the scheme is made with them), and fills its record; a bad value is
    a ``ValueError`` naming its flag (tyro prints it and exits 2)."""
    import rse
    from rse._rse import EnvTerrains, Scheme

    text = scheme_text(cfg.scheme)
    origin = cfg.scheme if "\n" not in cfg.scheme else "env.scene.terrain.scheme"
    try:
        scheme = Scheme.from_csv(text, origin)
    except ValueError as e:
        # rse's own words name the file, line and field.
        raise ValueError(f"{flag('scheme')}: {e}") from None
    if cfg.terrain_levels is not None and cfg.terrain_levels < 2:
        raise ValueError(f"{flag('terrain_levels')} {cfg.terrain_levels}: expected 2 or more levels")
    if cfg.max_init_terrain_level is not None:
        top = (cfg.terrain_levels or 2**31) - 1
        if not 0 <= cfg.max_init_terrain_level <= top:
            raise ValueError(
                f"{flag('max_init_terrain_level')} {cfg.max_init_terrain_level}: expected a level from 0 to {top}"
                + (f" ({flag('terrain_levels')} is {cfg.terrain_levels})" if cfg.terrain_levels else "")
            )
    if cfg.seed is not None and not 0 <= cfg.seed < 2**64:
        raise ValueError(f"{flag('seed')} {cfg.seed}: expected a whole number from 0 to 2^64 - 1")
    try:
        EnvTerrains(scheme, 1, oversample=cfg.oversample, seed=cfg.seed, difficulty=cfg.difficulty, spawn_radius=cfg.spawn_radius)
    except (ValueError, OverflowError, TypeError) as e:
        # rse names the argument first ("difficulty: ..."): the same names.
        name, _, reason = str(e).partition(": ")
        if name in ("difficulty", "oversample", "seed", "spawn_radius"):
            raise ValueError(f"{flag(name)} {getattr(cfg, name)}: {reason}") from None
        raise ValueError(f"{FLAG[:-1]}: {e}") from None
    cfg.scheme_csv = text
    cfg.scheme_sha256 = hashlib.sha256(text.encode("utf-8")).hexdigest()
    cfg.rse_version = rse.__version__
    cfg.difficulty_rule = rse.DIFFICULTY_RULE
