"""The mjlab terms that run in a step on rse's terrains: the exact height
scan (an observation), ``out_of_slot`` (a termination) and
``bound_near_robots`` (a step event)."""

from __future__ import annotations

from typing import Any, Optional

from rse._adapters import private
from rse._adapters.mjlab.reset_event import TERM, event_of


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
    under it, ``[B, F·N]``), from each env's exact tops instead of the
    rays: also within a sample of a step edge, where the height field is
    MuJoCo's slope between two samples. Off an env's terrain the top is
    the ground plane at its foot (0); a point farther below its frame than
    the sensor's ``max_distance`` is a miss (``miss_value``, default
    ``max_distance``), as for the rays. The sensor must cast its rays
    straight down (a grid pattern), as the velocity tasks' does. Computed
    where the simulation runs (``DeviceTops``: on a GPU from the fields
    there), with no copy between the host and a device. Use it in place
    of ``height_scan``:
    ``ObservationTermCfg(func=exact_height_scan, params={"sensor_name": "terrain_scan"})``."""
    import torch

    sensor = env.scene[sensor_name]
    event = event_of(env, term)
    if miss_value is None:
        miss_value = sensor.cfg.max_distance
    origins = private.getattr_checked(sensor, "_cached_world_origins", "mjlab")
    if origins is None:
        # No ray cast yet: mjlab's observation manager calls each term
        # once when it is built, for its shape. Every ray a miss.
        return torch.full((env.num_envs, sensor.num_rays), float(miss_value), device=env.device)
    B = origins.shape[0]
    xy = event.apart.slot_xy(origins[..., :2].detach())
    tops = event.exact_tops().tops(xy).to(origins.dtype)
    F, N = sensor.num_frames, sensor.num_rays_per_frame
    frame_z = sensor.data.frame_pos_w[:, :, 2:3]
    reach = (frame_z - tops.view(B, F, N)).view(B, F * N)
    return torch.where(reach > sensor.cfg.max_distance, miss_value, reach - offset)


def out_of_slot(env: Any, term: str = TERM, asset_name: str = "robot", margin: float = 0.3) -> Any:
    """mjlab termination term (time-out kind), as the velocity tasks'
    ``out_of_terrain_bounds`` for rse's pool: true where the robot's base
    is more than ``margin`` metres outside its env's terrain (its slot:
    ``[0, nx·s] × [0, ny·s]`` in its own world, twice the field's centre,
    ``hfield_pos``: no terrain is copied out in a step)."""
    event = event_of(env, term)
    xy = event.apart.slot_xy(env.scene[asset_name].data.root_link_pos_w[:, :2])
    size = event.apart.slot_size(xy)
    return ((xy < -margin) | (xy > size + margin)).any(dim=1)


def bound_near_robots(env: Any, env_ids: Any = None, term: str = TERM) -> None:
    """mjlab event term of mode ``"step"``: each world's terrain geoms
    bounded by the square its robot can reach before the next step, up to
    the highest top in it (``EnvTerrainsEvent.bound_near_robots``), so that
    the broadphase pairs a robot geom with the terrain only near a top
    that comes up to it. ``use_env_terrains`` adds it. It changes no
    contact: a pair it drops could not touch."""
    event_of(env, term).bound_near_robots()
