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

import dataclasses
import hashlib
import os
from dataclasses import dataclass, field
from typing import Any, Literal, NamedTuple, Optional

from mjlab.terrains import TerrainEntityCfg
from tyro.conf import Suppress

FLAG = "--env.scene.terrain."
"""How mjlab's ``train`` and ``play`` name this config's fields."""


def flag(name: str) -> str:
    """The command-line flag of field ``name`` (tyro writes ``-`` for ``_``)."""
    return FLAG + name.replace("_", "-")


def _inherited(name: str) -> Any:
    """A field of ``TerrainEntityCfg`` as it is (its default), to be
    declared again with another annotation."""
    base = TerrainEntityCfg.__dataclass_fields__[name]
    if base.default_factory is not dataclasses.MISSING:
        return field(default_factory=base.default_factory)
    return field(default=base.default)


@dataclass(kw_only=True)
class EnvTerrainCfg(TerrainEntityCfg):
    """Every env its own rse terrain, new every episode; mjlab's terrain
    fields keep their meaning (``max_init_terrain_level``: envs start at
    levels 0 … it)."""

    # mjlab's fields that rse's terrain fixes, or that would move or
    # change its geoms behind rse's back (its pose, geoms, collisions):
    # kept off the command line, where they could only fail or do nothing.
    # The plane's looks (textures, materials, lights) and cameras stay.
    terrain_type: Suppress[Literal["plane"]] = "plane"  # type: ignore[assignment]
    terrain_generator: Suppress[Optional[Any]] = None
    env_spacing: Suppress[Optional[float]] = 2.0  # the scene's own wins
    num_envs: Suppress[int] = 1  # the scene's own wins
    init_state: Suppress[Any] = _inherited("init_state")
    spec_fn: Suppress[Any] = _inherited("spec_fn")
    articulation: Suppress[Any] = _inherited("articulation")
    sort_actuators: Suppress[bool] = _inherited("sort_actuators")
    meshes: Suppress[Any] = _inherited("meshes")
    geoms: Suppress[Any] = _inherited("geoms")
    collisions: Suppress[Any] = _inherited("collisions")
    debug_vis: Suppress[bool] = False  # mjlab's origins, not rse's spawn points

    scheme: str = ""
    """The scheme: a CSV file's path, or the CSV text itself. (rse as one
    sub-terrain of mjlab's own generator instead, tiles made once beside
    mjlab's: ``rse.mjlab.RseTerrainCfg`` in
    ``terrain_generator.sub_terrains``, docs/frameworks.md.)"""
    schemes: dict[str, float] = field(default_factory=dict)
    """A mix of schemes, as mjlab's ``sub_terrains``: each scheme (a CSV
    file's path, or its text) and its proportion (its share of their sum).
    Each env draws its scheme by its global id and the seed, for the whole
    run (``rse.scheme_mix``); the curriculum is logged per scheme, by file
    name. Given, it replaces ``scheme``. The schemes share their block size;
    their grids (every slot fits the largest), step heights and bases may
    differ."""
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
    scheme_csv: Suppress[str] = field(init=False, default="")
    """The scheme's whole text, as read."""
    scheme_sha256: Suppress[str] = field(init=False, default="")
    """SHA-256 of ``scheme_csv`` (UTF-8), as ``sha256sum`` prints it for the file."""
    schemes_csv: Suppress[dict[str, str]] = field(init=False, default_factory=dict)
    """A mix's schemes' texts by name (their file names)."""
    schemes_sha256: Suppress[dict[str, str]] = field(init=False, default_factory=dict)
    rse_version: Suppress[str] = field(init=False, default="")
    difficulty_rule: Suppress[str] = field(init=False, default="")
    """How difficulty scales heights (``rse.json``'s ``difficulty_rule``)."""

    def __post_init__(self) -> None:
        check(self)


class Mix(NamedTuple):
    """The schemes of ``EnvTerrainCfg.schemes``, read: names (file names,
    else ``scheme1`` …), ``rse.Scheme``s, proportions and the texts they
    were read from, in order."""

    names: list[str]
    schemes: list[Any]
    proportions: list[float]
    texts: list[str]


def mix_names(keys: list[str]) -> list[str]:
    """Each scheme's name in the logs and on the contact sheet: its file's
    name without ``.csv`` (CSV text: ``scheme1`` …), made unique."""
    names: list[str] = []
    for i, key in enumerate(keys):
        name = f"scheme{i + 1}" if "\n" in key else os.path.splitext(os.path.basename(key))[0] or f"scheme{i + 1}"
        names.append(name if name not in names else f"{name}{i + 1}")
    return names


def scheme_text(scheme: str, field_name: str = "scheme") -> str:
    """The text of a scheme setting: itself when it is CSV text (it has a
    line break), else the file it names. Refused naming the flag of
    ``field_name``."""
    if "\n" in scheme:
        return scheme
    if not scheme:
        raise ValueError(f"{flag(field_name)}: no scheme given; a scheme CSV file's path, or its text")
    try:
        with open(scheme, encoding="utf-8") as f:
            return f.read()
    except OSError as e:
        raise ValueError(f"{flag(field_name)} {scheme}: cannot read it ({e.strerror or e})") from None
    except UnicodeDecodeError:
        raise ValueError(f"{flag(field_name)} {scheme}: not a text file (a scheme is a CSV file)") from None


def sha256(text: str) -> str:
    """SHA-256 of ``text``'s UTF-8 bytes, as ``sha256sum`` prints it."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def read_mix(schemes: dict[str, float]) -> Mix:
    """``EnvTerrainCfg.schemes`` read, each scheme checked; refused naming
    the flag (and the file, line and field of a bad row)."""
    from rse._rse import Scheme

    keys = list(schemes)
    read, texts = [], []
    for i, key in enumerate(keys):
        origin = key if "\n" not in key else f"env.scene.terrain.schemes (scheme {i + 1})"
        texts.append(scheme_text(key, "schemes"))
        try:
            read.append(Scheme.from_csv(texts[-1], origin))
        except ValueError as e:
            raise ValueError(f"{flag('schemes')}: {e}") from None
    proportions = []
    for key, p in schemes.items():
        try:
            proportions.append(float(p))
        except (TypeError, ValueError):
            raise ValueError(f"{flag('schemes')}: {key}'s proportion {p!r} is not a number") from None
    return Mix(mix_names(keys), read, proportions, texts)


def check(cfg: EnvTerrainCfg) -> None:
    """Checks every rse field of ``cfg`` as the terrains will use it (one env
    of the scheme is made with them), and fills its record; a bad value is
    a ``ValueError`` naming its flag (tyro prints it and exits 2)."""
    import rse
    from rse._rse import EnvTerrains, Scheme

    mix = read_mix(cfg.schemes) if cfg.schemes else None
    text = "" if mix else scheme_text(cfg.scheme)
    if mix is None:
        origin = cfg.scheme if "\n" not in cfg.scheme else "env.scene.terrain.scheme"
        try:
            scheme: Any = Scheme.from_csv(text, origin)
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
    options = env_options(cfg)
    try:
        if mix is None:
            EnvTerrains(scheme, 1, **options)
        else:
            EnvTerrains(mix.schemes, 1, proportions=mix.proportions, **options)
    except (ValueError, OverflowError, TypeError) as e:
        # rse names the argument first ("difficulty: …", "oversample 0: …"):
        # the same names as the fields.
        name = str(e).split(" ", 1)[0].rstrip(":")
        reason = str(e).rpartition(": ")[2]
        if name in options:
            raise ValueError(f"{flag(name)} {getattr(cfg, name)}: {reason}") from None
        if name in ("schemes", "proportions"):
            raise ValueError(f"{flag('schemes')}: {str(e).partition(': ')[2]}") from None
        raise ValueError(f"{FLAG[:-1]}: {e}") from None
    cfg.scheme_csv = text
    cfg.scheme_sha256 = sha256(text) if text else ""
    # A mix's texts as read_mix read them: each file once.
    cfg.schemes_csv = dict(zip(mix.names, mix.texts)) if mix else {}
    cfg.schemes_sha256 = {name: sha256(t) for name, t in cfg.schemes_csv.items()}
    cfg.rse_version = rse.__version__
    cfg.difficulty_rule = rse.DIFFICULTY_RULE


def env_options(cfg: Any) -> dict[str, Any]:
    """The per-env options of rse-core's table (``rse._rse._env_keywords()``)
    that ``cfg`` has a field for, by name: what its terrains are made with.
    A field of ``EnvTerrainCfg`` named as an option reaches the terrains,
    the check and the reset event with no other edit."""
    from rse._rse import _env_keywords

    return {name: getattr(cfg, name) for name, *_ in _env_keywords() if hasattr(cfg, name)}
