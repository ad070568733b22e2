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
        import warp as wp

        from rse._adapters.mjlab.tops_kernel import Square, near_boxes

        mjm = sim.mj_model
        device = sim.wp_model.hfield_data.device
        self.gids: Any = wp.array(np.asarray(gids, dtype=np.int32), dtype=wp.int32, device=device)
        self.offsets: Any = wp.array(np.asarray(apart.offsets, dtype=np.float32), dtype=wp.vec2, device=device)
        self.tops = tops
        self.square: Any = Square()
        self.square.root = root
        self.square.dof = int(mjm.jnt_dofadr[mjm.body_jntadr[root]])
        self.square.horizon = horizon
        self.square.slack = SLACK
        x, y = 0.5 * apart.size
        self.square.centre = wp.vec2(float(x), float(y))
        _, _, _, self.square.base = tops.envs.hfield_size
        self.reach = reach_m
        # Compiled now, not in the first step.
        wp.load_module(near_boxes.module, device=device)

    @property
    def reach(self) -> float:
        """How far from the root a geom that may touch the terrain reaches
        (``near.reach``), metres."""
        return float(self.square.reach)

    @reach.setter
    def reach(self, metres: float) -> None:
        # The largest half side the gather covers, and the cells a square
        # of that half side touches, one more each side.
        s = self.square
        s.reach = metres
        s.cap = metres + 2.0 * s.horizon * SPEED_CAP + SLACK
        s.span = int(math.ceil(2.0 * s.cap / self.tops.block)) + 4

    def update(self, sim: Any) -> None:
        """Bounds every world's terrain geoms by the square around its
        robot now: one kernel on the simulation's device
        (``tops_kernel.near_boxes``), written into the model's per-world
        ``geom_aabb``."""
        import warp as wp

        from rse._adapters.mjlab.tops_kernel import near_boxes

        m, d, t = sim.wp_model, sim.wp_data, self.tops
        wp.launch(
            near_boxes,
            dim=d.nworld,
            inputs=[m.hfield_data, t.starts, t.grid, self.square, d.xpos, d.qvel, self.offsets, self.gids],
            outputs=[m.geom_aabb],
            device=m.hfield_data.device,
        )
