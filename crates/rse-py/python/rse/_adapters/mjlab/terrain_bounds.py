"""Each world's terrain geoms bounded by its own terrain: the box MuJoCo
Warp's broadphase tests a robot geom against (``geom_aabb``, batched per
world) reaches up to that env's highest top, not to the highest a scheme
allows, so a geom above every top of its env's terrain (a hip, a trunk
over low ground) makes no pair with it."""

from __future__ import annotations

from typing import Any

import numpy as np

from rse._adapters.warp_fields import Run
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
        self.plan = [(float(mjm.geom_aabb[g, 0]), float(mjm.geom_aabb[g, 1]), float(mjm.geom_aabb[g, 3]), float(mjm.geom_aabb[g, 4])) for g in self.gids]
        """Each geom's box in x and y as MuJoCo made it: its whole field
        (centre x, y, half sides x, y)."""

    def runs(self, envs: EnvTerrains, ids: list[int], target: int) -> list[Run]:
        """The boxes of the terrain geoms of the worlds ``ids``, bounded by
        their envs' current tops (``envs.samples``, after
        ``envs.reset(ids)``) over the whole field, as ``Uploads`` runs (six
        floats of ``geom_aabb``, centre and half sides, a geom) into the
        flat float view of the model's ``geom_aabb`` (``flat_boxes``),
        which the caller names ``target``. The whole box, as the step's
        bounds around the robot (``near``) narrow it in x and y, and a
        reset may put the robot anywhere on its terrain."""
        if not ids or not self.gids:
            return []
        top = envs.samples[ids].reshape(len(ids), -1).max(axis=1).astype(np.float64) * self.elevation
        centre, half = z_extent(top, self.base)
        runs = []
        for i, w in enumerate(ids):
            for g, (cx, cy, sx, sy) in zip(self.gids, self.plan):
                box = (w * self.ngeom + g) * 2  # the geom's (center, size) vec3s
                runs.append((target, box * 3, np.array([cx, cy, centre[i], sx, sy, half[i]], dtype=np.float32)))
        return runs


def flat_boxes(m: Any) -> Any:
    """The device model ``m``'s ``geom_aabb`` as one flat float32 Warp
    array over the same memory."""
    return m.geom_aabb.flatten().view(float).flatten()
