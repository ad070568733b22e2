"""What an mjlab run records of the terrains it trains on, and reading it
back: the rse tasks' runner writes, beside mjlab's ``params/env.yaml``,
``params/rse_scheme.csv`` (the scheme's whole text, byte for byte as it
was given; a mix: ``params/rse_schemes/NAME.csv`` each) and
``params/rse_terrain.json`` (SHA-256s, proportions, the seed, the
difficulty rule, the starting levels actually used, rse's version);
``rse.mjlab_eval`` and ``play`` find the scheme there from a checkpoint's
path."""

from __future__ import annotations

import dataclasses
import json
import os
from pathlib import Path
from typing import Any, Optional

SCHEME_FILE = "rse_scheme.csv"
"""The scheme's text in a run folder's ``params/``."""

MIX_FOLDER = "rse_schemes"
"""A mix's schemes' texts in a run folder's ``params/``, ``NAME.csv`` each."""

RECORD_FILE = "rse_terrain.json"
"""The rest of the record in a run folder's ``params/``."""


def record(terrain: Any, env_offset: int = 0) -> dict[str, Any]:
    """The record of an ``EnvTerrainCfg`` (``terrain``) as a run used it:
    every value resolved (the seed the scheme gives where none was set)."""
    from rse._rse import Scheme

    def file_of(key: str) -> Optional[str]:
        return os.path.abspath(key) if "\n" not in key else None

    out: dict[str, Any] = {"rse_version": terrain.rse_version}
    if terrain.schemes:
        first = Scheme.from_csv(next(iter(terrain.schemes_csv.values())), "env.scene.terrain.schemes")
        out["schemes"] = {
            name: {"file": file_of(key), "sha256": terrain.schemes_sha256[name], "proportion": float(p)}
            for name, (key, p) in zip(terrain.schemes_csv, terrain.schemes.items())
        }
    else:
        first = Scheme.from_csv(terrain.scheme_csv, "env.scene.terrain.scheme")
        out["scheme_file"] = file_of(terrain.scheme)
        out["scheme_sha256"] = terrain.scheme_sha256
    out.update(
        seed=first.seed if terrain.seed is None else int(terrain.seed),
        difficulty_rule=terrain.difficulty_rule,
        difficulty=terrain.difficulty,
        max_init_terrain_level=terrain.max_init_terrain_level,
        terrain_levels=terrain.terrain_levels,
        oversample=terrain.oversample,
        spawn_radius=terrain.spawn_radius,
        env_offset=env_offset,
    )
    return out


def write_whole(path: Path, content: str) -> None:
    """``content`` into ``path``, whole or not at all, bytes as given (the
    copy's SHA-256 is the record's)."""
    partial = path.with_name(path.name + ".partial")
    partial.write_bytes(content.encode("utf-8"))
    os.replace(partial, path)


def write(run_dir: Path, terrain: Any, env_offset: int = 0) -> None:
    """Writes the record of ``terrain`` into ``run_dir/params/``."""
    params = Path(run_dir) / "params"
    params.mkdir(parents=True, exist_ok=True)
    if terrain.schemes:
        (params / MIX_FOLDER).mkdir(exist_ok=True)
        for name, text in terrain.schemes_csv.items():
            write_whole(params / MIX_FOLDER / f"{name}.csv", text)
    else:
        write_whole(params / SCHEME_FILE, terrain.scheme_csv)
    write_whole(params / RECORD_FILE, json.dumps(record(terrain, env_offset), indent=1) + "\n")


def run_terrain(checkpoint: str) -> Optional[dict[str, Any]]:
    """What a checkpoint's run trained on, as the ``EnvTerrainCfg`` fields
    that say it, each given — ``scheme`` (its copy's path, ``""`` for a
    mix), ``schemes`` (a mix's copies and proportions, ``{}`` for one
    scheme) and ``seed`` — or None where the run recorded nothing."""
    params = Path(checkpoint).resolve().parent / "params"
    saved = read_record(params)
    if not saved:
        return None
    if "schemes" in saved:
        mix = {str(params / MIX_FOLDER / f"{n}.csv"): m["proportion"] for n, m in saved["schemes"].items()}
        return {"scheme": "", "schemes": mix, "seed": saved.get("seed")}
    if (params / SCHEME_FILE).is_file():
        return {"scheme": str(params / SCHEME_FILE), "schemes": {}, "seed": saved.get("seed")}
    return None


def load_policy(task: str, env: Any, checkpoint: str, device: str) -> tuple[Any, Any]:
    """``env`` wrapped for rsl-rl and the inference policy of
    ``checkpoint`` (its actor), loaded by ``task``'s runner as mjlab's
    ``play`` loads it."""
    from mjlab.rl import MjlabOnPolicyRunner, RslRlVecEnvWrapper
    from mjlab.tasks.registry import load_rl_cfg, load_runner_cls

    agent_cfg = load_rl_cfg(task)
    wrapped = RslRlVecEnvWrapper(env, clip_actions=agent_cfg.clip_actions)
    runner = (load_runner_cls(task) or MjlabOnPolicyRunner)(wrapped, dataclasses.asdict(agent_cfg), device=device)
    runner.load(checkpoint, load_cfg={"actor": True}, strict=True, map_location=device)
    return wrapped, runner.get_inference_policy(device=device)


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
            from rse._adapters.mjlab.reset_event import TERM, event_of
            from rse._adapters.tiles import launcher_rank

            unwrapped = getattr(env, "unwrapped", env)
            terrain = unwrapped.cfg.scene.terrain
            if log_dir is None or launcher_rank() != 0 or type(terrain).__name__ != "EnvTerrainCfg":
                return
            offset = 0
            try:
                offset = event_of(unwrapped, TERM).env_offset
            except (ValueError, AttributeError):
                pass
            write(Path(log_dir), terrain, offset)

    RecordingRunner.__name__ = RecordingRunner.__qualname__ = f"Rse{base.__name__}"
    return RecordingRunner
