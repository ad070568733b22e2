"""The scene's ``spec_fn``: rse's pool added while mjlab's ``Scene`` builds
the scene, sized and set from the scene's own config (its env count, its
``EnvTerrainCfg``), and, in mjlab's ``play``, the run the checkpoint
recorded. Nothing is read off the call stack."""

from __future__ import annotations

import sys
from typing import Any, Optional

from rse._adapters import contacts
from rse._adapters.mjlab.scene_pool import add_pool, available_memory, pool_memory
from rse._adapters.mjlab.terrains import probe_envs, scheme_of, terrain_settings

PLAY_MODULE = "mjlab.scripts.play"
"""mjlab's ``play`` command."""

CHECKPOINT_FLAGS = ("--checkpoint-file", "--checkpoint_file")
"""How ``play``'s command line names the checkpoint it plays (mjlab's
``PlayConfig.checkpoint_file``; tyro takes either spelling)."""


class PoolSpec:
    """The ``spec_fn`` of one scene config (``scene``): the earlier one,
    then rse's pool, one field per env. Made afresh each time the scene
    config's ``spec_fn`` is read (``PoolScene``), so it is bound to the
    config mjlab builds, as mjlab's ``train`` and ``play`` rebuilt it from
    the registered config with the command line's overrides
    (``--env.scene.num-envs 4096``, ``--env.scene.terrain.scheme``). mjlab
    sets ``scene.terrain.num_envs`` from the scene before it calls this."""

    def __init__(self, earlier: Any, scene: Any = None) -> None:
        self.earlier = earlier
        self.scene = scene

    def __getstate__(self) -> dict[str, Any]:
        # A logged config (mjlab's env.yaml, written from a copy) has the
        # scene once, where it is, not again inside its spec_fn.
        return {"earlier": self.earlier}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.earlier, self.scene = state["earlier"], None

    def __call__(self, spec: Any) -> None:
        if self.earlier is not None:
            self.earlier(spec)
        scene = self.scene
        if scene is None:
            raise ValueError("env_cfg.scene.spec_fn: rse's pool is added by the scene config use_env_terrains set (read it from env_cfg.scene)")
        if type(scene.terrain).__name__ != "EnvTerrainCfg":
            raise ValueError(
                f"env_cfg.scene.terrain: rse's pool needs the EnvTerrainCfg use_env_terrains set; the scene's terrain is a {type(scene.terrain).__name__}"
            )
        from rse._adapters.mjlab.scene_cfg import check

        play_the_runs_scheme(scene.terrain)
        # Fields set by assignment after the config was made (and the
        # run's, in play) were not checked: checked and recorded now, once,
        # before anything is built.
        check(scene.terrain)
        settings = terrain_settings(scene.terrain)
        scheme = scheme_of(settings["scheme"])
        oversample = settings["oversample"]
        n = int(scene.num_envs)
        device = likely_device()
        probe = probe_envs(scheme, oversample)
        record_what_is_used(scene.terrain, probe)
        host, on_device = pool_memory(probe, n, device, geoms=len(spec.geoms) + POOL_GEOMS, cameras=has_cameras(scene))
        print(
            f"[INFO] rse terrains: {n} envs, {host / 2**30:.2f} GiB in host memory ({host / n / 1024:.0f} KiB an env)"
            + (f" and {on_device / 2**30:.2f} GiB on {device} ({on_device / n / 1024:.0f} KiB an env)" if on_device else "")
        )
        available = available_memory()
        if available is not None and host > available:
            raise MemoryError(
                f"env.scene.num_envs: {n} envs of this scheme take about {host / 2**30:.1f} GiB of host memory "
                f"and {available / 2**30:.1f} GiB is available; use fewer envs, a smaller scheme or "
                "--env.scene.terrain.oversample 1"
            )
        add_pool(spec, scheme, n, oversample=oversample, apart=bool(settings.get("apart")))


class PoolScene:
    """Mixed into a copy of an mjlab ``SceneCfg`` by ``pool_scene``: its
    ``spec_fn`` reads as a ``PoolSpec`` bound to this very config, so
    every copy (tyro's from the command line, ``dataclasses.replace``,
    ``copy.deepcopy``) adds the pool of its own settings. What was set as
    ``spec_fn`` (the task's own, or a ``PoolSpec`` read from another copy)
    runs first."""

    @property
    def spec_fn(self) -> PoolSpec:
        return PoolSpec(self.__dict__.get("_rse_earlier"), self)

    @spec_fn.setter
    def spec_fn(self, value: Any) -> None:
        self.__dict__["_rse_earlier"] = value.earlier if isinstance(value, PoolSpec) else value


_SCENE_CLASSES: dict[type, type] = {}


def pool_scene(scene: Any) -> Any:
    """A copy of ``scene`` (an mjlab ``SceneCfg``, or a subclass) whose
    ``spec_fn`` adds rse's pool after the one it had. Its class is the
    scene's own with ``PoolScene`` mixed in (its fields, its dataclass
    methods), ``RsePool<Name>``, made once per class. (It needs no name
    pickle could find: mjlab's scene configs do not pickle, their
    entities' defaults being lambdas.)"""
    base = type(scene)
    cls = _SCENE_CLASSES.get(base)
    if cls is None:
        name = f"RsePool{base.__name__}"
        cls = type(name, (PoolScene, base), {"__module__": __name__, "__qualname__": name, "__doc__": base.__doc__})
        _SCENE_CLASSES[base] = cls
    copy: Any = object.__new__(cls)
    fields = dict(vars(scene))
    earlier = fields.pop("spec_fn", None)
    copy.__dict__.update(fields)
    copy.spec_fn = earlier
    return copy


def record_what_is_used(terrain: Any, probe: Any) -> None:
    """Writes into the scene's ``EnvTerrainCfg`` the seed and oversample
    its unset fields (None) resolve to, as the scene is built: the
    scheme's ``# seed:`` (a mix's first scheme's) and rse's default
    oversample. mjlab's ``env.yaml`` and rse's ``rse_terrain.json`` then
    say the same values; the config built once says what it was built
    with. (Not when the config is made: a scheme set later, on ``train``'s
    command line, brings its own seed.)"""
    if terrain.seed is None:
        terrain.seed = int(probe.schemes[0].seed)
    if terrain.oversample is None:
        terrain.oversample = contacts.oversample_of(probe)


POOL_GEOMS = 4
"""The most geoms ``add_pool`` adds: the exact and coarse terrain geoms,
the ground, the view geom."""


def has_cameras(scene: Any) -> bool:
    """Whether the scene config has camera sensors (they render rse's
    terrain through per-env meshes: ``RayMeshes``)."""
    from mjlab.sensor import CameraSensorCfg

    return any(isinstance(s, CameraSensorCfg) for s in (getattr(scene, "sensors", None) or ()))


def likely_device() -> str:
    """Where mjlab will put the simulation: CUDA where torch sees a GPU,
    else the CPU, as ``train`` (CPU when ``CUDA_VISIBLE_DEVICES`` is empty,
    which hides every GPU from torch) and ``play`` (unless ``--device``)
    choose. Only the memory check reads it: the scene config does not
    carry the device, which mjlab passes to its ``Scene`` alone."""
    try:
        import torch

        return "cuda" if torch.cuda.is_available() else "cpu"
    except ImportError:
        return "cpu"


def play_the_runs_scheme(terrain: Any) -> None:
    """In mjlab's ``play`` of a checkpoint whose run recorded its terrains
    (``rse._adapters.mjlab.run_record``), the terrain's scheme and seed become the run's,
    and it says so: ``play`` takes no terrain flags, and would show the
    task's registered scheme. The checkpoint is the one ``play``'s command
    line names (``plays_checkpoint``); elsewhere nothing changes."""
    from rse._adapters.mjlab.run_record import run_terrain

    checkpoint = plays_checkpoint(sys.argv)
    recorded = run_terrain(checkpoint) if checkpoint is not None else None
    if recorded is None:
        return
    for name, value in recorded.items():
        setattr(terrain, name, value)
    shown = recorded["scheme"] or ", ".join(recorded["schemes"])
    print(f"[INFO] rse: playing on what the run trained on: {shown} (seed {terrain.seed})")


def plays_checkpoint(argv: list[str]) -> Optional[str]:
    """The checkpoint file mjlab's ``play`` was given (``--checkpoint-file
    PATH`` on its command line, ``argv``) when this process runs ``play``
    (its module imported, or run as ``python -m``); None otherwise. The
    flag is ``play``'s public interface; a checkpoint found through
    ``--wandb-run-path`` is downloaded without its run folder, so it has no
    record to replay."""
    main = getattr(sys.modules.get("__main__"), "__spec__", None)
    if PLAY_MODULE not in sys.modules and getattr(main, "name", None) != PLAY_MODULE:
        return None
    found = None
    for i, arg in enumerate(argv[1:], start=1):
        for flag in CHECKPOINT_FLAGS:
            if arg == flag and i + 1 < len(argv):
                found = argv[i + 1]
            elif arg.startswith(flag + "="):
                found = arg[len(flag) + 1 :]
    return found
