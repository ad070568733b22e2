"""The contacts' routing at run time: the coarse fields ``add_pool`` made
for the robot's large geoms, their geom routed per world and their
samples copied in at a reset (``rse._adapters.contacts`` chose the geoms
and set their bits when the scene was built)."""

from __future__ import annotations

from typing import Any

import numpy as np

from rse._adapters import contacts
from rse._adapters.pool import GEOM
from rse._adapters.uploads import Block, Filled
from rse._adapters.warp_fields import route_per_world
from rse._rse import EnvTerrains


class CoarsePool:
    """The coarse fields ``add_pool`` made for the robot's large geoms, if
    any: their geom routed to env ``w``'s coarse field in world ``w``, and
    the reset envs' coarse samples copied in beside the exact ones."""

    def __init__(self, m: Any, mjm: Any, envs: EnvTerrains, name: str) -> None:
        import mujoco

        self.gid = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, GEOM + contacts.COARSE)
        if self.gid < 0:
            return
        first = mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_HFIELD, f"{name}{contacts.COARSE}0")
        self.adr = np.asarray(mjm.hfield_adr[first : first + envs.num_envs], dtype=np.int64)
        route_per_world(m, self.gid, first)

    def blocks(self, mjm: Any, envs: EnvTerrains, ids: list[int], target: int) -> list[Block]:
        """Copies the coarse samples of ``ids`` into the host model
        ``mjm`` and returns them as an ``Uploads`` block for the device
        model's ``hfield_data``, which the caller names ``target``: each
        cell's sample the mean of its first and last (``EnvTerrains._copy_fields``
        with ``coarse``, a thread an env)."""
        if self.gid < 0 or not ids:
            return []
        starts = self.adr[ids]
        envs._copy_fields(ids, mjm.hfield_data, starts, coarse=True)
        size = int(np.prod(contacts.slot_cells(envs)))
        return [(target, starts, Filled(size, lambda data, at, part: envs._copy_fields(ids[part], data, at, coarse=True)), None)]
