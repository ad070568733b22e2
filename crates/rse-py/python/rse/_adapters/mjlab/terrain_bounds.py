"""Each world's terrain geoms bounded by its own terrain: the box MuJoCo
Warp's broadphase tests a robot geom against (``geom_aabb``, batched per
world) reaches up to that env's highest top, not to the highest a scheme
allows, so a geom above every top of its env's terrain (a hip, a trunk
over low ground) makes no pair with it."""

from __future__ import annotations

from typing import Any

import numpy as np

from rse._adapters.uploads import Block
from rse._rse import EnvTerrains

FIELD = "geom_aabb"
"""The model field batched per world: each geom's box, ``(center, half
size)`` in its frame."""


def z_extent(top: Any, base: float) -> tuple[Any, Any]:
    """The centre and half height in z of a terrain geom's box reaching up
    to ``top`` (metres above the field, an array or a tensor) and down to
    the prisms' bottom, ``base`` below it."""
    return 0.5 * (top - base), 0.5 * (top + base)


class TerrainBounds:
    """The terrain geoms ``gids`` (the exact and coarse fields' geoms, in
    the field's frame: the samples go from 0 to ``elevation`` above it, the
    base ``base`` below) of world ``w`` bounded by env ``w``'s tops, over
    the whole field. The model's ``geom_aabb`` must be batched per world
    (mjlab's ``expand_model_fields``)."""

    def __init__(self, m: Any, mjm: Any, gids: list[int], envs: EnvTerrains) -> None:
        self.gids = [g for g in gids if g >= 0]
        _, _, self.elevation, self.base = envs.hfield_size
        nworld, self.ngeom = m.geom_aabb.shape[:2]
        if nworld != envs.num_envs:
            raise ValueError(f"m: geom_aabb holds {nworld} worlds, expected one per env ({envs.num_envs})")
        self.plan = np.array([mjm.geom_aabb[g, [0, 1, 3, 4]] for g in self.gids], dtype=np.float32).reshape(-1, 4)
        """Each geom's box in x and y as MuJoCo made it: its whole field
        (centre x, y, half sides x, y)."""

    def blocks(self, envs: EnvTerrains, ids: list[int], target: int) -> list[Block]:
        """The boxes of the terrain geoms of the worlds ``ids``, bounded by
        their envs' current tops (``envs.samples``, after
        ``envs.reset(ids)``) over the whole field, as an ``Uploads`` block
        (six floats of ``geom_aabb``, centre and half sides, a geom) into
        the flat float view of the model's ``geom_aabb`` (``flat_boxes``),
        which the caller names ``target``. The whole box, as the step's
        bounds around the robot (``near``) narrow it in x and y, and a
        reset may put the robot anywhere on its terrain."""
        if not ids or not self.gids:
            return []
        samples = envs.samples
        # Each env's highest sample, read where it is (a gather of the
        # rows first took twice as long).
        top = np.array([samples[e].max() for e in ids], dtype=np.float64) * self.elevation
        centre, half = z_extent(top, self.base)
        n, g = len(ids), len(self.gids)
        boxes = np.empty((n, g, 6), dtype=np.float32)
        boxes[:, :, [0, 1, 3, 4]] = self.plan
        boxes[:, :, 2] = centre[:, None]
        boxes[:, :, 5] = half[:, None]
        # Each geom's (center, size) vec3s, as floats.
        starts = (np.asarray(ids, dtype=np.int64)[:, None] * self.ngeom + np.asarray(self.gids, dtype=np.int64)[None, :]) * 6
        return [(target, starts.reshape(-1), boxes.reshape(n * g, 6), None)]


def flat_boxes(m: Any) -> Any:
    """The device model ``m``'s ``geom_aabb`` as one flat float32 Warp
    array over the same memory."""
    return m.geom_aabb.flatten().view(float).flatten()
