"""Each world's terrain geoms bounded, every step, by the square around its
robot that the robot can reach before the next step, up to the highest
top in that square: MuJoCo Warp's broadphase then pairs a robot geom with
the terrain only where a top near the robot comes up to it, not wherever
the slot holds a step (``TerrainBounds`` bounds a whole terrain at a
reset; this narrows it between resets).

The square holds every geom of the robot that may touch the terrain, in
every pose of its joints (``reach``), wherever the robot's root can go
before the next update (its speed over the step and a substep, doubled):
a geom outside it cannot touch a cell of it, and a geom inside cannot
touch a top above the square's highest. So a pair the square drops would
have made no contact: the simulation is the same, fewer pairs are
tested."""

from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

from rse._adapters.mjlab.device_tops import DeviceTops
from rse._adapters.mjlab.terrain_bounds import z_extent
from rse._adapters.mjlab.watch_layout import Apart

SLACK = 0.02
"""Metres added to each square's half side: a fall's gain in speed over
a step (g·t²/2 is 3 mm at 25 ms) and the cell a riser's slope takes."""

SPEED_CAP = 4.0
"""Root speed (m/s) the gather is sized for; an env moving faster is
bounded by its square up to the highest top a terrain may have."""


def terrain_colliders(mjm: Any, terrain: list[int]) -> np.ndarray:
    """The geoms that may collide with any of the ``terrain`` geoms
    (MuJoCo's ``contype``/``conaffinity`` test; explicit pairs too), the
    terrain's own body left out."""
    bodies = {int(mjm.geom_bodyid[g]) for g in terrain}
    found = np.zeros(mjm.ngeom, dtype=bool)
    for t in terrain:
        found |= ((mjm.geom_contype & mjm.geom_conaffinity[t]) | (mjm.geom_conaffinity & mjm.geom_contype[t])) != 0
        for a, b in zip(mjm.pair_geom1, mjm.pair_geom2):
            if t in (a, b):
                found[b if a == t else a] = True
    found &= ~np.isin(mjm.geom_bodyid, list(bodies | {0}))
    return np.flatnonzero(found)


def free_root(mjm: Any, geoms: np.ndarray) -> Optional[int]:
    """The one body, moving freely (its first joint a free joint), whose
    tree holds every geom of ``geoms``, or None (no such geom, or several
    trees: each would need a square of its own)."""
    import mujoco

    roots = {int(mjm.body_rootid[mjm.geom_bodyid[g]]) for g in geoms}
    if len(roots) != 1:
        return None
    root = roots.pop()
    first = int(mjm.body_jntadr[root])
    if first < 0 or mjm.jnt_type[first] != mujoco.mjtJoint.mjJNT_FREE:
        return None
    return root


def reach(mjm: Any, root: int, geoms: np.ndarray) -> float:
    """How far from ``root``'s origin any point of ``geoms`` (and its
    margin) can be, in any pose of the joints below ``root``: along each
    body's chain, its offset from its parent plus twice each joint's offset
    in it (a hinge or a ball turns the body's origin about the joint) plus
    a slide's longest travel, then the geom's offset and bounding
    radius."""
    import mujoco

    far = np.zeros(mjm.nbody)
    for b in range(root + 1, mjm.nbody):
        parent = int(mjm.body_parentid[b])
        if int(mjm.body_rootid[b]) != root:
            continue
        out = float(np.linalg.norm(mjm.body_pos[b]))
        for j in range(int(mjm.body_jntadr[b]), int(mjm.body_jntadr[b] + mjm.body_jntnum[b])):
            out += 2.0 * float(np.linalg.norm(mjm.jnt_pos[j]))
            if mjm.jnt_type[j] == mujoco.mjtJoint.mjJNT_SLIDE:
                out += float(np.abs(mjm.jnt_range[j]).max()) if mjm.jnt_limited[j] else math.inf
        far[b] = far[parent] + out
    return max(
        float(far[mjm.geom_bodyid[g]] + np.linalg.norm(mjm.geom_pos[g]) + mjm.geom_rbound[g] + mjm.geom_margin[g] + mjm.geom_gap[g])
        for g in geoms
    )


class NearRobotBounds:
    """Each world's terrain geoms ``gids`` bounded, at each ``update``, by
    the square around its robot's root (``root``, a free body) that the
    robot's geoms can reach before the next update, up to the highest top
    of its env's terrain in that square. A horizon of ``horizon`` seconds:
    the step after the update and the substep its positions lag by."""

    def __init__(self, sim: Any, gids: list[int], root: int, reach_m: float, horizon: float, tops: DeviceTops, apart: Apart) -> None:
        import torch

        mjm = sim.mj_model
        self.gids = torch.as_tensor(gids, dtype=torch.long, device=sim.device)
        self.root = root
        self.dof = int(mjm.jnt_dofadr[mjm.body_jntadr[root]])
        self.reach = reach_m
        self.horizon = horizon
        self.tops = tops
        self.apart = apart
        self.cap = reach_m + 2.0 * horizon * SPEED_CAP + SLACK
        """The largest half side the gather covers, metres."""
        # Cells a square of half side `cap` touches, and one more each side.
        self.span = int(math.ceil(2.0 * self.cap / tops.block)) + 4
        self.steps = torch.arange(self.span, device=sim.device)
        self.centre = torch.as_tensor(0.5 * apart.size, dtype=torch.float32, device=sim.device)
        _, _, _, self.base = tops.envs.hfield_size

    def update(self, sim: Any) -> None:
        """Bounds every world's terrain geoms by the square around its
        robot now: tensor ops on the simulation's device, written into the
        model's per-world ``geom_aabb``."""
        import torch

        t = self.tops
        ny, nx = t.cells
        xy = self.apart.slot_xy(sim.data.xpos[:, self.root, :2]).to(torch.float32)
        speed = torch.linalg.vector_norm(sim.data.qvel[:, self.dof : self.dof + 3], dim=1).to(torch.float32)
        half = self.reach + 2.0 * self.horizon * speed + SLACK
        # The cells the square touches, one more each side (a riser's
        # slope), clamped onto the terrain; those past the square repeat
        # its last and are masked.
        first = torch.floor((xy - half[:, None]) / t.block).long() - 1
        last = torch.floor((xy + half[:, None]) / t.block).long() + 1
        cx, cy = first[:, 0:1] + self.steps, first[:, 1:2] + self.steps
        inside = (cy <= last[:, 1:2]).unsqueeze(2) & (cx <= last[:, 0:1]).unsqueeze(1)
        index = t.adr.view(-1, 1, 1) + (cy.clamp(0, ny - 1) * (t.k * t.ncol)).unsqueeze(2) + (cx.clamp(0, nx - 1) * t.k).unsqueeze(1)
        samples = torch.take(t.samples(), index).masked_fill_(~inside, 0.0)
        top = samples.amax(dim=(1, 2)).to(torch.float32)
        # Faster than the gather covers: up to the highest top there is.
        top = torch.where(half <= self.cap, top, 1.0) * t.elevation
        z, half_z = z_extent(top, self.base)
        box = torch.stack(
            [
                torch.stack([xy[:, 0] - self.centre[0], xy[:, 1] - self.centre[1], z], dim=1),
                torch.stack([half, half, half_z], dim=1),
            ],
            dim=1,
        )
        aabb = sim.model.geom_aabb
        aabb[:, self.gids] = box.unsqueeze(1).to(aabb.dtype)
