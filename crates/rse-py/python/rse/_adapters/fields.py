"""The checks every adapter makes before it touches a simulator: the
``EnvTerrains`` layout it needs, and a height field found by name in a
compiled MuJoCo model (``MjModel``) with its size checked against the
envs'. Errors are ``ValueError``s that start with the argument at fault."""

from __future__ import annotations

from typing import Any

from rse._rse import EnvTerrains


def require_layout(envs: EnvTerrains, layout: str, why: str) -> None:
    """``ValueError`` naming ``envs`` unless they are in ``layout``
    ("slots": a field per env; "tiles": one map); ``why`` says what the
    framework does that needs it."""
    if envs.layout != layout:
        raise ValueError(f'envs: {why}: make them with layout="{layout}"')


def hfield_id(model: Any, name: str, argument: str, hint: str) -> int:
    """The id of the height field ``name`` in ``model``; a ``ValueError``
    naming ``argument`` (the caller's parameter) when there is none, with
    ``hint`` (how to add it) in brackets."""
    import mujoco

    hid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_HFIELD, name)
    if hid < 0:
        raise ValueError(f"{argument}: no height field named {name!r} ({hint})")
    return int(hid)


def geom_id(model: Any, name: str, argument: str, hint: str) -> int:
    """As ``hfield_id``, for the geom ``name``."""
    import mujoco

    gid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, name)
    if gid < 0:
        raise ValueError(f"{argument}: no geom named {name!r} ({hint})")
    return int(gid)


def field_size(model: Any, hid: int) -> int:
    """The number of samples of height field ``hid``."""
    return int(model.hfield_nrow[hid]) * int(model.hfield_ncol[hid])


def env_field(model: Any, envs: EnvTerrains, name: str, argument: str, hint: str) -> tuple[int, int]:
    """The address in ``hfield_data`` and the sample count of the height
    field ``name``, which must hold one env's field of ``envs``; else a
    ``ValueError`` naming ``argument``."""
    hid = hfield_id(model, name, argument, hint)
    size = field_size(model, hid)
    if size != envs.samples[0].size:
        raise ValueError(f"{argument}: height field {name!r} holds {size} samples, but the envs' field has {envs.samples[0].size}")
    return int(model.hfield_adr[hid]), size
