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
``rse._adapters.tiles.fit``). mjlab hands each tile its generator's seeded ``rng``: the
tile's world index is drawn from it, so the same configuration and seed
give the same terrains. Flat patches are rse's (deterministic, spread out,
flat within ``max_height_diff`` rounded down to whole steps), filtered by
the ranges of each ``FlatPatchSamplingCfg``.

Every env its own terrain, new every episode (``use_env_terrains`` and its
terms) lives in ``rse._adapters.mjlab``, one module a job, and is
re-exported here.
"""

from __future__ import annotations

from rse._adapters.mjlab.curriculum import terrain_difficulty
from rse._adapters.mjlab.env_cfg import use_env_terrains
from rse._adapters.mjlab.reset_event import TERM, EnvTerrainsEvent, contact_sheet, env_terrains
from rse._adapters.mjlab.scene_pool import BODY, add_pool
from rse._adapters.mjlab.step_terms import bound_near_robots, exact_height_scan, out_of_slot
from rse._adapters.mjlab.sub_terrain import RseTerrainCfg

__all__ = [
    "BODY",
    "TERM",
    "EnvTerrainsEvent",
    "RseTerrainCfg",
    "add_pool",
    "bound_near_robots",
    "contact_sheet",
    "env_terrains",
    "exact_height_scan",
    "out_of_slot",
    "terrain_difficulty",
    "use_env_terrains",
]
