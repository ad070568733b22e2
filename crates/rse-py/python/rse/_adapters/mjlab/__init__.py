"""Every mjlab env its own rse terrain, new every episode (docs/envs.md),
one module a job: ``terrains`` (the scheme, the envs, where each
starts), ``pool`` (the height fields in the scene's spec), ``spec_fn``
(adding it while mjlab builds the scene), ``event`` (the reset event
term), ``coarse`` (the large geoms' fields), ``apart`` (envs laid out
for watching), ``rays`` (rays on each env's own field, camera meshes), ``tops``
(the exact tops on the device), ``curriculum`` (the difficulty term),
``terms`` (height scan, out of slot) and ``config``
(``use_env_terrains``, which wires them into an env config). ``rse.mjlab``
re-exports the public ones."""
