"""A Gymnasium environment with a new stepfield every episode:
Gymnasium's own MuJoCo Ant (``Ant-v5``, its model untouched but for the
ground) on an rse height field that ``reset()`` rewrites in place.

Episode ``e`` (counted from the last ``reset(seed=...)``, or set with
``reset(options={"episode": e})``) walks on world ``e`` of the scheme and
``rse_seed`` (rse's base seed, named as in ``rse.mjlab`` and
``rse.isaaclab``: ``seed`` is Gymnasium's; default the scheme's ``# seed:``)
at ``difficulty``, so every episode's terrain is
reproducible in any process; the robot spawns at the terrain's centre,
``spawn_height`` above the highest top within ``footprint`` metres.
``new_terrain_each_reset=False`` keeps the first episode's terrain (the
baseline ``bench/hfield.py`` compares with)::

    import gymnasium as gym
    import rse.gym  # registers "rse/AntStepfield-v0"

    env = gym.make("rse/AntStepfield-v0", scheme="schemes/six_obstacles.csv", difficulty=0.5)
    obs, info = env.reset(seed=0)       # episode 0; info["episode"], info["terrain_index"]

Needs ``gymnasium`` and ``mujoco`` (``pip install "gymnasium[mujoco]"``).
Generating a new 50×50 terrain and writing it into the live model takes
tens of microseconds (``bench/hfield.py``): next to an episode of hundreds
of steps, nothing.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any, Optional, Union

import numpy as np

import rse
from rse._adapters import private
from rse._rse import DEFAULT_OVERSAMPLE
from rse.mujoco import HFieldSlot, add_hfield, max_top

ENV_ID = "rse/AntStepfield-v0"

INSTALL = 'pip install "gymnasium[mujoco]"'

# Gymnasium's MuJoCo Ant needs gymnasium, mujoco and imageio. Without them
# the environment is still registered (when gymnasium is there at all), and
# gym.make / AntStepfieldEnv raise this error with the install line: a
# registration that silently did not happen reads "Namespace rse not found".
_ANT_IMPORT_ERROR: Optional[ImportError] = None
try:
    from gymnasium.envs.mujoco.ant_v5 import AntEnv as _AntEnv
except ImportError as e:
    _AntEnv = None  # type: ignore[assignment,misc]
    _ANT_IMPORT_ERROR = e


def _missing_ant() -> ImportError:
    """Why the environment cannot be made here, with what installs it."""
    return ImportError(
        f"{ENV_ID} needs Gymnasium's MuJoCo environments, which do not import here "
        f"({_ANT_IMPORT_ERROR}): {INSTALL}"
    )


def ant_on_hfield_xml(scheme: rse.Scheme, oversample: int, elevation: float) -> str:
    """Gymnasium's ``ant.xml`` with an rse height field under it: the field
    (named ``terrain``, flat until ``set_hfield``) centred on the origin
    where the Ant starts, surface from z = 0 to ``elevation``, in geom group
    2 (drawn by default; rays can select it alone); Gymnasium's
    floor plane stays, at z = 0, for a robot that walks off the field."""
    import mujoco
    from gymnasium.envs.mujoco import ant_v5

    ant = Path(ant_v5.__file__).parent / "assets" / "ant.xml"
    spec = mujoco.MjSpec.from_file(str(ant))
    add_hfield(spec, scheme, oversample, name="terrain", elevation=elevation)
    return spec.to_xml()


if _AntEnv is not None:

    class AntStepfieldEnv(_AntEnv):  # type: ignore[misc,valid-type]
        """Gymnasium's Ant on a new rse stepfield every episode (see the
        module's documentation). ``ant_kwargs`` go to ``Ant-v5``."""

        def __init__(
            self,
            scheme: Union[rse.Scheme, str, "os.PathLike[str]"] = "schemes/six_obstacles.csv",
            rse_seed: Optional[int] = None,
            difficulty: Optional[float] = None,
            oversample: int = DEFAULT_OVERSAMPLE,
            footprint: float = 0.6,
            spawn_height: float = 0.75,
            new_terrain_each_reset: bool = True,
            **ant_kwargs: Any,
        ) -> None:
            self.scheme = scheme if isinstance(scheme, rse.Scheme) else rse.Scheme.load(scheme)
            # None for either is the library's default (the scheme's
            # `# seed:`, full difficulty); a bad difficulty is refused here,
            # by the library, not at the first reset.
            self.rse_seed = rse_seed
            self.difficulty = difficulty
            self.scheme.generate(seed=rse_seed, index=0, difficulty=difficulty)
            self.oversample = int(oversample)
            self.footprint = float(footprint)
            self.spawn_height = float(spawn_height)
            self.new_terrain_each_reset = bool(new_terrain_each_reset)
            self.episode = 0
            self.terrain: Optional[rse.Terrain] = None
            top = max_top(self.scheme)
            ant_kwargs.setdefault("healthy_z_range", (0.2, 1.0 + top))
            # Ant-v5 reads its model from a file: write ours once.
            handle, self._xml_path = tempfile.mkstemp(prefix="rse_ant_", suffix=".xml")
            with os.fdopen(handle, "w") as f:
                f.write(ant_on_hfield_xml(self.scheme, self.oversample, top))
            super().__init__(xml_file=self._xml_path, **ant_kwargs)
            self._slot = HFieldSlot(self.model, "terrain", self.oversample)

        def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):  # type: ignore[override]
            if seed is not None:
                self.episode = 0  # a seeded reset restarts the terrain sequence
            if options and "episode" in options:
                self.episode = int(options["episode"])
            obs, info = super().reset(seed=seed, options=options)
            info["episode"] = self.episode
            info["terrain_index"] = self.episode
            self.episode += 1
            return obs, info

        def reset_model(self) -> np.ndarray:
            if self.terrain is None or self.new_terrain_each_reset:
                # Generating on a worker thread ahead of time was tried: in
                # back-to-back resets the hand-over through the GIL cost more
                # than the ~25 us it hides (bench/hfield.py).
                self.terrain = self.scheme.generate(
                    seed=self.rse_seed, index=self.episode, difficulty=self.difficulty
                )
                self._slot.write(self.terrain)
            ground = float(self.terrain.spawn_origin(self.footprint)[2])
            noise = private.getattr_checked(self, "_reset_noise_scale", "gymnasium")
            qpos = self.init_qpos + self.np_random.uniform(low=-noise, high=noise, size=self.model.nq)
            qpos[2] = ground + self.spawn_height
            qvel = self.init_qvel + noise * self.np_random.standard_normal(self.model.nv)
            self.set_state(qpos, qvel)
            return private.getattr_checked(self, "_get_obs", "gymnasium")()

        def close(self) -> None:
            super().close()
            if os.path.exists(self._xml_path):
                os.remove(self._xml_path)


def make_env(**kwargs: Any) -> Any:
    """``gym.make``'s entry point: an ``AntStepfieldEnv``, or the
    ``ImportError`` that names what to install."""
    if _AntEnv is None:
        raise _missing_ant() from _ANT_IMPORT_ERROR
    return AntStepfieldEnv(**kwargs)


def __getattr__(name: str) -> Any:
    if name == "AntStepfieldEnv":  # only defined where Gymnasium's Ant imports
        raise _missing_ant() from _ANT_IMPORT_ERROR
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _register() -> None:
    try:
        import gymnasium
    except ImportError:  # nothing to register with; gym.make cannot be called
        return
    if ENV_ID not in gymnasium.registry:
        gymnasium.register(id=ENV_ID, entry_point="rse.gym:make_env", max_episode_steps=1000)


_register()

__all__ = ["ENV_ID", "INSTALL", "AntStepfieldEnv", "ant_on_hfield_xml", "make_env"]
