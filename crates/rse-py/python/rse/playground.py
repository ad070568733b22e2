"""rse's per-env terrains in MuJoCo Playground (MJX): its Go1 joystick
task on a stepfield, every world its own rse terrain (docs/train.md).

``go1_joystick(envs)`` is Playground's ``Go1JoystickRoughTerrain`` with its
height field ``hfield`` (a 256 × 256 PNG) replaced by a field of ``envs``'
slot shape, on MJX's JAX implementation (``rse.mjx`` batches ``hfield_data``
per world there). ``terrains_fn(env, envs)`` is the ``randomization_fn`` that
Playground's ``wrap_for_brax_training`` and Brax's PPO take: it gives world
``w`` env ``w``'s samples and moves world ``w``'s floor so that its
spawn origin is at (0, 0, 0), where Playground's Go1 resets (± 0.5 m)::

    import rse, rse.playground
    from brax.training.agents.ppo import train as ppo
    from mujoco_playground import wrapper

    envs = rse.EnvTerrains(scheme, num_envs, spawn_radius=rse.playground.SPAWN_RADIUS)
    env = rse.playground.go1_joystick(envs)
    ppo.train(environment=env, num_envs=num_envs, wrap_env_fn=wrapper.wrap_for_brax_training,
              randomization_fn=rse.playground.terrains_fn(env, envs), ...)

The terrains are fixed for a training run: Brax's PPO runs its whole loop
under ``jit`` and auto-resets to cached or re-drawn states within it, so no
host code runs between episodes to write new terrains (mjlab, Genesis,
Newton and ``rse.mjx`` in a loop of one's own renew them at every reset).
To draw others, train again with ``envs.reset(...)`` or another
``env_offset``. Playground's Go1 meshes come from MuJoCo Menagerie, which
Playground clones from GitHub on first use (docs/train.md says how to
provide them offline).
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any, Callable, Optional

import numpy as np

from rse._adapters import private
from rse._adapters.fields import env_field, geom_id, require_layout
from rse._adapters.mjcf import replace_field
from rse._adapters.world_rows import world_rows
from rse._rse import EnvTerrains

__all__ = ["FIELD", "FLOOR", "SPAWN_RADIUS", "go1_joystick", "terrains_fn"]

FIELD = "hfield"
"""The height field of Playground's rough scenes, which rse's replaces."""
FLOOR = "floor"
"""The geom showing it (Playground's feet contact sensors name it)."""
SPAWN_RADIUS = 0.8
"""Playground's Go1 resets within ± 0.5 m of (0, 0) and its feet reach
0.3 m further: with this ``spawn_radius`` no top it can land on is above
its spawn origin."""


def _stepfield_scene(xml: str, envs: EnvTerrains) -> str:
    """Playground's rough scene ``xml`` with the field ``hfield`` of
    ``envs``' slot shape (its samples written after compiling) and the floor
    geom at ``envs.hfield_pos``. Raises ``ValueError`` if the scene has no
    such field or floor (another Playground version)."""
    try:
        return replace_field(xml, FIELD, FLOOR, envs.field_shape, envs.hfield_size, envs.hfield_pos)
    except ValueError as e:
        raise ValueError(f"{e} (mujoco_playground 0.2)") from None


def go1_joystick(envs: EnvTerrains, config: Any = None, config_overrides: Optional[dict[str, Any]] = None) -> Any:
    """Playground's ``Go1JoystickRoughTerrain`` (``joystick.Joystick`` with
    ``task="rough_terrain"``) on rse's field: the scene's height field
    replaced by one of ``envs``' slot shape holding env 0's terrain (each
    world gets its own through ``terrains_fn``), MJX's JAX implementation
    (``impl="jax"``, the one that batches a field per world). ``config``
    and ``config_overrides`` as Playground takes them."""
    from mujoco import mjx

    require_layout(envs, "slots", "MJX batches a field per world")
    # Playground's Go1 classes are not exported: its private package, as
    # listed in rse._adapters.private.
    private.verify("playground")
    from mujoco_playground._src.locomotion.go1 import base, joystick
    from mujoco_playground._src.locomotion.go1 import go1_constants as consts

    config = config if config is not None else joystick.default_config()
    # What Joystick.__init__ sets for its rough task.
    config.naconmax = 8 * 8192
    config.njmax = 12 + 48
    overrides = {**(config_overrides or {}), "impl": "jax"}
    scene = _stepfield_scene(consts.FEET_ONLY_ROUGH_TERRAIN_XML.read_text(), envs)

    class StepfieldJoystick(joystick.Joystick):
        """Playground's Go1 joystick task on an rse stepfield."""

        def __init__(self) -> None:
            # Go1Env reads the scene from a path and its includes and meshes
            # from its assets; the file is read once, here.
            with tempfile.TemporaryDirectory() as folder:
                path = Path(folder) / "scene_rse_stepfield.xml"
                path.write_text(scene)
                base.Go1Env.__init__(self, xml_path=path.as_posix(), config=config, config_overrides=overrides)
            private.getattr_checked(self, "_post_init", "playground")()
            model = private.getattr_checked(self, "_mj_model", "playground")
            hid = model.hfield(FIELD).id
            adr = int(model.hfield_adr[hid])
            model.hfield_data[adr : adr + envs.samples[0].size] = envs.samples[0].ravel()
            private.setattr_checked(self, "_mjx_model", mjx.put_model(model, impl="jax"), "playground")

    return StepfieldJoystick()


def terrains_fn(env: Any, envs: EnvTerrains, *, field: str = FIELD, floor: str = FLOOR) -> Callable[..., tuple[Any, Any]]:
    """The ``randomization_fn`` giving world ``w`` of ``env`` (from
    ``go1_joystick(envs)``) env ``w``'s terrain:
    ``fn(model, rng=None) -> (batched model, in_axes)``, as Playground's
    ``wrap_for_brax_training`` and Brax's PPO call it. ``hfield_data`` and
    ``geom_pos`` get a world axis: world ``w``'s floor is moved by
    ``-envs.origins[w]``, so its spawn origin is at (0, 0, 0). Brax passes
    one key per world in ``rng``: training asks for ``num_envs`` worlds
    (make ``envs`` with as many), evaluation for ``num_eval_envs``, which
    get the first envs' terrains; more worlds than envs is a
    ``ValueError``."""

    mjm = env.mj_model
    hint = "build it with rse.playground.go1_joystick(envs)"
    adr, _ = env_field(mjm, envs, field, "env", hint)
    gid = geom_id(mjm, floor, "env", hint)

    def fn(model: Any, rng: Any = None) -> tuple[Any, Any]:
        import jax
        import jax.numpy as jnp

        worlds = envs.num_envs if rng is None else len(rng)
        if worlds > envs.num_envs:
            raise ValueError(f"num_envs: Brax asks for {worlds} worlds per device, rse has {envs.num_envs} envs' terrains")
        rows = world_rows(model.hfield_data, adr, envs.samples[:worlds])
        pos = np.repeat(np.asarray(model.geom_pos, dtype=np.float32)[None], worlds, axis=0)
        pos[:, gid] -= envs.origins[:worlds].astype(np.float32)
        batched = model.replace(hfield_data=jnp.asarray(rows), geom_pos=jnp.asarray(pos))
        axes = jax.tree_util.tree_map(lambda _: None, model).replace(hfield_data=0, geom_pos=0)
        return batched, axes

    return fn

