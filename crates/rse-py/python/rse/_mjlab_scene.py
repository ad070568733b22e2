"""mjlab's scene terrain as rse's: ``EnvTerrainCfg``, the ``scene.terrain``
of an mjlab config that ``use_env_terrains`` has given every env its own
terrain. A dataclass of mjlab's own ``TerrainEntityCfg`` family, so mjlab's
``train`` and ``play`` set its fields from their command line, named as
mjlab names its own terrain settings::

    train Rse-Velocity-Rough-Unitree-Go1 --env.scene.terrain.scheme my.csv \\
        --env.scene.terrain.seed 7 --env.scene.terrain.difficulty 0.3

mjlab builds it as a ground plane (``terrain_type="plane"``: a body and
plane geom named ``terrain``, its checker texture and sun light), and rse's
pool of height fields goes into that body. Imports mjlab: the rest of rse
imports this module only where mjlab is in use."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from mjlab.terrains import TerrainEntityCfg


@dataclass(kw_only=True)
class EnvTerrainCfg(TerrainEntityCfg):
    """Every env its own rse terrain, new every episode; mjlab's terrain
    fields keep their meaning (``max_init_terrain_level``: envs start at
    levels 0 … it)."""

    scheme: str = ""
    """The scheme: a CSV file's path, or the CSV text itself."""
    seed: Optional[int] = None
    """The base seed of every env's terrains; None: the scheme's ``# seed:``."""
    difficulty: Optional[float] = None
    """Every env's starting difficulty (0 to 1); None: each env at a level
    drawn from 0 … ``max_init_terrain_level``, as mjlab starts its envs."""
    oversample: Optional[int] = None
    """Height-field samples per cell; None: rse's default for envs."""
    spawn_radius: Optional[float] = None
    """Radius of the disc around an env's centre whose highest top the
    robot spawns above, metres; None: rse's default."""
    apart: bool = False
    """Lay the envs' terrains out on a grid, each robot on its own terrain in
    its own place (for watching: the play configs set it); else every env's
    terrain is at one place in its own world."""
