"""rse's variants of mjlab's rough-terrain velocity tasks (``rse.mjlab_tasks``,
mjlab's entry point, says how they are run), registered in mjlab's task
registry when this module is imported."""

from __future__ import annotations

from typing import Optional

from rse._adapters.tiles import SchemeLike

STEPFIELD = """# A stepfield for legged robots: random steps of 5 cm under two stepped
# hills and a ridge, on an 8 m x 8 m slot of 10 cm cells.
# size: 80x80
# block_size: 0.1
# step_height: 0.05
type,height,angle,x1,y1,x2,y2
random,0..2,,,,,
peak,2..6,20,15..65,15..65,,
peak,2..6,20,15..65,15..65,,
wall,1..3,30,10,5..75,70,5..75
"""

PREFIX = "Mjlab-Velocity-Rough-"
"""mjlab's rough tasks, each of which gets an rse variant."""


def rse_task_id(task_id: str, prefix: str = "Rse-Velocity-Rough-") -> str:
    """The rse variant's id of mjlab's rough task ``task_id``."""
    return prefix + task_id[len(PREFIX) :]


def experiment_name(mjlab_name: str) -> str:
    """The experiment name (the log folder under ``logs/rsl_rl/``) of the rse
    variant of an mjlab task named ``mjlab_name``: ``rse_`` before it."""
    return "rse_" + mjlab_name


def register(scheme: SchemeLike = STEPFIELD, *, prefix: str = "Rse-Velocity-Rough-", oversample: Optional[int] = None) -> list[str]:
    """Registers an rse variant of every mjlab rough velocity task on
    ``scheme`` (play configs too); returns their ids. A task registered
    already (this module imported twice) is kept."""
    import mjlab.tasks  # noqa: F401  (mjlab's own tasks first)
    from mjlab.rl import MjlabOnPolicyRunner
    from mjlab.tasks import registry

    from rse._adapters.mjlab.env_cfg import use_env_terrains
    from rse._adapters.mjlab.run_record import recording_runner
    from rse._adapters.mjlab.terrains import scheme_of

    scheme_of(scheme)  # a bad scheme fails here, naming its line
    made = []
    for task_id in registry.list_tasks():
        if not task_id.startswith(PREFIX):
            continue
        new_id = rse_task_id(task_id, prefix)
        if new_id in registry.list_tasks():
            continue
        env_cfg = registry.load_env_cfg(task_id)
        play_cfg = registry.load_env_cfg(task_id, play=True)
        use_env_terrains(env_cfg, scheme, oversample=oversample)
        # play shows each robot on its own terrain, apart, as mjlab's own task.
        use_env_terrains(play_cfg, scheme, oversample=oversample, apart=True)
        rl_cfg = registry.load_rl_cfg(task_id)
        # Runs log apart from mjlab's own (logs/rsl_rl/rse_go1_velocity/).
        rl_cfg.experiment_name = experiment_name(rl_cfg.experiment_name)
        registry.register_mjlab_task(
            task_id=new_id,
            env_cfg=env_cfg,
            play_env_cfg=play_cfg,
            rl_cfg=rl_cfg,
            # mjlab's runner, which also records the terrains in the run folder.
            runner_cls=recording_runner(registry.load_runner_cls(task_id) or MjlabOnPolicyRunner),
        )
        made.append(new_id)
    return made


TASKS = register()
"""The ids registered when mjlab imported this module."""
