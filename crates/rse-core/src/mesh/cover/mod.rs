//! The rectangles of the block model: for each level, rectangles of cells
//! at least that high which together hold every cell of exactly that level.
//!
//! A box from the ground to level `l` is exact wherever every cell under it
//! is at least `l` high: the part over a higher cell is inside that cell's
//! own column. So boxes may overlap inside the solid and run under higher
//! neighbours, and a cover needs far fewer of them than a partition into
//! rectangles of equal height: a cell of level 1 beside a tower no longer
//! splits the rectangle around it. The union stays the solid exactly: over
//! each cell the highest box is that cell's own level.
//!
//! The rule is a greedy one (see [`level_cover`]); the work is kept near
//! the size of the grid by asking two indexes instead of walking areas: how
//! far a rectangle reaches ([`blockers`]) and which cells it would add
//! ([`uncovered`]). A cone, whose every level is a thin ring inside a wide
//! disk of allowed cells, once took time growing as its radius to the 3.5th
//! power (a 1000×1000 one: 155 s).

mod blockers;
pub(crate) mod reference;
mod uncovered;

use blockers::Blockers;
use uncovered::{MinTree, NewCells, Uncovered};

use super::faces::Levels;

/// What a cover emits: a rectangle `[x0, y0, x1, y1]` and its level.
pub(crate) type Emit<'a> = &'a mut dyn FnMut([u32; 4], u32);

/// A cover of a grid's levels (ours, or the reference it must match).
pub(crate) type Cover = fn(&Levels, Emit);

/// Emits `([x0, y0, x1, y1], level)` (`x1`, `y1` exclusive) such that every
/// cell in a rectangle is at least `level` high and every cell of level
/// `l > 0` lies in a rectangle of level `l`. Deterministic: levels in
/// increasing order, start cells in row-major order within a level.
///
/// For each start cell not yet covered, four rectangles holding it are
/// tried: the widest run of its row (rightwards, or both ways) raised as
/// far as it fits, and the tallest run of its column upwards widened as far
/// as it fits (rightwards, or both ways). The one adding the most uncovered
/// cells of the level wins, the earlier on ties, trimmed to the cells it
/// adds.
pub(crate) fn level_cover(levels: &Levels, emit: Emit) {
    let (nx, ny) = (levels.nx(), levels.ny());
    let by_level = CellsByLevel::new(levels);
    let mut blockers = Blockers::new(nx, ny);
    let mut covered = vec![false; levels.cells().len()];
    let mut head = vec![(0, 0); nx as usize];
    let mut lowest = MinTree::new(nx);
    let mut blocking = 0; // levels below this one are in `blockers`
    for level in 1..by_level.levels() {
        let (in_rows, in_columns) = by_level.level(level);
        if in_rows.is_empty() {
            continue;
        }
        for low in blocking..level {
            for &cell in by_level.level(low).0 {
                blockers.insert(cell % nx, cell / nx);
            }
        }
        blocking = level;
        let mut uncovered = Uncovered::new(nx, in_columns, &mut head, &mut lowest);
        for &start in in_rows {
            if covered[start as usize] {
                continue;
            }
            let (x, y) = (start % nx, start / nx);
            let best = [
                row_first(&blockers, x, y, false),
                row_first(&blockers, x, y, true),
                column_first(&blockers, x, y, false),
                column_first(&blockers, x, y, true),
            ]
            .into_iter()
            .map(|rect| (rect, uncovered.count(rect)))
            .reduce(|best, next| if next.1.0 > best.1.0 { next } else { best })
            .expect("four candidates");
            let (rect, (_, trimmed)): ([u32; 4], NewCells) = best;
            // Trimmed to the cells it adds: the same cover with smaller
            // boxes, so fewer overlap a robot's bounding box for nothing.
            uncovered.cover(rect, |cell| covered[cell as usize] = true);
            emit(trimmed, level);
        }
    }
}

/// The bytes `level_cover` holds over an `nx` × `ny` grid: its indexes and
/// the levels.
pub(crate) fn level_cover_bytes(nx: u32, ny: u32) -> u64 {
    let cells = u64::from(nx) * u64::from(ny);
    // The levels, two orders of the cells, the covered flags; a column's
    // ends.
    cells * (4 + 4 + 4 + 1) + u64::from(nx) * 8 + Blockers::bytes(nx, ny) + MinTree::bytes(nx)
}

/// The widest run of allowed cells in row `y` from `x` (rightwards, or
/// both ways), then as many rows upwards as the run fits in.
fn row_first(blockers: &Blockers, x: u32, y: u32, both_ways: bool) -> [u32; 4] {
    let x1 = blockers.next_x(x + 1, y, y + 1);
    let x0 = if both_ways {
        blockers.prev_x(x, y, y + 1).map_or(0, |b| b + 1)
    } else {
        x
    };
    let y1 = blockers.next_y(y + 1, x0, x1);
    [x0, y, x1, y1]
}

/// The tallest run of allowed cells in column `x` upwards from `y`, then
/// as many columns (rightwards, or both ways) as it fits in.
fn column_first(blockers: &Blockers, x: u32, y: u32, both_ways: bool) -> [u32; 4] {
    let y1 = blockers.next_y(y + 1, x, x + 1);
    let x1 = blockers.next_x(x + 1, y, y1);
    let x0 = if both_ways {
        blockers.prev_x(x, y, y1).map_or(0, |b| b + 1)
    } else {
        x
    };
    [x0, y, x1, y1]
}

/// The cells (row-major indices) grouped by level, in two orders: row by
/// row, and column by column. A counting sort: linear in the cells.
struct CellsByLevel {
    /// Level `l` at `[starts[l], starts[l + 1])` of both orders.
    starts: Vec<usize>,
    in_rows: Vec<u32>,
    in_columns: Vec<u32>,
}

impl CellsByLevel {
    fn new(levels: &Levels) -> Self {
        let cells = levels.cells();
        let top = cells.iter().copied().max().unwrap_or(0) as usize;
        let mut starts = vec![0usize; top + 2];
        for &level in cells {
            starts[level as usize + 1] += 1;
        }
        for l in 1..starts.len() {
            starts[l] += starts[l - 1];
        }
        let place = |order: &mut dyn Iterator<Item = u32>| {
            let mut next = starts.clone();
            let mut out = vec![0u32; cells.len()];
            for cell in order {
                let slot = &mut next[cells[cell as usize] as usize];
                out[*slot] = cell;
                *slot += 1;
            }
            out
        };
        let (nx, ny) = (levels.nx(), levels.ny());
        let in_rows = place(&mut (0..nx * ny));
        let in_columns = place(&mut (0..nx).flat_map(|x| (0..ny).map(move |y| y * nx + x)));
        CellsByLevel {
            starts,
            in_rows,
            in_columns,
        }
    }

    /// One past the highest level.
    fn levels(&self) -> u32 {
        (self.starts.len() - 1) as u32
    }

    /// Level `l`'s cells row by row and column by column.
    fn level(&self, l: u32) -> (&[u32], &[u32]) {
        let range = self.starts[l as usize]..self.starts[l as usize + 1];
        (&self.in_rows[range.clone()], &self.in_columns[range])
    }
}

#[cfg(test)]
mod tests {
    use super::level_cover;
    use super::reference::level_cover as reference_cover;
    use crate::heightmap::Heightmap;
    use crate::mesh::faces::Levels;
    use proptest::prelude::*;

    type Rectangles = Vec<([u32; 4], u32)>;

    fn both(levels: &Levels) -> (Rectangles, Rectangles) {
        let (mut ours, mut reference) = (Vec::new(), Vec::new());
        level_cover(levels, &mut |r, l| ours.push((r, l)));
        reference_cover(levels, &mut |r, l| reference.push((r, l)));
        (ours, reference)
    }

    proptest! {
        /// The union of the rectangles, each raised to its level, is the
        /// heightmap: no rectangle over a lower cell, and over every cell
        /// one of its own level.
        #[test]
        fn cover_is_exact(
            (nx, ny, cells, base) in (1u32..10, 1u32..10).prop_flat_map(|(nx, ny)| {
                (
                    Just(nx),
                    Just(ny),
                    proptest::collection::vec(0u16..5, (nx * ny) as usize),
                    any::<bool>(),
                )
            })
        ) {
            let map = Heightmap::from_cells(nx, ny, cells).unwrap();
            let levels = Levels::new(&map, base);
            let mut top = vec![0u32; (nx * ny) as usize];
            let mut count = 0;
            level_cover(&levels, &mut |[x0, y0, x1, y1], level| {
                count += 1;
                assert!(x0 < x1 && y0 < y1 && x1 <= nx && y1 <= ny);
                for y in y0..y1 {
                    for x in x0..x1 {
                        assert!(levels.get(x, y) >= level, "box over a lower cell");
                        let i = (y * nx + x) as usize;
                        top[i] = top[i].max(level);
                    }
                }
            });
            for y in 0..ny {
                for x in 0..nx {
                    prop_assert_eq!(top[(y * nx + x) as usize], levels.get(x, y));
                }
            }
            prop_assert!(count <= (nx * ny) as usize);
        }

        /// The same rectangles, in the same order, as the plain greedy
        /// search that walks areas: the world files' bytes do not change.
        #[test]
        fn same_rectangles_as_the_area_walk(
            (nx, ny, cells, base) in (1u32..70, 1u32..70).prop_flat_map(|(nx, ny)| {
                (
                    Just(nx),
                    Just(ny),
                    proptest::collection::vec(prop_oneof![0u16..3, 0u16..40], (nx * ny) as usize),
                    any::<bool>(),
                )
            })
        ) {
            let map = Heightmap::from_cells(nx, ny, cells).unwrap();
            let (ours, reference) = both(&Levels::new(&map, base));
            prop_assert_eq!(ours, reference);
        }
    }

    /// Cones, pyramids, terraces and walls: the shapes whose levels are
    /// thin and whose candidates are wide.
    #[test]
    fn same_rectangles_on_cones_and_slopes() {
        type Shape = (u32, u32, fn(i64, i64) -> i64);
        let shapes: [Shape; 5] = [
            (60, 60, |x, y| {
                30 - ((x - 30).pow(2) + (y - 30).pow(2)).isqrt()
            }),
            (61, 37, |x, y| 20 - (x - 30).abs().max((y - 18).abs())),
            (50, 70, |x, y| x + y),
            (
                80,
                9,
                |x, y| if x == 40 { 600 } else { (x * 7 + y * 3) % 5 },
            ),
            (45, 45, |x, y| ((x / 3) ^ (y / 5)) % 7),
        ];
        for (nx, ny, height) in shapes {
            let cells = (0..ny)
                .flat_map(|y| {
                    (0..nx).map(move |x| height(i64::from(x), i64::from(y)).max(0) as u16)
                })
                .collect();
            let map = Heightmap::from_cells(nx, ny, cells).unwrap();
            for base in [false, true] {
                let (ours, reference) = both(&Levels::new(&map, base));
                assert_eq!(ours, reference, "{nx}x{ny} base {base}");
            }
        }
    }
}
