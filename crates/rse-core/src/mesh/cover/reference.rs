//! The greedy cover as first written, walking every cell of every
//! rectangle it tries: the reference the indexed search must match
//! rectangle for rectangle (the world files' bytes depend on them), and the
//! baseline `bench/` measures it against.

use crate::mesh::faces::Levels;

/// Emits `([x0, y0, x1, y1], level)` (`x1`, `y1` exclusive) such that every
/// cell in a rectangle is at least `level` high and every cell of level
/// `l > 0` lies in a rectangle of level `l`. Deterministic: levels in
/// increasing order, start cells in row-major order within a level.
pub(crate) fn level_cover(levels: &Levels, emit: super::Emit) {
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
