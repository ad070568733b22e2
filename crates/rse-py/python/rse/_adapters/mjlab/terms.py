"""The mjlab terms that read rse's terrains in a step: the exact height
scan (an observation) and ``out_of_slot`` (a termination)."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from rse._adapters import private
from rse._adapters.mjlab.event import TERM, event_of


def exact_height_scan(
    env: Any,
    sensor_name: str = "terrain_scan",
    term: str = TERM,
    offset: float = 0.0,
    miss_value: Optional[float] = None,
) -> Any:
    """mjlab observation term: the height scan of the ray sensor
    ``sensor_name`` (its pattern, frames and shape, as mjlab's
    ``height_scan`` gives it: each ray's frame height above the terrain
    under it, ``[B, F·N]``), from ``heights_at`` instead of the rays: the
    exact tops, also within a sample of a step edge, where the height
    field is MuJoCo's slope between two samples. Off an env's terrain the
    top is the ground plane at its foot (0); a point farther below its
    frame than the sensor's ``max_distance`` is a miss (``miss_value``,
    default ``max_distance``), as for the rays. The sensor must cast its
    rays straight down (a grid pattern), as the velocity tasks' does.
    Use it in place of ``height_scan``:
    ``ObservationTermCfg(func=exact_height_scan, params={"sensor_name": "terrain_scan"})``."""
    import torch

    sensor = env.scene[sensor_name]
    event = event_of(env, term)
    envs = event.envs
    origins = private.getattr_checked(sensor, "_cached_world_origins", "mjlab")
    if origins is None:
        raise ValueError(f"sensor_name: {sensor_name!r} has cast no rays yet (step or reset the env first)")
    B = origins.shape[0]
    xy = event.apart.slot_xy(origins[..., :2].detach()).to("cpu", torch.float64).numpy()
    tops = envs.heights_at(np.arange(B), xy)
    tops = torch.as_tensor(np.nan_to_num(tops, nan=0.0), device=origins.device, dtype=origins.dtype)
    F, N = sensor.num_frames, sensor.num_rays_per_frame
    frame_z = sensor.data.frame_pos_w[:, :, 2:3]
    heights = (frame_z - tops.view(B, F, N) - offset).view(B, F * N)
    if miss_value is None:
        miss_value = sensor.cfg.max_distance
    reach = (frame_z - tops.view(B, F, N)).view(B, F * N)
    return torch.where(reach > sensor.cfg.max_distance, torch.full_like(heights, miss_value), heights)


def out_of_slot(env: Any, term: str = TERM, asset_name: str = "robot", margin: float = 0.3) -> Any:
    """mjlab termination term (time-out kind), as the velocity tasks'
    ``out_of_terrain_bounds`` for rse's pool: true where the robot's base
    is more than ``margin`` metres outside its env's terrain (its slot:
    ``[0, nx·s] × [0, ny·s]`` in its own world, twice the field's centre,
    ``hfield_pos``: no terrain is copied out in a step)."""
    import torch

    event = event_of(env, term)
    x, y, _ = event.envs.hfield_pos
    xy = event.apart.slot_xy(env.scene[asset_name].data.root_link_pos_w[:, :2])
    size = torch.tensor([2.0 * x, 2.0 * y], device=xy.device, dtype=xy.dtype)
    return ((xy < -margin) | (xy > size + margin)).any(dim=1)
