"""A Unitree Go2 learning to walk on rse stepfield tiles in Genesis: the task
of Genesis's Go2 locomotion example (its robot from Genesis's wheel, its
observations, rewards, gains, commands and PPO settings), with every env on
its own tile of one shared height field and the tiles of the envs that reset
renewed in the built scene (``rse.genesis.reset``).

What differs from Genesis's example, because the ground is no longer flat:
each env spawns over its own tile's origin (the highest top near the tile's
centre) instead of at (0, 0); the base-height reward measures the height
above the terrain under the base; an env whose base leaves its tile resets;
tilt ends an episode past ``max_tilt_deg`` (roll and pitch together, 30°
for 10°: a Go2 standing on steps leans).
``train.py`` trains it with rsl-rl's PPO, as Genesis's example does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import genesis as gs
import rse
import rse.genesis
import torch
from genesis.utils.geom import inv_quat, transform_by_quat
from tensordict import TensorDict

# The Go2's twelve motors in the policy's order (Genesis's example's order).
JOINTS = [f"{leg}_{part}_joint" for leg in ("FR", "FL", "RR", "RL") for part in ("hip", "thigh", "calf")]
# Genesis merges the URDF's fixed foot links into the calves: a foot is its
# calf's sphere geom.
CALVES = [f"{leg}_calf" for leg in ("FR", "FL", "RR", "RL")]
# The standing pose: hips straight, thighs forward, calves folded (radians).
STANCE = {"hip": 0.0, "thigh": {"F": 0.8, "R": 1.0}, "calf": -1.5}

STEPFIELD = """# The Go2's stepfield: 4 m x 4 m tiles of 10 cm blocks, random steps of
# 2.5 cm under a stepped hill and a ridge.
# size: 40x40
# block_size: 0.1
# step_height: 0.025
type,height,angle,x1,y1,x2,y2
random,0..2,,,,,
peak,2..6,20,8..32,8..32,,
wall,1..3,30,5,5..35,35,5..35
"""


def stance(joint: str) -> float:
    """The standing angle of ``joint`` (e.g. ``"FL_thigh_joint"``)."""
    leg, part, _ = joint.split("_")
    angle = STANCE[part]
    return angle[leg[0]] if isinstance(angle, dict) else angle


@dataclass
class Go2Config:
    """The task's settings; the defaults are Genesis's Go2 example's."""

    dt: float = 0.02
    substeps: int = 2
    episode_s: float = 20.0
    command_resample_s: float = 4.0
    kp: float = 20.0
    kd: float = 0.5
    action_scale: float = 0.25
    clip_actions: float = 100.0
    action_latency: bool = True
    spawn_height: float = 0.42
    """Base height above the tile's origin at a reset, metres."""
    max_tilt_deg: float = 30.0
    """Genesis's example ends an episode past 10° of roll or pitch on flat
    ground; on steps a standing Go2 leans more."""
    lin_vel_x: tuple[float, float] = (0.5, 0.5)
    lin_vel_y: tuple[float, float] = (0.0, 0.0)
    ang_vel_z: tuple[float, float] = (0.0, 0.0)
    obs_scales: dict[str, float] = field(
        default_factory=lambda: {"lin_vel": 2.0, "ang_vel": 0.25, "dof_pos": 1.0, "dof_vel": 0.05}
    )
    tracking_sigma: float = 0.25
    base_height_target: float = 0.3
    reward_scales: dict[str, float] = field(
        default_factory=lambda: {
            "tracking_lin_vel": 1.0,
            "tracking_ang_vel": 0.2,
            "lin_vel_z": -1.0,
            "base_height": -50.0,
            "action_rate": -0.005,
            "similar_to_default": -0.1,
        }
    )


def make_tiles(num_envs: int, scheme: str | None = None, seed: int = 0, env_offset: int | None = None) -> rse.EnvTerrains:
    """The envs' tiles: ``scheme`` (a file) or ``STEPFIELD``; the spawn
    origin is the highest top within 0.3 m of a tile's centre, the disc the
    Go2's feet stand in."""
    loaded = rse.Scheme.load(scheme) if scheme else rse.Scheme.from_csv(STEPFIELD)
    return rse.EnvTerrains(loaded, num_envs, layout="tiles", border=2, seed=seed, spawn_radius=0.3, env_offset=env_offset)


class Go2Stepfield:
    """rsl-rl's ``VecEnv``: ``num_envs`` Go2s, env e on tile e of ``tiles``
    (an ``rse.EnvTerrains`` with layout ``"tiles"``). Call ``gs.init``
    first."""

    def __init__(self, tiles: rse.EnvTerrains, cfg: Go2Config | None = None, show_viewer: bool = False) -> None:
        self.cfg = cfg or Go2Config()
        self.tiles = tiles
        self.num_envs = tiles.num_envs
        self.num_actions = len(JOINTS)
        self.device = gs.device
        self.max_episode_length = math.ceil(self.cfg.episode_s / self.cfg.dt)

        self.scene = gs.Scene(
            sim_options=gs.options.SimOptions(dt=self.cfg.dt, substeps=self.cfg.substeps),
            rigid_options=gs.options.RigidOptions(enable_self_collision=False, tolerance=1e-5),
            show_viewer=show_viewer,
        )
        self.terrain = self.scene.add_entity(rse.genesis.terrain_morph(tiles))
        self.robot = self.scene.add_entity(gs.morphs.URDF(file="urdf/go2/urdf/go2.urdf", pos=(0.0, 0.0, self.cfg.spawn_height)))
        self.scene.build(n_envs=self.num_envs)

        self.motors = [self.robot.get_joint(name).dofs_idx_local[0] for name in JOINTS]
        self.feet = [
            geom for name in CALVES for geom in self.robot.get_link(name).geoms if geom.type == gs.GEOM_TYPE.SPHERE
        ]
        self.foot_radius = float(self.feet[0].data[0])
        self.robot.set_dofs_kp([self.cfg.kp] * self.num_actions, self.motors)
        self.robot.set_dofs_kv([self.cfg.kd] * self.num_actions, self.motors)

        def tensor(values, dtype=gs.tc_float):
            return torch.as_tensor(values, dtype=dtype, device=gs.device)

        first = tiles.terrain(0)
        ny, nx = first.elevation.shape
        self.tile_half_extent = tensor([nx * first.block_size / 2, ny * first.block_size / 2])
        self.default_dof_pos = tensor([stance(name) for name in JOINTS])
        self.spawn_pos = torch.zeros((self.num_envs, 3), dtype=gs.tc_float, device=gs.device)
        self.up_quat = tensor([1.0, 0.0, 0.0, 0.0])
        self.gravity = tensor([0.0, 0.0, -1.0])
        low, high = zip(self.cfg.lin_vel_x, self.cfg.lin_vel_y, self.cfg.ang_vel_z)
        self.command_low, self.command_high = tensor(low), tensor(high)
        scales = self.cfg.obs_scales
        self.command_scale = tensor([scales["lin_vel"], scales["lin_vel"], scales["ang_vel"]])

        n, a = self.num_envs, self.num_actions
        self.episode_length_buf = torch.zeros(n, dtype=gs.tc_int, device=gs.device)
        self.commands = torch.zeros((n, 3), dtype=gs.tc_float, device=gs.device)
        self.actions = torch.zeros((n, a), dtype=gs.tc_float, device=gs.device)
        self.last_actions = torch.zeros_like(self.actions)
        # Reward terms are per second of simulation, as in Genesis's example.
        self.reward_scales = {name: scale * self.cfg.dt for name, scale in self.cfg.reward_scales.items()}
        self.episode_sums = {name: torch.zeros(n, dtype=gs.tc_float, device=gs.device) for name in self.reward_scales}
        self.extras: dict = {}
        self.reset()

    # --- state -------------------------------------------------------------------

    def _read_state(self) -> None:
        self.base_pos = self.robot.get_pos()
        self.base_quat = self.robot.get_quat()
        inverse = inv_quat(self.base_quat)
        self.base_lin_vel = transform_by_quat(self.robot.get_vel(), inverse)
        self.base_ang_vel = transform_by_quat(self.robot.get_ang(), inverse)
        self.projected_gravity = transform_by_quat(self.gravity.expand(self.num_envs, 3), inverse)
        self.dof_pos = self.robot.get_dofs_position(self.motors)
        self.dof_vel = self.robot.get_dofs_velocity(self.motors)

    def feet_pos(self) -> torch.Tensor:
        """The feet's sphere centres, ``(num_envs, 4, 3)``, world frame
        (radius ``foot_radius``)."""
        return torch.stack([foot.get_pos() for foot in self.feet], dim=1)

    def _resample_commands(self, mask: torch.Tensor) -> None:
        drawn = self.command_low + (self.command_high - self.command_low) * torch.rand_like(self.commands)
        torch.where(mask[:, None], drawn, self.commands, out=self.commands)

    def get_observations(self) -> TensorDict:
        s = self.cfg.obs_scales
        obs = torch.cat(
            (
                self.base_ang_vel * s["ang_vel"],
                self.projected_gravity,
                self.commands * self.command_scale,
                (self.dof_pos - self.default_dof_pos) * s["dof_pos"],
                self.dof_vel * s["dof_vel"],
                self.actions,
            ),
            dim=-1,
        )
        return TensorDict({"policy": obs}, batch_size=[self.num_envs])

    # --- stepping ----------------------------------------------------------------

    def step(self, actions: torch.Tensor) -> tuple[TensorDict, torch.Tensor, torch.Tensor, dict]:
        self.actions = torch.clip(actions, -self.cfg.clip_actions, self.cfg.clip_actions)
        applied = self.last_actions if self.cfg.action_latency else self.actions
        self.robot.control_dofs_position(applied * self.cfg.action_scale + self.default_dof_pos, self.motors)
        self.scene.step()
        self.episode_length_buf += 1
        self._read_state()

        rewards = torch.zeros(self.num_envs, dtype=gs.tc_float, device=gs.device)
        for name, scale in self.reward_scales.items():
            term = getattr(self, f"_reward_{name}")() * scale
            rewards += term
            self.episode_sums[name] += term

        every = int(self.cfg.command_resample_s / self.cfg.dt)
        self._resample_commands(self.episode_length_buf % every == 0)

        timed_out = self.episode_length_buf > self.max_episode_length
        tilted = self.projected_gravity[:, 2] > -math.cos(math.radians(self.cfg.max_tilt_deg))
        off_tile = ((self.base_pos[:, :2] - self.spawn_pos[:, :2]).abs() > self.tile_half_extent).any(dim=-1)
        dones = timed_out | tilted | off_tile | self.scene.rigid_solver.get_error_envs_mask()
        self.extras["time_outs"] = timed_out.to(gs.tc_float)
        self._reset_idx(dones)
        self.last_actions.copy_(self.actions)
        return self.get_observations(), rewards, dones, self.extras

    def reset(self) -> TensorDict:
        self._reset_idx(torch.ones(self.num_envs, dtype=torch.bool, device=gs.device))
        return self.get_observations()

    def _reset_idx(self, mask: torch.Tensor) -> None:
        """Resets the envs of the boolean ``mask``: new terrains in their
        tiles, their Go2s standing over their new origins."""
        ids = rse.genesis.reset(self.scene, self.terrain, self.tiles, mask)
        if len(ids):
            origins = torch.as_tensor(self.tiles.origins, dtype=gs.tc_float, device=gs.device)
            self.spawn_pos[:] = origins + torch.tensor([0.0, 0.0, self.cfg.spawn_height], device=gs.device)
            qpos = torch.cat(
                (self.spawn_pos, self.up_quat.expand(self.num_envs, 4), self.default_dof_pos.expand(self.num_envs, -1)),
                dim=-1,
            )
            self.robot.set_qpos(qpos, envs_idx=mask, zero_velocity=True)
        self._read_state()
        self.actions.masked_fill_(mask[:, None], 0.0)
        self.last_actions.masked_fill_(mask[:, None], 0.0)
        self.episode_length_buf.masked_fill_(mask, 0)
        count = mask.sum()
        self.extras["episode"] = {
            f"rew_{name}": torch.where(count > 0, sums[mask].sum() / count.clamp(min=1), 0.0) / self.cfg.episode_s
            for name, sums in self.episode_sums.items()
        }
        for sums in self.episode_sums.values():
            sums.masked_fill_(mask, 0.0)
        self._resample_commands(mask)

    # --- rewards (Genesis's example's terms) ---------------------------------------

    def _reward_tracking_lin_vel(self) -> torch.Tensor:
        error = torch.sum(torch.square(self.commands[:, :2] - self.base_lin_vel[:, :2]), dim=1)
        return torch.exp(-error / self.cfg.tracking_sigma)

    def _reward_tracking_ang_vel(self) -> torch.Tensor:
        error = torch.square(self.commands[:, 2] - self.base_ang_vel[:, 2])
        return torch.exp(-error / self.cfg.tracking_sigma)

    def _reward_lin_vel_z(self) -> torch.Tensor:
        return torch.square(self.base_lin_vel[:, 2])

    def _reward_action_rate(self) -> torch.Tensor:
        return torch.sum(torch.square(self.last_actions - self.actions), dim=1)

    def _reward_similar_to_default(self) -> torch.Tensor:
        return torch.sum(torch.abs(self.dof_pos - self.default_dof_pos), dim=1)

    def _reward_base_height(self) -> torch.Tensor:
        # Above the terrain under the base (the ground is not at z = 0 here).
        ground = self.terrain.get_terrain_height(self.base_pos[:, None, :2])[:, 0]
        return torch.square(self.base_pos[:, 2] - ground - self.cfg.base_height_target)
