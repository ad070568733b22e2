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

use super::faces::Levels;

/// Emits `([x0, y0, x1, y1], level)` (`x1`, `y1` exclusive) such that every
/// cell in a rectangle is at least `level` high and every cell of level
/// `l > 0` lies in a rectangle of level `l`. Deterministic: levels in
/// increasing order, start cells in row-major order within a level.
pub(crate) fn level_cover(levels: &Levels, mut emit: impl FnMut([u32; 4], u32)) {
    let (nx, ny) = (levels.nx(), levels.ny());
    let width = nx as usize;
    let mut starts: Vec<(u32, u32)> = (0..ny)
        .flat_map(|y| (0..nx).map(move |x| (x, y)))
        .map(|(x, y)| (levels.get(x, y), y * nx + x))
        .filter(|&(level, _)| level > 0)
        .collect();
    starts.sort_unstable();
    let mut covered = vec![false; width * ny as usize];
    for (level, start) in starts {
        if covered[start as usize] {
            continue;
        }
        let region = Region {
            levels,
            level,
            covered: &covered,
        };
        let (x, y) = (start % nx, start / nx);
        // Each candidate holds the start cell; the one covering the most
        // cells still uncovered wins, earlier candidates on ties.
        let best = [
            region.row_first(x, y, false),
            region.row_first(x, y, true),
            region.column_first(x, y, false),
            region.column_first(x, y, true),
        ]
        .into_iter()
        .map(|rect| region.new_cells(rect))
        .reduce(|best, next| if next.0 > best.0 { next } else { best })
        .expect("four candidates");
        // Trimmed to the cells it adds: the same cover with smaller boxes,
        // so fewer overlap a robot's bounding box for nothing.
        let [x0, y0, x1, y1] = best.1;
        for yy in y0..y1 {
            for xx in x0..x1 {
                if levels.get(xx, yy) == level {
                    covered[yy as usize * width + xx as usize] = true;
                }
            }
        }
        emit(best.1, level);
    }
}

/// The cells a rectangle of one level may hold, and which of its cells are
/// already covered.
struct Region<'a> {
    levels: &'a Levels,
    level: u32,
    covered: &'a [bool],
}

impl Region<'_> {
    fn allows(&self, x: u32, y: u32) -> bool {
        self.levels.get(x, y) >= self.level
    }

    /// The widest run of allowed cells in row `y` from `x` (rightwards, or
    /// both ways), then as many rows upwards as the run fits in.
    fn row_first(&self, x: u32, y: u32, both_ways: bool) -> [u32; 4] {
        let (x0, x1) = run(x, both_ways, self.levels.nx(), |xx| self.allows(xx, y));
        let (_, y1) = run(y, false, self.levels.ny(), |yy| {
            (x0..x1).all(|xx| self.allows(xx, yy))
        });
        [x0, y, x1, y1]
    }

    /// The tallest run of allowed cells in column `x` upwards from `y`,
    /// then as many columns (rightwards, or both ways) as it fits in.
    fn column_first(&self, x: u32, y: u32, both_ways: bool) -> [u32; 4] {
        let (_, y1) = run(y, false, self.levels.ny(), |yy| self.allows(x, yy));
        let (x0, x1) = run(x, both_ways, self.levels.nx(), |xx| {
            (y..y1).all(|yy| self.allows(xx, yy))
        });
        [x0, y, x1, y1]
    }

    /// How many cells of this level in `rect` are still uncovered, and
    /// `rect` trimmed to their bounding box.
    fn new_cells(&self, [x0, y0, x1, y1]: [u32; 4]) -> (usize, [u32; 4]) {
        let nx = self.levels.nx() as usize;
        let mut count = 0;
        let mut bounds = [x1, y1, x0, y0];
        for y in y0..y1 {
            for x in x0..x1 {
                if self.levels.get(x, y) == self.level
                    && !self.covered[y as usize * nx + x as usize]
                {
                    count += 1;
                    bounds = [
                        bounds[0].min(x),
                        bounds[1].min(y),
                        bounds[2].max(x + 1),
                        bounds[3].max(y + 1),
                    ];
                }
            }
        }
        (count, bounds)
    }
}

/// `[start, end)` around `at` (which `ok` is known to accept) as far as
/// `ok` holds, below `limit`; leftwards too when `both_ways`.
fn run(at: u32, both_ways: bool, limit: u32, ok: impl Fn(u32) -> bool) -> (u32, u32) {
    let mut start = at;
    while both_ways && start > 0 && ok(start - 1) {
        start -= 1;
    }
    let mut end = at + 1;
    while end < limit && ok(end) {
        end += 1;
    }
    (start, end)
}

#[cfg(test)]
mod tests {
    use super::level_cover;
    use crate::heightmap::Heightmap;
    use crate::mesh::faces::Levels;
    use proptest::prelude::*;

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
            level_cover(&levels, |[x0, y0, x1, y1], level| {
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
    }
}
