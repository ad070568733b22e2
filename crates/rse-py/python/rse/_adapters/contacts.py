"""Contacts without overflow on an oversampled pool: MuJoCo (and MuJoCo
Warp) test a geom against every height-field prism under it and keep at
most ``MAX_PRISMS`` (``mjMAXCONPAIR``) prisms in contact per pair; past
that they drop the rest and warn ("height field collision overflow"). A
foot is small beside rse's 5 cm samples; a fallen robot's trunk, torso
or thigh lying on the terrain covers more than 50 of them. So the robot's
large geoms collide with a coarse copy of each env's field (one sample a
cell: the cells' heights at their centres), its small ones (the feet) with
the exact, oversampled one. Which geom is large is read from its shape:
its widest footprint in cells (``footprint_cells``). bench/mjlab_contacts.py
measured the split; docs/train.md says why."""

from __future__ import annotations

import math
from typing import Any

from rse._rse import EnvTerrains

MAX_PRISMS = 50
"""MuJoCo's and MuJoCo Warp's cap on height-field prisms in contact with
one geom (``mjMAXCONPAIR``)."""

LARGE_CELLS = 20.0
"""A geom whose footprint may cover more cells than this (two prisms a
cell: 40 of the 50) collides with the coarse field."""

SMALL_BIT = 1 << 29
"""The ``contype`` bit of the geoms that collide with the exact field,
the exact field's ``conaffinity``."""

LARGE_BIT = 1 << 30
"""The ``contype`` bit of the geoms that collide with the coarse field,
the coarse field's ``conaffinity``."""

COARSE = "_coarse"
"""What the coarse fields' and geom's names add to the pool's."""


def oversample_of(envs: EnvTerrains) -> int:
    """Samples per cell along each axis of ``envs``' fields."""
    return int(envs.oversample)


def slot_cells(envs: EnvTerrains) -> tuple[int, int]:
    """The cells of one env's slot (or tile), ``(ny, nx)``: the largest grid
    of a mix (a smaller terrain lies in its first cells)."""
    k = oversample_of(envs)
    nrow, ncol = envs.field_shape
    return nrow // k, ncol // k


def coarse_size(envs: EnvTerrains) -> list[float]:
    """MuJoCo's ``size`` of an env's coarse field: one sample at each cell's
    centre, centred where the exact field is (``hfield_pos``)."""
    s = envs.terrain(0).block_size  # one block size in a mix
    ny, nx = slot_cells(envs)
    _, _, elevation, base = envs.hfield_size
    return [0.5 * (nx - 1) * s, 0.5 * (ny - 1) * s, elevation, base]


def footprint_cells(geom_type: int, size: Any, rbound: float, spacing: float) -> float:
    """How many cells of side ``spacing`` a geom (MuJoCo's compiled
    ``geom_type``, ``geom_size``, ``geom_rbound``) may cover, lying on the
    terrain with its widest side down: its widest shadow's area in cells
    plus the cells its outline crosses."""
    import mujoco

    T = mujoco.mjtGeom
    r = float(size[0])
    if geom_type == T.mjGEOM_SPHERE:
        area, rim = math.pi * r * r, 2 * math.pi * r
    elif geom_type == T.mjGEOM_CAPSULE:
        h = float(size[1])
        area, rim = 4 * h * r + math.pi * r * r, 4 * h + 2 * math.pi * r
    elif geom_type == T.mjGEOM_CYLINDER:
        h = float(size[1])
        area, rim = max(4 * h * r, math.pi * r * r), max(4 * (h + r), 2 * math.pi * r)
    elif geom_type in (T.mjGEOM_BOX, T.mjGEOM_ELLIPSOID):
        a, b, c = sorted(float(x) for x in size[:3])
        area, rim = 4 * b * c, 4 * (b + c)
    else:  # meshes and the rest: the bounding sphere's shadow
        area, rim = math.pi * rbound * rbound, 2 * math.pi * rbound
    return area / (spacing * spacing) + rim / spacing + 1.0


def split_geoms(spec: Any, terrain: set[str], spacing: float) -> tuple[list[Any], list[Any]]:
    """The colliding geoms of ``spec`` (all but those named in ``terrain``)
    small and large enough for the exact field of ``spacing``, by their
    footprint. Only geoms that would collide with a plain terrain geom
    (``contype`` and ``conaffinity`` 1) take part. Compiles ``spec`` once
    to read the geoms' sizes."""
    model = spec.compile()
    small: list[Any] = []
    large: list[Any] = []
    for geom in spec.geoms:
        if geom.name in terrain or not ((geom.contype | geom.conaffinity) & 1):
            continue
        g = geom.id
        cells = footprint_cells(int(model.geom_type[g]), model.geom_size[g], float(model.geom_rbound[g]), spacing)
        (large if cells > LARGE_CELLS else small).append(geom)
    return small, large


def route_geoms(small: list[Any], large: list[Any], exact: Any, coarse: Any, ground: Any) -> None:
    """Sets the collision bits: the ``small`` geoms collide with the
    ``exact`` field, the ``large`` ones with the ``coarse`` field, both with
    the ``ground`` plane; the geoms' own bits stay as they were, so they
    collide with each other and the rest of the scene as before."""
    for geom in small:
        geom.contype |= SMALL_BIT
    for geom in large:
        geom.contype |= LARGE_BIT
    exact.contype, exact.conaffinity = 0, SMALL_BIT
    coarse.contype, coarse.conaffinity = 0, LARGE_BIT
    ground.contype, ground.conaffinity = 0, SMALL_BIT | LARGE_BIT
