"""Where each env's terrain is in its world: all at one place, or laid
out apart on a grid for watching (``EnvTerrainCfg.apart``)."""

from __future__ import annotations

from typing import Any

import numpy as np

from rse._adapters import contacts
from rse._adapters.mjlab.scene_pool import BODY, VIEW
from rse._adapters.pool import GEOM
from rse._adapters.warp_fields import route_per_world
from rse._rse import EnvTerrains

APART_GAP = 1.0
"""Metres between two envs' slots when they are laid out apart."""


class Apart:
    """Where each env's terrain is in its world: all at one place (the
    default: every env in a world of its own), or laid out on a grid,
    ``APART_GAP`` between slots, as mjlab's own terrain lays its envs out,
    so that a viewer drawing every world at once shows each robot on its
    own terrain. ``offsets[e]`` is env ``e``'s xy shift: its terrain geoms
    (per-world ``geom_pos``), its origin and its view body (``mocap_pos``)
    move by it."""

    def __init__(self, sim: Any, envs: EnvTerrains, name: str, on: bool) -> None:
        import mujoco
        import warp as wp

        n = envs.num_envs
        self.offsets = np.zeros((n, 2))
        x, y, _ = envs.hfield_pos
        self.size = np.array([2.0 * x, 2.0 * y])
        """A slot's size ``[x, y]``, metres: twice the field's centre."""
        self.mocap = -1
        self._tensors: dict[tuple[str, Any, Any], Any] = {}
        if not on:
            return
        self.offsets = apart_offsets(envs)
        mjm, m = sim.mj_model, sim.wp_model
        if "geom_pos" not in sim.expanded_fields:
            sim.expand_model_fields(("geom_pos",))
            m = sim.wp_model
        pos = m.geom_pos.numpy()
        for geom in (GEOM, GEOM + contacts.COARSE):
            gid = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, geom)
            if gid >= 0:
                pos[:, gid, :2] = mjm.geom_pos[gid, :2] + self.offsets
        wp.copy(m.geom_pos, wp.array(pos, dtype=wp.vec3, device=m.geom_pos.device))
        view = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, GEOM + VIEW)
        if view < 0:
            raise ValueError("apart: the scene has no view geom (add_pool(..., apart=True) makes it)")
        route_per_world(m, view, mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_HFIELD, f"{name}0"))
        self.mocap = int(mjm.body_mocapid[mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_BODY, BODY + VIEW)])

    def slot_xy(self, xy: Any) -> Any:
        """World xy (torch, ``[num_envs, ..., 2]``) in each env's slot
        frame: less its env's offset."""
        if not self.offsets.any():
            return xy
        shift = self._tensor("offsets", xy)
        return xy - shift.view(shift.shape[0], *([1] * (xy.dim() - 2)), 2)

    def slot_size(self, like: Any) -> Any:
        """``size`` as a tensor of ``like``'s device and dtype."""
        return self._tensor("size", like)

    def _tensor(self, name: str, like: Any) -> Any:
        """The array ``name`` of this object as a tensor of ``like``'s
        device and dtype, made once each: a term's step makes no tensor
        from host data."""
        key = (name, like.device, like.dtype)
        tensor = self._tensors.get(key)
        if tensor is None:
            import torch

            tensor = self._tensors[key] = torch.as_tensor(getattr(self, name), dtype=like.dtype, device=like.device)
        return tensor

    def place(self, sim: Any, ids: list[int], index: Any = None) -> None:
        """Puts the view bodies of ``ids`` (at ``index`` on the device,
        made if None) at their envs' places (a reset may have put them
        back), from the offsets kept on the device."""
        import torch

        if self.mocap < 0 or not ids:
            return
        mocap = sim.data.mocap_pos
        if index is None:
            index = torch.as_tensor(ids, dtype=torch.long, device=mocap.device)
        at = torch.zeros((len(ids), 3), dtype=mocap.dtype, device=mocap.device)
        at[:, :2] = self._tensor("offsets", at)[index]
        mocap[index, self.mocap] = at


def apart_offsets(envs: EnvTerrains) -> np.ndarray:
    """The xy shift of each env's slot laid out apart: a grid of
    ``ceil(sqrt(num_envs))`` columns, ``APART_GAP`` metres between slots,
    env ``e`` in row ``e // cols``, column ``e % cols``."""
    x, y, _ = envs.hfield_pos
    n = envs.num_envs
    cols = max(int(np.ceil(np.sqrt(n))), 1)
    e = np.arange(n)
    return np.stack([(e % cols) * (2.0 * x + APART_GAP), (e // cols) * (2.0 * y + APART_GAP)], axis=1)
