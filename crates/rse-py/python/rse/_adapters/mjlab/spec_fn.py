"""The scene's ``spec_fn``: rse's pool added while mjlab's ``Scene`` builds
the scene, sized and set from the ``Scene`` being built (its env count,
its ``EnvTerrainCfg``, the run ``play`` replays)."""

from __future__ import annotations

from typing import Any

from rse._adapters import private
from rse._adapters.mjlab.pool import add_pool, available_memory, pool_memory
from rse._adapters.mjlab.terrains import probe_envs, scheme_of, terrain_settings


class PoolSpec:
    """The scene's ``spec_fn``: the earlier one, then rse's pool, one field
    per env of the scene being built. Everything is read from the ``Scene``
    mjlab is building (the caller of ``spec_fn``): its env count and its
    ``EnvTerrainCfg``, as mjlab's ``train`` and ``play`` rebuilt it from the
    registered config with the command line's overrides
    (``--env.scene.num-envs 4096``, ``--env.scene.terrain.scheme``). It
    holds no settings of its own, so a run's logged config (``env.yaml``)
    has the scheme once, where it was set."""

    def __init__(self, earlier: Any) -> None:
        self.earlier = earlier

    def __call__(self, spec: Any) -> None:
        if self.earlier is not None:
            self.earlier(spec)
        scene, device = scene_being_built()
        if type(scene.terrain).__name__ != "EnvTerrainCfg":
            raise ValueError(
                f"env_cfg.scene.terrain: rse's pool needs the EnvTerrainCfg use_env_terrains set; the scene's terrain is a {type(scene.terrain).__name__}"
            )
        from rse._mjlab_scene import check

        play_the_runs_scheme(scene.terrain)
        # Fields set by assignment after the config was made (and the
        # run's, in play) were not checked: checked and recorded now, once,
        # before anything is built.
        check(scene.terrain)
        settings = terrain_settings(scene.terrain)
        scheme = scheme_of(settings["scheme"])
        oversample = settings["oversample"]
        n = int(scene.num_envs)
        host, on_device = pool_memory(probe_envs(scheme, oversample), n, device)
        print(
            f"[INFO] rse terrains: {n} envs, {(host + on_device) / n / 2**20:.2f} MiB an env, "
            f"{host / 2**30:.2f} GiB in host memory" + (f" and {on_device / 2**30:.2f} GiB on {device}" if on_device else "")
        )
        available = available_memory()
        if available is not None and host > available:
            raise MemoryError(
                f"env.scene.num_envs: {n} envs of this scheme take about {host / 2**30:.1f} GiB of host memory "
                f"and {available / 2**30:.1f} GiB is available; use fewer envs, a smaller scheme or "
                "--env.scene.terrain.oversample 1"
            )
        add_pool(spec, scheme, n, oversample=oversample, apart=bool(settings.get("apart")))


def play_the_runs_scheme(terrain: Any) -> None:
    """In mjlab's ``play`` of a checkpoint whose run recorded its terrains
    (``rse._mjlab_run``), the terrain's scheme and seed become the run's,
    and it says so: ``play`` takes no terrain flags, and would show the
    task's registered scheme. Found as ``run_play``'s ``resume_path`` on
    the call stack (``play`` builds the env inside it); elsewhere nothing
    changes."""
    from rse._mjlab_run import run_terrain

    def resume_path(frame: Any) -> Any:
        if frame.f_code.co_name == "run_play" and frame.f_globals.get("__name__", "").startswith("mjlab."):
            return frame.f_locals.get("resume_path")
        return None

    resume = on_the_stack(resume_path)
    recorded = run_terrain(str(resume)) if resume is not None else None
    if recorded is None:
        return
    for name, value in recorded.items():
        setattr(terrain, name, value)
    shown = recorded["scheme"] or ", ".join(recorded["schemes"])
    print(f"[INFO] rse: playing on what the run trained on: {shown} (seed {terrain.seed})")


def on_the_stack(pick: Any) -> Any:
    """The first value ``pick(frame)`` gives that is not None, walking up
    the call stack from the caller; None if none does."""
    import inspect

    frame = inspect.currentframe()
    try:
        while frame is not None:
            found = pick(frame)
            if found is not None:
                return found
            frame = frame.f_back
    finally:
        del frame
    return None


def scene_being_built() -> tuple[Any, str]:
    """The ``SceneCfg`` and device of the mjlab ``Scene`` whose construction
    called this (through ``spec_fn``)."""
    from mjlab.scene import Scene

    def scene(frame: Any) -> Any:
        owner = frame.f_locals.get("self")
        if isinstance(owner, Scene):
            return private.getattr_checked(owner, "_cfg", "mjlab"), str(owner.device)
        return None

    found = on_the_stack(scene)
    if found is None:
        raise ValueError("env_cfg.scene.spec_fn: rse's pool is added while mjlab's Scene builds the scene (ManagerBasedRlEnv)")
    return found
