"""rse's variants of mjlab's rough-terrain velocity tasks, registered in
mjlab's task registry (``Rse-Velocity-Rough-Unitree-Go1``,
``Rse-Velocity-Rough-Unitree-G1``, one per ``Mjlab-Velocity-Rough-*`` task
mjlab registers): the task's own config with ``use_env_terrains`` applied —
every env its own stepfield, new every episode, rse's difficulty curriculum
in place of mjlab's terrain levels. mjlab imports this module through its
``mjlab.tasks`` entry point, so its ``train`` and ``play`` scripts run the
tasks by name::

    train Rse-Velocity-Rough-Unitree-Go1 --env.scene.num-envs 4096
    train Rse-Velocity-Rough-Unitree-Go1 --env.scene.terrain.scheme my.csv \
        --env.scene.terrain.seed 7 --env.scene.terrain.max-init-terrain-level 2

The stepfield is ``STEPFIELD`` (8 m × 8 m, the size of a sub-terrain of
mjlab's rough terrain), set on the command line by
``--env.scene.terrain.scheme`` (``rse._adapters.mjlab.scene_cfg.EnvTerrainCfg``); runs
log under ``logs/rsl_rl/rse_<mjlab's experiment name>/``;
``register(scheme, prefix=...)`` registers others."""

from rse._adapters.mjlab.tasks import PREFIX, STEPFIELD, TASKS, experiment_name, register, rse_task_id

__all__ = ["PREFIX", "STEPFIELD", "TASKS", "experiment_name", "register", "rse_task_id"]
