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

/// The level code of every cell's top (0: no solid there), with the grid size.
pub(crate) struct Levels {
    nx: u32,
    ny: u32,
    cells: Vec<u32>,
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

/// Every rectangle of the boundary, `emit`ted in order: tops, the bottom,
/// and the walls. Streamed rather than collected: on a large random field
/// a list of them would be the biggest buffer of the whole build.
pub(crate) fn rectangles(levels: &Levels, emit: &mut dyn FnMut(Rect)) {
    let (nx, ny) = (levels.nx, levels.ny);

    // Tops: cells of equal level merged into rectangles.
    levels.top_rectangles(|[x0, y0, x1, y1], l| {
        emit(Rect {
            corners: [[x0, y0, l], [x1, y0, l], [x1, y1, l], [x0, y1, l]],
            normal: Normal::PosZ,
        });
    });
    // The bottom: every cell with solid, at level 0, facing down.
    greedy_rectangles(
        nx,
        ny,
        |x, y| (levels.get(x, y) > 0).then_some(0),
        |[x0, y0, x1, y1], _| {
            emit(Rect {
                corners: [[x0, y0, 0], [x0, y1, 0], [x1, y1, 0], [x1, y0, 0]],
                normal: Normal::NegZ,
            });
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
            if j < covered_until[i as usize] {
                continue;
            }
            let Some(this) = x_segment(i, j) else {
                continue;
            };
            let mut j1 = j + 1;
            while j1 < ny && x_segment(i, j1) == Some(this) {
                j1 += 1;
            }
            covered_until[i as usize] = j1;
            emit(x_wall(i, [j, j1], this));
        }
    }

    // Walls on the line y = j between cells (i, j−1) and (i, j).
    for j in 0..=ny {
        let (south, north) = (i64::from(j) - 1, i64::from(j));
        let side = |i: u32| (levels.at(i.into(), south), levels.at(i.into(), north));
        wall_runs(nx, side, |[i0, i1], [lo, hi], faces_positive| {
            let corners = [[i0, j, lo], [i0, j, hi], [i1, j, hi], [i1, j, lo]];
            emit(wall(corners, faces_positive, [Normal::PosY, Normal::NegY]));
        });
    }
}

/// A wall segment between two cells: its `[lo, hi]` span of levels and
/// whether it faces the positive axis.
type Wall = ([u32; 2], bool);

/// The wall between a cell `behind` and the cell `front` of it (levels), if
/// they differ. It faces the lower side: positive when `behind` is higher.
fn wall_between(behind: u32, front: u32) -> Option<Wall> {
    (behind != front).then(|| ([behind.min(front), behind.max(front)], behind > front))
}

/// The wall on the line x = `i` over rows `j0..j1`.
fn x_wall(i: u32, [j0, j1]: [u32; 2], ([lo, hi], faces_positive): Wall) -> Rect {
    let corners = [[i, j0, lo], [i, j1, lo], [i, j1, hi], [i, j0, hi]];
    wall(corners, faces_positive, [Normal::PosX, Normal::NegX])
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

/// Along one grid line, the walls between the cells on its two sides
/// (`side(k)` gives the levels behind and in front of segment `k`): runs of
/// segments with the same span and facing become one rectangle.
/// `emit([k0, k1], [lo, hi], faces_positive)`.
fn wall_runs(
    segments: u32,
    side: impl Fn(u32) -> (u32, u32),
    mut emit: impl FnMut([u32; 2], [u32; 2], bool),
) {
    let wall = |k: u32| {
        let (behind, front) = side(k);
        wall_between(behind, front)
    };
    let mut k = 0;
    while k < segments {
        let Some(this) = wall(k) else {
            k += 1;
            continue;
        };
        let mut end = k + 1;
        while end < segments && wall(end) == Some(this) {
            end += 1;
        }
        emit([k, end], this.0, this.1);
        k = end;
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
