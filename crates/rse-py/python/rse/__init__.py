"""Random Step Environments (NIST stepfields) for robot simulators.

The generator lives in Rust (``rse._rse``); this package re-exports it::

    import rse
    scheme = rse.Scheme.load("schemes/six_obstacles.csv")
    terrain = scheme.generate(seed=0, index=7)
    terrain.heights            # numpy (ny, nx) heights in steps, read-only
    vertices, faces = terrain.mesh()
"""

from rse._check import CheckReport, Fault, WorldReport, check
from rse._curriculum import CurriculumReport, LevelStats, check_curriculum
from rse._rse import (
    DEFAULT_ENV_OVERSAMPLE,
    DEFAULT_OVERSAMPLE,
    DEFAULT_PATCH_RADIUS,
    DEFAULT_SPAWN_RADIUS,
    DIFFICULTY_RULE,
    MESH_MODES,
    MUJOCO_COLLIDERS,
    TARGETS,
    Atlas,
    EnvTerrains,
    Obstacle,
    Scheme,
    SchemeError,
    ShardBusyError,
    Terrain,
    __version__,
    generate_batch,
    scheme_mix,
    write_world,
    write_worlds,
)

__all__ = [
    "DEFAULT_ENV_OVERSAMPLE",
    "DEFAULT_OVERSAMPLE",
    "DEFAULT_PATCH_RADIUS",
    "DEFAULT_SPAWN_RADIUS",
    "DIFFICULTY_RULE",
    "MESH_MODES",
    "MUJOCO_COLLIDERS",
    "TARGETS",
    "Atlas",
    "CheckReport",
    "CurriculumReport",
    "EnvTerrains",
    "Fault",
    "LevelStats",
    "Obstacle",
    "Scheme",
    "SchemeError",
    "ShardBusyError",
    "Terrain",
    "WorldReport",
    "__version__",
    "check",
    "check_curriculum",
    "generate_batch",
    "scheme_mix",
    "write_world",
    "write_worlds",
]
