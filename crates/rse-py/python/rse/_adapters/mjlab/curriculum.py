"""The difficulty curriculum term (mjlab's terrain-levels rule,
continuous) and the levels the envs start at."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from rse._adapters.mjlab.reset_event import TERM, event_of, index_of


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

    event = event_of(env, term)
    envs = event.envs
    if step is None:
        step = 1.0 / (event.terrain_levels - 1) if event.terrain_levels else 0.1
    ids = event.ids(env_ids)
    if env.common_step_counter > 0 and ids:
        index = index_of(env_ids, ids, env.scene.env_origins.device)
        walked = torch.norm(env.scene[asset_name].data.root_link_pos_w[index, :2] - env.scene.env_origins[index, :2], dim=1)
        half = event.halves(walked)[index]
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


def initial_levels(terrain: Any, max_init: Optional[int], levels: Optional[int]) -> Optional[tuple[int, int]]:
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
