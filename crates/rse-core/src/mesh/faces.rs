//! The boundary of the solid `{0 ≤ z ≤ base + h·step}` as axis-aligned
//! rectangles and staircases on an integer lattice.
//!
//! A lattice point ([`LatticePoint`]) is `[x, y, level]`: `x`, `y` count cell corners
//! and `level` codes a height: 0 is the ground `z = 0`, and `h + 1` is the top
//! of a cell of `h` steps, `z = base + h·step` (with no slab, `h = 0` is the
//! ground itself and codes 0). Levels grow with `z`, so order and collinearity
//! along the lattice are those of space.

use crate::heightmap::Heightmap;

/// A lattice point `[x, y, level]`.
pub(crate) type LatticePoint = [u32; 3];

/// The outward normal of a face: axis-aligned, but for a ramp's plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Normal {
    /// +x
    PosX,
    /// −x
    NegX,
    /// +y
    PosY,
    /// −y
    NegY,
    /// +z (tops)
    PosZ,
    /// −z (the bottom)
    NegZ,
    /// A ramp's plane: the unit vector's `f32` bits (`Eq` by its bits, as
    /// writers compare it).
    Tilted([u32; 3]),
}

impl Normal {
    /// The six axis-aligned ones, in the order writers number them (a
    /// ramp's planes follow them, in the order of their faces).
    pub const ALL: [Normal; 6] = [
        Normal::PosX,
        Normal::NegX,
        Normal::PosY,
        Normal::NegY,
        Normal::PosZ,
        Normal::NegZ,
    ];

    /// The unit vector.
    pub fn vector(self) -> [f32; 3] {
        match self {
            Normal::PosX => [1.0, 0.0, 0.0],
            Normal::NegX => [-1.0, 0.0, 0.0],
            Normal::PosY => [0.0, 1.0, 0.0],
            Normal::NegY => [0.0, -1.0, 0.0],
            Normal::PosZ => [0.0, 0.0, 1.0],
            Normal::NegZ => [0.0, 0.0, -1.0],
            Normal::Tilted(bits) => bits.map(f32::from_bits),
        }
    }

    /// The unit vector along `v` (not zero), as a tilted normal.
    pub(crate) fn tilted(v: [f64; 3]) -> Normal {
        let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        Normal::Tilted(v.map(|c| ((c / length) as f32).to_bits()))
    }
}

/// A rectangle of the boundary: corners counter-clockwise seen from outside.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rect {
    pub corners: [LatticePoint; 4],
    pub normal: Normal,
}

/// A face of the boundary, as [`faces`] emits it.
pub(crate) enum Face<'a> {
    /// Tops, the bottom, and walls of one span.
    Rect(Rect),
    /// A polygon monotone along lattice axis `axes[0]` (`u`), spanning
    /// along `axes[1]` (`w`): the wall segments along one grid line that
    /// face the same way, each overlapping the next (`w` is z), or a piece
    /// of a top or of the bottom (u = y, w = x). `outline[..split]`: the
    /// corners of its low-`w` edge, `outline[split..]` those of its
    /// high-`w` edge, each by increasing `u`.
    Staircase {
        outline: &'a [LatticePoint],
        split: usize,
        normal: Normal,
        axes: [u8; 2],
    },
}

/// The level code of every cell's top (0: no solid there), with the grid size.
pub(crate) struct Levels {
    nx: u32,
    ny: u32,
    cells: Vec<u32>,
    has_base: bool,
}

impl Levels {
    pub(crate) fn new(map: &Heightmap, has_base: bool) -> Self {
        let cells = map
            .cells()
            .iter()
            .map(|&h| {
                if h == 0 && !has_base {
                    0
                } else {
                    u32::from(h) + 1
                }
            })
            .collect();
        Levels {
            nx: map.nx(),
            ny: map.ny(),
            cells,
            has_base,
        }
    }

    /// The height of `level` in steps, up to one offset for the whole mesh,
    /// where heights in steps are linear in `z` — which is what a wall's
    /// triangulation needs to tell left turns from right ones. Without a
    /// slab that is every level (the ground, 0, is the top of an empty
    /// cell); with one, only the tops are: the ground is `base`, not a
    /// whole number of steps, below the lowest top. `None` for the ground
    /// then.
    pub(crate) fn steps(&self, level: u32) -> Option<i64> {
        match level {
            0 if self.has_base => None,
            0 => Some(0),
            l => Some(i64::from(l) - 1),
        }
    }

    pub(crate) fn nx(&self) -> u32 {
        self.nx
    }

    pub(crate) fn ny(&self) -> u32 {
        self.ny
    }

    /// Every cell's level, row by row.
    pub(crate) fn cells(&self) -> &[u32] {
        &self.cells
    }

    /// The level of cell `(x, y)`, which is inside the grid.
    pub(crate) fn get(&self, x: u32, y: u32) -> u32 {
        self.cells[y as usize * self.nx as usize + x as usize]
    }

    /// The level of cell `(x, y)`, or 0 (nothing) outside the grid.
    pub(crate) fn at(&self, x: i64, y: i64) -> u32 {
        let inside = (0..i64::from(self.nx)).contains(&x) && (0..i64::from(self.ny)).contains(&y);
        if inside {
            self.get(x as u32, y as u32)
        } else {
            0
        }
    }

    /// The four cells around grid corner `(x, y)`: south-west, south-east,
    /// north-west, north-east.
    pub(crate) fn around(&self, x: u32, y: u32) -> [u32; 4] {
        let (x, y) = (i64::from(x), i64::from(y));
        [
            self.at(x - 1, y - 1),
            self.at(x, y - 1),
            self.at(x - 1, y),
            self.at(x, y),
        ]
    }
}

/// Every face of the boundary, `emit`ted in order: tops, the bottom, and
/// the walls. Streamed rather than collected: on a large random field a
/// list of them would be the biggest buffer of the whole build.
pub(crate) fn faces(levels: &Levels, emit: &mut dyn FnMut(Face)) {
    let (nx, ny) = (levels.nx, levels.ny);

    let mut buffers = RunBuffers::default();
    // Tops: cells of equal level; the bottom: every cell with solid, at
    // level 0, facing down. Each in pieces monotone along y, one run of
    // cells per row.
    let mut flat = |y0: u32, runs: &[[u32; 2]], level: u32, normal: Normal| {
        let [x0, x1] = runs[0];
        let y1 = y0 + runs.len() as u32;
        if runs.iter().all(|&r| r == runs[0]) {
            let [a, b, c, d] = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]].map(|[x, y]| [x, y, level]);
            // Counter-clockwise seen from outside: from above for a top.
            let corners = if normal == Normal::PosZ {
                [a, b, c, d]
            } else {
                [a, d, c, b]
            };
            emit(Face::Rect(Rect { corners, normal }));
        } else {
            let split = outline(y0, runs, |y, x| [x, y, level], &mut buffers.outline);
            emit(Face::Staircase {
                outline: &buffers.outline,
                split,
                normal,
                axes: [1, 0],
            });
        }
    };
    monotone_pieces(
        nx,
        ny,
        |x, y| Some(levels.get(x, y)).filter(|&l| l > 0),
        |y0, runs, l| {
            flat(y0, runs, l, Normal::PosZ);
        },
    );
    monotone_pieces(
        nx,
        ny,
        |x, y| (levels.get(x, y) > 0).then_some(0),
        |y0, runs, _| {
            flat(y0, runs, 0, Normal::NegZ);
        },
    );

    // Walls on the line x = i between cells (i−1, j) and (i, j); outside is
    // level 0. Emitted row by row like everything else, so that later
    // lookups walk memory in order instead of striding down columns: a run
    // is found when its first segment is reached, and the line skips the
    // rows it covers.
    let x_segment = |i: u32, j: u32| {
        let west = if i > 0 { levels.get(i - 1, j) } else { 0 };
        let east = if i < nx { levels.get(i, j) } else { 0 };
        wall_between(west, east)
    };
    let mut covered_until = vec![0u32; nx as usize + 1];
    for j in 0..ny {
        for i in 0..=nx {
            if j < covered_until[i as usize] || x_segment(i, j).is_none() {
                continue;
            }
            let line = WallLine {
                levels,
                segments: ny,
                wall: |j| x_segment(i, j),
                key: |j, level| [i, j, level],
                normals: [Normal::PosX, Normal::NegX],
                along_y: true,
            };
            covered_until[i as usize] = line.emit_run(j, &mut buffers, emit);
        }
    }

    // Walls on the line y = j between cells (i, j−1) and (i, j).
    for j in 0..=ny {
        let (south, north) = (i64::from(j) - 1, i64::from(j));
        let line = WallLine {
            levels,
            segments: nx,
            wall: |i: u32| wall_between(levels.at(i.into(), south), levels.at(i.into(), north)),
            key: |i, level| [i, j, level],
            normals: [Normal::PosY, Normal::NegY],
            along_y: false,
        };
        let mut i = 0;
        while i < nx {
            i = if (line.wall)(i).is_some() {
                line.emit_run(i, &mut buffers, emit)
            } else {
                i + 1
            };
        }
    }
}

/// One grid line of walls: `wall(k)` is the wall of segment `k` (if any),
/// `key(k, level)` the lattice point at the start of segment `k`.
struct WallLine<'a, W, K> {
    levels: &'a Levels,
    segments: u32,
    wall: W,
    key: K,
    /// The normals facing the positive and the negative side.
    normals: [Normal; 2],
    /// The line runs along y (a wall facing ±x).
    along_y: bool,
}

impl<W: Fn(u32) -> Option<Wall>, K: Fn(u32, u32) -> LatticePoint> WallLine<'_, W, K> {
    /// Emits the run of walls that starts at segment `start` (which has
    /// one) and returns the segment after it. A run is the segments facing
    /// the same way, each overlapping the one before: a rectangle when they
    /// all have the same span, else a staircase. Walls down to a ground that
    /// is no whole number of steps below the tops stay rectangles (see
    /// [`Levels::steps`]).
    fn emit_run(&self, start: u32, buffers: &mut RunBuffers, emit: &mut dyn FnMut(Face)) -> u32 {
        let first @ ([lo, hi], faces_positive) =
            (self.wall)(start).expect("a run starts at a wall");
        let staircase = self.levels.steps(lo).is_some();
        let (mut uniform, mut previous) = (true, [lo, hi]);
        // Read once: a line along y strides through the grid.
        let spans = &mut buffers.spans;
        spans.clear();
        spans.push([lo, hi]);
        let mut end = start + 1;
        while end < self.segments {
            let Some(this @ ([l, h], f)) = (self.wall)(end) else {
                break;
            };
            let joins = if uniform && this == first {
                true
            } else {
                let overlaps = l.max(previous[0]) < h.min(previous[1]);
                f == faces_positive && overlaps && staircase && self.levels.steps(l).is_some()
            };
            if !joins {
                break;
            }
            uniform &= this == first;
            previous = [l, h];
            spans.push(previous);
            end += 1;
        }
        if uniform {
            let [a, b, c, d] =
                [(start, lo), (start, hi), (end, hi), (end, lo)].map(|(k, l)| (self.key)(k, l));
            // Counter-clockwise seen from the positive side: along +y that
            // is a, d, c, b (y runs to the right), along +x a, b, c, d.
            let corners = if self.along_y {
                [a, d, c, b]
            } else {
                [a, b, c, d]
            };
            emit(Face::Rect(wall(corners, faces_positive, self.normals)));
            return end;
        }
        let split = outline(start, spans, &self.key, &mut buffers.outline);
        emit(Face::Staircase {
            outline: &buffers.outline,
            split,
            normal: self.normals[usize::from(!faces_positive)],
            axes: [u8::from(self.along_y), 2],
        });
        end
    }
}

/// The outline of a [`Face::Staircase`] whose `spans[k]` (`[low, high]` in
/// `w`) stands on `u = start + k .. start + k + 1`, into `outline`: the
/// corners of the low side, then of the high side, each by increasing `u`.
/// `key(u, w)` is the lattice point. Returns where the high side starts.
fn outline(
    start: u32,
    spans: &[[u32; 2]],
    key: impl Fn(u32, u32) -> LatticePoint,
    outline: &mut Vec<LatticePoint>,
) -> usize {
    outline.clear();
    let end = start + spans.len() as u32;
    let mut split = 0;
    for side in 0..2 {
        let mut previous = spans[0][side];
        outline.push(key(start, previous));
        for (u, span) in (start + 1..end).zip(&spans[1..]) {
            let this = span[side];
            if this != previous {
                outline.extend([key(u, previous), key(u, this)]);
                previous = this;
            }
        }
        outline.push(key(end, previous));
        if side == 0 {
            split = outline.len();
        }
    }
    split
}

/// Covers the cells where `value` is `Some` with pieces monotone along y:
/// each piece is one run of cells of equal value per row, over consecutive
/// rows, each run overlapping the one before. A run continues the first
/// piece it overlaps that has its value and no run in this row yet.
/// `emit(y0, runs, value)` with the runs `[x0, x1)` from row `y0` on, as
/// each piece closes: row by row, and along a row by x.
fn monotone_pieces(
    nx: u32,
    ny: u32,
    value: impl Fn(u32, u32) -> Option<u32>,
    mut emit: impl FnMut(u32, &[[u32; 2]], u32),
) {
    struct Piece {
        y0: u32,
        value: u32,
        runs: Vec<[u32; 2]>,
    }
    // The pieces with a run in the row before, by x; `None` once continued.
    let (mut open, mut next): (Vec<Option<Piece>>, Vec<Option<Piece>>) = (Vec::new(), Vec::new());
    let mut spare: Vec<Vec<[u32; 2]>> = Vec::new();
    let mut close = |piece: Option<Piece>, spare: &mut Vec<Vec<[u32; 2]>>| {
        if let Some(piece) = piece {
            emit(piece.y0, &piece.runs, piece.value);
            spare.push(piece.runs);
        }
    };
    for y in 0..=ny {
        let mut k = 0;
        let mut x = 0;
        while y < ny && x < nx {
            let Some(v) = value(x, y) else {
                x += 1;
                continue;
            };
            let mut x1 = x + 1;
            while x1 < nx && value(x1, y) == Some(v) {
                x1 += 1;
            }
            // Pieces ending left of this run can no longer continue.
            while k < open.len()
                && open[k]
                    .as_ref()
                    .is_none_or(|p| p.runs[p.runs.len() - 1][1] <= x)
            {
                close(open[k].take(), &mut spare);
                k += 1;
            }
            let continued = open[k..]
                .iter_mut()
                .take_while(|p| p.as_ref().is_none_or(|p| p.runs[p.runs.len() - 1][0] < x1))
                .find(|p| p.as_ref().is_some_and(|p| p.value == v))
                .and_then(Option::take);
            let mut piece = continued.unwrap_or_else(|| Piece {
                y0: y,
                value: v,
                runs: spare
                    .pop()
                    .map(|mut r| {
                        r.clear();
                        r
                    })
                    .unwrap_or_default(),
            });
            piece.runs.push([x, x1]);
            next.push(Some(piece));
            x = x1;
        }
        for piece in open.drain(..) {
            close(piece, &mut spare);
        }
        std::mem::swap(&mut open, &mut next);
    }
}

/// Buffers for [`WallLine::emit_run`], reused from one run to the next.
#[derive(Default)]
struct RunBuffers {
    /// The spans of the run's segments.
    spans: Vec<[u32; 2]>,
    /// The staircase's corners.
    outline: Vec<LatticePoint>,
}

/// A wall segment between two cells: its `[lo, hi]` span of levels and
/// whether it faces the positive axis.
type Wall = ([u32; 2], bool);

/// The wall between a cell `behind` and the cell `front` of it (levels), if
/// they differ. It faces the lower side: positive when `behind` is higher.
fn wall_between(behind: u32, front: u32) -> Option<Wall> {
    (behind != front).then(|| ([behind.min(front), behind.max(front)], behind > front))
}

/// A wall with `corners` counter-clockwise seen from the positive side: as
/// given when it faces that way (`normals[0]`), reversed when it faces the
/// other (`normals[1]`).
fn wall(corners: [LatticePoint; 4], faces_positive: bool, normals: [Normal; 2]) -> Rect {
    let [a, b, c, d] = corners;
    if faces_positive {
        Rect {
            corners,
            normal: normals[0],
        }
    } else {
        Rect {
            corners: [a, d, c, b],
            normal: normals[1],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::monotone_pieces;
    use proptest::prelude::*;

    proptest! {
        /// Every cell with a value is in exactly one piece, of its value;
        /// a piece's runs are in consecutive rows, each overlapping the one
        /// before.
        #[test]
        fn monotone_pieces_cover_each_cell_once(
            (nx, ny, cells) in (1u32..9, 1u32..9).prop_flat_map(|(nx, ny)| {
                (Just(nx), Just(ny), proptest::collection::vec(0u32..4, (nx * ny) as usize))
            })
        ) {
            let value = |x: u32, y: u32| Some(cells[(y * nx + x) as usize]).filter(|&v| v > 0);
            let mut covered = vec![0; cells.len()];
            monotone_pieces(nx, ny, value, |y0, runs, v| {
                for (k, &[x0, x1]) in runs.iter().enumerate() {
                    assert!(x0 < x1 && x1 <= nx);
                    if k > 0 {
                        let [p0, p1] = runs[k - 1];
                        assert!(x0.max(p0) < x1.min(p1), "runs overlap");
                    }
                    let y = y0 + k as u32;
                    for x in x0..x1 {
                        assert_eq!(value(x, y), Some(v));
                        covered[(y * nx + x) as usize] += 1;
                    }
                }
            });
            for (i, &c) in covered.iter().enumerate() {
                prop_assert_eq!(c, u32::from(cells[i] > 0), "cell {}", i);
            }
        }
    }
}
