# mypy: disable-error-code="valid-type, misc, name-defined"
"""Warp kernels that read each env's exact tops from the pool's fields
where they are (the device model's ``hfield_data``): the tops under given
points (``tops_under``: the exact height scan) and each world's terrain
box around its robot (``near_boxes``: the step event's bounds). One
launch each, where the tensor ops they replace launched 150 (the scan)
and 44 (the bounds) kernels a call from Python, and a GPU pays for each
launch. Imported only where Warp is (mjlab's envs)."""

from __future__ import annotations

# Warp's array annotations are calls, which mypy cannot read: the first
# line of this file.
import warp as wp


@wp.struct
class Grid:
    """Where a slot's cells are in the pool: ``nx`` × ``ny`` cells of
    ``block`` metres, ``k`` × ``k`` samples a cell, rows of ``ncol``
    samples; a sample of 1 is ``elevation`` metres above ``z0``."""

    nx: int
    ny: int
    k: int
    ncol: int
    block: wp.float64
    elevation: wp.float64
    z0: wp.float64


@wp.func
def cell_top(data: wp.array(dtype=float), start: wp.int64, g: Grid, cx: int, cy: int, ux: wp.float64, uy: wp.float64) -> wp.float64:
    # Cell (cx, cy)'s top at (ux, uy) (in cells), a fraction of the
    # elevation: its first sample, or where its samples lie on a ramp's
    # plane, that plane (through its first sample and its last along each
    # axis) at the point; a flat cell's samples are equal.
    first = start + wp.int64(cy) * wp.int64(g.k * g.ncol) + wp.int64(cx * g.k)
    a = wp.float64(data[first])
    if g.k > 1:
        # Each cell's first sample sits (½)/k of the way across it, its
        # last (k − ½)/k: the point's place in sample spacings from the
        # first, over the k − 1 between first and last.
        span = wp.float64(g.k - 1)
        along_x = wp.float64(data[first + wp.int64(g.k - 1)]) - a
        along_y = wp.float64(data[first + wp.int64((g.k - 1) * g.ncol)]) - a
        fx = ((ux - wp.float64(cx)) * wp.float64(g.k) - wp.float64(0.5)) / span
        fy = ((uy - wp.float64(cy)) * wp.float64(g.k) - wp.float64(0.5)) / span
        a = a + along_x * fx + along_y * fy
    return a


@wp.func
def two_cells(u: wp.float64, n: int, which: int) -> int:
    # The two cells a point at u (in cells) may touch along an axis: the
    # one before a line it is on (which 0) and the one after (1), on the
    # terrain.
    if which == 0:
        return wp.clamp(int(wp.ceil(u)) - 1, 0, n - 1)
    return wp.clamp(int(wp.floor(u)), 0, n - 1)


@wp.kernel(enable_backward=False)
def tops_under(
    data: wp.array(dtype=float),
    adr: wp.array(dtype=wp.int64),
    g: Grid,
    xy: wp.array3d(dtype=wp.float64),
    tops: wp.array2d(dtype=wp.float64),
):
    # Env e's top under its point p (its slot's frame, metres), metres: the
    # highest of the cells the point may touch (a point on a line between
    # cells reads the highest), 0 off its terrain. As
    # EnvTerrains.heights_at, in float64.
    e, p = wp.tid()
    ux = xy[e, p, 0] / g.block
    uy = xy[e, p, 1] / g.block
    if not (ux >= wp.float64(0.0) and ux <= wp.float64(g.nx) and uy >= wp.float64(0.0) and uy <= wp.float64(g.ny)):
        tops[e, p] = wp.float64(0.0)
        return
    top = wp.float64(-1.0e300)
    for i in range(2):
        cy = two_cells(uy, g.ny, i)
        for j in range(2):
            cx = two_cells(ux, g.nx, j)
            top = wp.max(top, cell_top(data, adr[e], g, cx, cy, ux, uy))
    tops[e, p] = top * g.elevation + g.z0


@wp.struct
class Square:
    """The square around a world's robot (``near.NearRobotBounds``): its
    root body and the root's first velocity dof, the reach, the horizon,
    the slack (metres, seconds, metres), the largest half side the gather
    covers (``cap``) and its cells a side (``span``), the prisms' depth
    below the field (``base``) and the slot's centre."""

    root: int
    dof: int
    reach: float
    horizon: float
    slack: float
    cap: float
    span: int
    base: float
    centre: wp.vec2


@wp.func
def highest_near(data: wp.array(dtype=float), start: wp.int64, g: Grid, s: Square, x: float, y: float, half: float) -> float:
    # The highest sample of the cells a square of half side `half` at
    # (x, y) touches, one more each side (a riser's slope), clamped onto
    # the terrain; no more than `span` a side. 0 at least. Every sample of
    # each cell, not its first alone: a ramp's cell rises within it, and
    # at a ramp's top edge its last sample stands above the next cell.
    block = float(g.block)
    x0 = int(wp.floor((x - half) / block)) - 1
    y0 = int(wp.floor((y - half) / block)) - 1
    x1 = wp.min(int(wp.floor((x + half) / block)) + 1, x0 + s.span - 1)
    y1 = wp.min(int(wp.floor((y + half) / block)) + 1, y0 + s.span - 1)
    # Clamping each cell onto the terrain keeps a run of cells a run: the
    # samples of [clamp(x0), clamp(x1)] × [clamp(y0), clamp(y1)].
    c0 = wp.clamp(x0, 0, g.nx - 1) * g.k
    c1 = (wp.clamp(x1, 0, g.nx - 1) + 1) * g.k
    r0 = wp.clamp(y0, 0, g.ny - 1) * g.k
    r1 = (wp.clamp(y1, 0, g.ny - 1) + 1) * g.k
    top = float(0.0)
    for r in range(r0, r1):
        row = start + wp.int64(r) * wp.int64(g.ncol)
        for c in range(c0, c1):
            top = wp.max(top, data[row + wp.int64(c)])
    return top


@wp.kernel(enable_backward=False)
def near_boxes(
    data: wp.array(dtype=float),
    adr: wp.array(dtype=wp.int64),
    g: Grid,
    s: Square,
    xpos: wp.array2d(dtype=wp.vec3),
    qvel: wp.array2d(dtype=float),
    offsets: wp.array(dtype=wp.vec2),
    gids: wp.array(dtype=int),
    aabb: wp.array3d(dtype=wp.vec3),
):
    # World w's terrain geoms bounded by the square its robot can reach
    # before the next update (its root's speed over the horizon, doubled),
    # up to the highest top in it; an env faster than the gather covers
    # (or whose state is not finite), up to the highest top a terrain may
    # have.
    w = wp.tid()
    at = xpos[w, s.root]
    x = at[0] - offsets[w][0]
    y = at[1] - offsets[w][1]
    speed = wp.length(wp.vec3(qvel[w, s.dof], qvel[w, s.dof + 1], qvel[w, s.dof + 2]))
    half = s.reach + 2.0 * s.horizon * speed + s.slack
    top = float(1.0)
    if half <= s.cap and wp.isfinite(x) and wp.isfinite(y):
        top = highest_near(data, adr[w], g, s, x, y, half)
    top = top * float(g.elevation)
    centre = wp.vec3(x - s.centre[0], y - s.centre[1], 0.5 * (top - s.base))
    size = wp.vec3(half, half, 0.5 * (top + s.base))
    for i in range(gids.shape[0]):
        aabb[w, gids[i], 0] = centre
        aabb[w, gids[i], 1] = size
