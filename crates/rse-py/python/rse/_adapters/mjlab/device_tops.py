"""Every env's exact tops on the simulation's device, for the terms that
read them in a step (``exact_height_scan``): on a GPU one kernel over the
fields where they already are (``tops_kernel``), on the CPU device ``heights_at`` over the
points' own memory; no copy between the host and a device either way."""

from __future__ import annotations

from typing import Any

import numpy as np

from rse._adapters import contacts
from rse._rse import EnvTerrains


class DeviceTops:
    """Every env's exact tops on the simulation's device, read from the
    pool's fields where they are (the device model's ``hfield_data``, no
    copy kept): each cell's k×k samples hold its top, or a ramp's plane
    over it (``tops_kernel.cell_top``). Only the fields' addresses and the
    grid's shape are made here, once (``starts``, ``grid``: the kernels'
    arguments, also ``near.NearRobotBounds``')."""

    def __init__(self, sim: Any, envs: EnvTerrains, name: str) -> None:
        import mujoco
        import torch
        import warp as wp

        from rse._adapters.mjlab.tops_kernel import Grid, tops_under

        mjm = sim.mj_model
        first = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_HFIELD, f"{name}0")
        n = envs.num_envs
        self.block = float(envs.terrain(0).block_size)
        self.model = sim.wp_model
        device = sim.wp_model.hfield_data.device
        self.starts: Any = wp.array(mjm.hfield_adr[first : first + n].astype(np.int64), dtype=wp.int64, device=device)
        """Each env's field's first sample in ``hfield_data``."""
        g: Any = Grid()
        g.ny, g.nx = contacts.slot_cells(envs)  # a slot's: the largest grid of a mix
        g.k, g.ncol = contacts.oversample_of(envs), int(mjm.hfield_ncol[first])
        g.block, g.elevation, g.z0 = self.block, float(envs.hfield_size[2]), float(envs.hfield_pos[2])
        self.grid = g
        """The slot's grid: the kernels' (``tops_kernel.Grid``)."""
        # Compiled now, not in the first step.
        wp.load_module(tops_under.module, device=device)
        self.envs = envs
        self.all = np.arange(n)
        self.on_host = torch.device(sim.device).type == "cpu"
        """Whether the fields' device is the host: there the tops come from
        ``EnvTerrains.heights_at`` over the points' own memory (0.15 ms for
        32 envs × 187 points, against 0.20 ms for the kernel on the CPU),
        elsewhere from one kernel on the device (``device_tops``)."""

    def tops(self, xy: Any) -> Any:
        """The tops under ``xy`` (``[num_envs, P, 2]``, each env's slot
        frame, metres): ``[num_envs, P]``, 0 off its terrain. As
        ``EnvTerrains.heights_at``: a point on a line between cells reads
        the highest of them; the cells are found in float64, as there."""
        import torch

        if not self.on_host:
            return self.device_tops(xy)
        tops = self.envs.heights_at(self.all, xy.detach().numpy())
        return torch.from_numpy(np.nan_to_num(tops, nan=0.0, copy=False))

    def device_tops(self, xy: Any) -> Any:
        """``tops`` by one kernel where ``xy`` is (``tops_kernel.tops_under``):
        the two cells a point may touch along each axis, each cell's top at
        the point from its own samples, their highest. A cell's samples
        hold its top, or a ramp's plane over it: the plane through its
        first sample and its last along each axis, at the point, is either
        (a flat cell's samples are equal: its top exactly)."""
        import torch
        import warp as wp

        from rse._adapters.mjlab.tops_kernel import tops_under

        points = xy.detach().to(torch.float64).reshape(xy.shape[0], -1, 2).contiguous()
        out = torch.empty(points.shape[:2], dtype=torch.float64, device=points.device)
        data = self.model.hfield_data
        wp.launch(
            tops_under,
            dim=tuple(points.shape[:2]),
            inputs=[data, self.starts, self.grid, wp.from_torch(points, dtype=wp.float64)],
            outputs=[wp.from_torch(out, dtype=wp.float64)],
            device=data.device,
        )
        return out.view(xy.shape[:-1])
