"""Every env's exact tops on the simulation's device, for the terms that
read them in a step (``exact_height_scan``): on a GPU tensor ops on the
fields where they already are, on the CPU device ``heights_at`` over the
points' own memory; no copy between the host and a device either way."""

from __future__ import annotations

from typing import Any

import numpy as np

from rse._adapters import contacts
from rse._rse import EnvTerrains


class DeviceTops:
    """Every env's exact tops on the simulation's device, read from the
    pool's fields where they are (the device model's ``hfield_data``, no
    copy kept): each cell's k×k samples hold its height, so the sample at
    a cell's first corner is its top. Only the fields' addresses are made
    here, once."""

    def __init__(self, sim: Any, envs: EnvTerrains, name: str) -> None:
        import mujoco
        import torch

        mjm = sim.mj_model
        first = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_HFIELD, f"{name}0")
        n = envs.num_envs
        t = envs.terrain(0)
        self.cells = contacts.slot_cells(envs)  # (ny, nx): a slot's, the largest grid of a mix
        self.k = contacts.oversample_of(envs)
        self.ncol = int(mjm.hfield_ncol[first])
        self.block = float(t.block_size)
        _, _, self.elevation, _ = envs.hfield_size
        self.z0 = float(envs.hfield_pos[2])
        self.model = sim.wp_model
        self._wrapped: Any = None
        self._tensor: Any = None
        self.adr = torch.as_tensor(mjm.hfield_adr[first : first + n].astype(np.int64), device=sim.device)
        self.envs = envs
        self.all = np.arange(n)
        self.on_host = torch.device(sim.device).type == "cpu"
        """Whether the fields' device is the host: there the tops come from
        ``EnvTerrains.heights_at`` over the points' own memory (3.3x faster
        than the tensor ops on the CPU), elsewhere from tensor ops on the
        device (``device_tops``)."""

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
        """``tops`` by tensor ops where ``xy`` is: the two cells a point
        may touch along each axis, each cell's top at the point from its
        own samples, their highest. A cell's samples hold its top, or a
        ramp's plane over it: the plane through its first sample and its
        last along each axis, at the point, is either (a flat cell's
        samples are equal: its top exactly)."""
        import torch

        ny, nx = self.cells
        k = self.k
        u = xy.to(torch.float64) / self.block
        ux, uy = u[..., 0], u[..., 1]
        row = k * self.ncol
        data, start = self.samples(), self.adr.view(-1, *([1] * (ux.dim() - 1)))
        # Each cell's first sample sits (½)/k of the way across it, its
        # last (k − ½)/k: a point's place in the cell, in sample spacings
        # from the first, over the k − 1 between first and last.
        span = float(max(k - 1, 1))
        top = None
        for cy in ((torch.ceil(uy) - 1.0).clamp_(0, ny - 1), torch.floor(uy).clamp_(0, ny - 1)):
            for cx in ((torch.ceil(ux) - 1.0).clamp_(0, nx - 1), torch.floor(ux).clamp_(0, nx - 1)):
                first = start + cy.long() * row + cx.long() * k
                a = torch.take(data, first).to(torch.float64)
                if k > 1:
                    along_x = torch.take(data, first + (k - 1)).to(torch.float64) - a
                    along_y = torch.take(data, first + (k - 1) * self.ncol).to(torch.float64) - a
                    fx = ((ux - cx) * k - 0.5) / span
                    fy = ((uy - cy) * k - 0.5) / span
                    a = a + along_x * fx + along_y * fy
                top = a if top is None else torch.maximum(top, a)
        assert top is not None
        on = (ux >= 0) & (ux <= nx) & (uy >= 0) & (uy <= ny)
        return torch.where(on, top * self.elevation + self.z0, 0.0)

    def samples(self) -> Any:
        """The device model's ``hfield_data`` as a tensor sharing its memory,
        wrapped once (Warp's CPU interop goes through numpy), and again only
        if the model's array was replaced."""
        import warp as wp

        array = self.model.hfield_data
        if array is not self._wrapped:
            self._wrapped, self._tensor = array, wp.to_torch(array)
        return self._tensor
