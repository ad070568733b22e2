//! The boundary of the solid `{0 ≤ z ≤ base + h·step}` as axis-aligned
//! rectangles on an integer lattice.
//!
//! A lattice point ([`Key`]) is `[x, y, level]`: `x`, `y` count cell corners
//! and `level` codes a height: 0 is the ground `z = 0`, and `h + 1` is the top
//! of a cell of `h` steps, `z = base + h·step` (with no slab, `h = 0` is the
//! ground itself and codes 0). Levels grow with `z`, so order and collinearity
//! along the lattice are those of space.

use crate::heightmap::Heightmap;

/// A lattice point `[x, y, level]`.
pub(crate) type Key = [u32; 3];

/// The outward normal of a face; all faces are axis-aligned.
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
}

impl Normal {
    /// All six, in the order writers number them.
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
        }
    }
}

/// A rectangle of the boundary: corners counter-clockwise seen from outside.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rect {
    pub corners: [Key; 4],
    pub normal: Normal,
}

/// A face of the boundary, as [`faces`] emits it.
pub(crate) enum Face<'a> {
    /// Tops, the bottom, and walls of one span.
    Rect(Rect),
    /// The wall segments along one grid line that face the same way, each
    /// overlapping the next, as one polygon. `outline[..split]`: the
    /// corners of its lower edge, `outline[split..]` those of its upper
    /// edge, each in order along the line from the same end.
    Staircase {
        outline: &'a [Key],
        split: usize,
        normal: Normal,
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

    /// Cells of equal level with solid on them, merged into rectangles:
    /// `emit([x0, y0, x1, y1], level)`. The tops of the mesh, and the boxes
    /// of the block model.
    pub(crate) fn top_rectangles(&self, emit: impl FnMut([u32; 4], u32)) {
        greedy_rectangles(
            self.nx,
            self.ny,
            |x, y| Some(self.get(x, y)).filter(|&l| l > 0),
            emit,
        );
    }
}

/// Every face of the boundary, `emit`ted in order: tops, the bottom, and
/// the walls. Streamed rather than collected: on a large random field a
/// list of them would be the biggest buffer of the whole build.
pub(crate) fn faces(levels: &Levels, emit: &mut dyn FnMut(Face)) {
    let (nx, ny) = (levels.nx, levels.ny);

    // Tops: cells of equal level merged into rectangles.
    levels.top_rectangles(|[x0, y0, x1, y1], l| {
        emit(Face::Rect(Rect {
            corners: [[x0, y0, l], [x1, y0, l], [x1, y1, l], [x0, y1, l]],
            normal: Normal::PosZ,
        }));
    });
    // The bottom: every cell with solid, at level 0, facing down.
    greedy_rectangles(
        nx,
        ny,
        |x, y| (levels.get(x, y) > 0).then_some(0),
        |[x0, y0, x1, y1], _| {
            emit(Face::Rect(Rect {
                corners: [[x0, y0, 0], [x0, y1, 0], [x1, y1, 0], [x1, y0, 0]],
                normal: Normal::NegZ,
            }));
        },
    );

    let mut buffers = RunBuffers::default();
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

impl<W: Fn(u32) -> Option<Wall>, K: Fn(u32, u32) -> Key> WallLine<'_, W, K> {
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
        // The corners of the lower edge, then of the upper one.
        let outline = &mut buffers.outline;
        outline.clear();
        let mut split = 0;
        for side in 0..2 {
            let mut previous = spans[0][side];
            outline.push((self.key)(start, previous));
            for (k, span) in (start + 1..end).zip(&spans[1..]) {
                let this = span[side];
                if this != previous {
                    outline.extend([(self.key)(k, previous), (self.key)(k, this)]);
                    previous = this;
                }
            }
            outline.push((self.key)(end, previous));
            if side == 0 {
                split = outline.len();
            }
        }
        emit(Face::Staircase {
            outline,
            split,
            normal: self.normals[usize::from(!faces_positive)],
        });
        end
    }
}

/// Buffers for [`WallLine::emit_run`], reused from one run to the next.
#[derive(Default)]
struct RunBuffers {
    /// The spans of the run's segments.
    spans: Vec<[u32; 2]>,
    /// The staircase's corners.
    outline: Vec<Key>,
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
fn wall(corners: [Key; 4], faces_positive: bool, normals: [Normal; 2]) -> Rect {
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

/// Greedy meshing: covers the cells where `value` is `Some` with rectangles
/// of equal value, each grown along x first, then along y.
/// `emit([x0, y0, x1, y1], value)` with `x1`, `y1` exclusive.
fn greedy_rectangles(
    nx: u32,
    ny: u32,
    value: impl Fn(u32, u32) -> Option<u32>,
    mut emit: impl FnMut([u32; 4], u32),
) {
    let width = nx as usize;
    let mut used = vec![false; width * ny as usize];
    for y in 0..ny {
        let mut x = 0;
        while x < nx {
            let start = y as usize * width + x as usize;
            let Some(v) = value(x, y).filter(|_| !used[start]) else {
                x += 1;
                continue;
            };
            let free = |x: u32, y: u32, used: &[bool]| {
                !used[y as usize * width + x as usize] && value(x, y) == Some(v)
            };
            let mut x1 = x + 1;
            while x1 < nx && free(x1, y, &used) {
                x1 += 1;
            }
            let mut y1 = y + 1;
            while y1 < ny && (x..x1).all(|xx| free(xx, y1, &used)) {
                y1 += 1;
            }
            for yy in y..y1 {
                let row = yy as usize * width;
                used[row + x as usize..row + x1 as usize].fill(true);
            }
            emit([x, y, x1, y1], v);
            x = x1;
        }
    }
}
