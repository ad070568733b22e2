"""What an mjlab run records of the terrains it trains on, and reading it
back: the rse tasks' runner writes, beside mjlab's ``params/env.yaml``,
``params/rse_scheme.csv`` (the scheme's whole text, byte for byte as it
was given) and ``params/rse_terrain.json`` (its SHA-256, the seed, the
difficulty rule, the starting levels actually used, rse's version);
``rse.mjlab_eval`` and ``play`` find the scheme there from a checkpoint's
path."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any, Optional

SCHEME_FILE = "rse_scheme.csv"
"""The scheme's text in a run folder's ``params/``."""

RECORD_FILE = "rse_terrain.json"
"""The rest of the record in a run folder's ``params/``."""


def record(terrain: Any, env_offset: int = 0) -> dict[str, Any]:
    """The record of an ``EnvTerrainCfg`` (``terrain``) as a run used it:
    every value resolved (the seed the scheme gives where none was set)."""
    from rse._rse import Scheme

    scheme = Scheme.from_csv(terrain.scheme_csv, "env.scene.terrain.scheme")
    given = terrain.scheme if "\n" not in terrain.scheme else None
    return {
        "rse_version": terrain.rse_version,
        "scheme_file": os.path.abspath(given) if given else None,
        "scheme_sha256": terrain.scheme_sha256,
        "seed": scheme.seed if terrain.seed is None else int(terrain.seed),
        "difficulty_rule": terrain.difficulty_rule,
        "difficulty": terrain.difficulty,
        "max_init_terrain_level": terrain.max_init_terrain_level,
        "terrain_levels": terrain.terrain_levels,
        "oversample": terrain.oversample,
        "spawn_radius": terrain.spawn_radius,
        "env_offset": env_offset,
    }


def write(run_dir: Path, terrain: Any, env_offset: int = 0) -> None:
    """Writes the record of ``terrain`` into ``run_dir/params/``, each file
    whole or not at all."""
    params = Path(run_dir) / "params"
    params.mkdir(parents=True, exist_ok=True)
    text = json.dumps(record(terrain, env_offset), indent=1) + "\n"
    for name, content in ((SCHEME_FILE, terrain.scheme_csv), (RECORD_FILE, text)):
        partial = params / f"{name}.partial"
        # Bytes as given: the copy's SHA-256 is the record's.
        partial.write_bytes(content.encode("utf-8"))
        os.replace(partial, params / name)


def scheme_of_run(checkpoint: str) -> Optional[Path]:
    """The scheme a checkpoint's run trained on (``params/rse_scheme.csv``
    in the checkpoint's folder), or None where the run has no record."""
    path = Path(checkpoint).resolve().parent / "params" / SCHEME_FILE
    return path if path.is_file() else None


def read_record(params: Path) -> dict[str, Any]:
    """The record in a run's ``params/`` folder; empty where there is none."""
    try:
        with open(Path(params) / RECORD_FILE) as f:
            return dict(json.load(f))
    except (OSError, ValueError):
        return {}


def recording_runner(base: Any) -> Any:
    """mjlab's runner class ``base`` that also writes the terrains' record
    into its run folder when made with one (``train``; rank 0 alone, as
    mjlab writes its own ``params/``)."""

    class RecordingRunner(base):  # type: ignore[misc,valid-type]
        def __init__(self, env: Any, train_cfg: Any, log_dir: Optional[str] = None, device: str = "cpu", **kwargs: Any) -> None:
            super().__init__(env, train_cfg, log_dir, device, **kwargs)
            from rse._adapters.tiles import launcher_rank
            from rse._mjlab_envs import TERM, _event

            unwrapped = getattr(env, "unwrapped", env)
            terrain = unwrapped.cfg.scene.terrain
            if log_dir is None or launcher_rank() != 0 or type(terrain).__name__ != "EnvTerrainCfg":
                return
            offset = 0
            try:
                offset = _event(unwrapped, TERM).env_offset
            except (ValueError, AttributeError):
                pass
            write(Path(log_dir), terrain, offset)

    RecordingRunner.__name__ = RecordingRunner.__qualname__ = f"Rse{base.__name__}"
    return RecordingRunner
