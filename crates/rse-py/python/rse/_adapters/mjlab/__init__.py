"""Everything rse does in mjlab (docs/envs.md, docs/train.md), one module a
job; ``rse.mjlab``, ``rse.mjlab_tasks``, ``rse.mjlab_eval`` and
``rse.mjlab_video`` are its public faces.

Every env its own terrain, new every episode: ``env_cfg``
(``use_env_terrains``, which wires the rest into an env config),
``scene_cfg`` (``EnvTerrainCfg``, the scene's terrain settings),
``terrains`` (the scheme or mix, the envs, where each starts),
``scene_pool`` (the height fields in the scene's spec), ``spec_fn``
(adding them while mjlab builds the scene), ``reset_event`` (the reset
event term), ``large_geom_fields`` (the coarse fields of the robot's large
geoms), ``terrain_bounds`` and ``near_bounds`` (each world's terrain geoms
bounded, at a reset and every step), ``watch_layout`` (envs laid out apart
for watching), ``ray_sensors`` and ``ray_kernel`` (rays on each env's own
field, camera meshes), ``device_tops`` and ``tops_kernel`` (the exact
tops on the device, and the kernels that read them there),
``curriculum`` (the difficulty term), ``step_terms`` (height scan, out of
slot, the near bounds' step event).

Runs and what they make: ``tasks`` (rse's variants of mjlab's rough
tasks), ``run_record`` (what a run records of its terrains, read back),
``evaluation`` and ``evaluation_cli`` (``python -m rse.mjlab_eval``),
``video`` (``python -m rse.mjlab_video``); ``sub_terrain``
(``RseTerrainCfg``, rse as one of mjlab's sub-terrains)."""
