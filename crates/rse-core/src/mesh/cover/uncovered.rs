//! The cells of the level being covered that no rectangle holds yet, column
//! by column: which of them a rectangle would add, in time that grows with
//! how many it adds (and the tree's depth), not with its area.
//!
//! Starts are taken in row order, so when a rectangle is tried every cell
//! of its level below the start's row (and left of it in that row) is
//! covered already: the uncovered cells of a column inside a rectangle are
//! the column's lowest uncovered ones up to the rectangle's top, and
//! covering them moves the column's first uncovered cell up. A min-tree over
//! the columns' first uncovered rows finds the columns a rectangle adds
//! cells in without looking at the others.

/// The uncovered cells of one level.
pub(super) struct Uncovered<'a> {
    nx: u32,
    /// The level's cells (row-major indices), sorted by column, then row.
    by_column: &'a [u32],
    /// Per column present in `by_column`: the index there of its first
    /// uncovered cell, and one past its last cell.
    head: &'a mut [(u32, u32)],
    /// Per column, the row of its first uncovered cell (`u32::MAX`: none).
    lowest: &'a mut MinTree,
    /// The columns a rectangle adds cells in (kept to spare allocations).
    columns: Vec<u32>,
}

/// Counted cells of a rectangle: how many, and their bounding box
/// `[x0, y0, x1, y1]`.
pub(super) type NewCells = (usize, [u32; 4]);

impl<'a> Uncovered<'a> {
    /// Every cell of `by_column` uncovered; `head` holds a slot a column,
    /// `lowest` a leaf a column, all `u32::MAX` (as every level leaves it).
    pub(super) fn new(
        nx: u32,
        by_column: &'a [u32],
        head: &'a mut [(u32, u32)],
        lowest: &'a mut MinTree,
    ) -> Self {
        let mut previous = u32::MAX;
        for (i, &cell) in by_column.iter().enumerate() {
            let (x, y) = (cell % nx, cell / nx);
            if x != previous {
                head[x as usize].0 = i as u32;
                lowest.set(x, y);
                previous = x;
            }
            head[x as usize].1 = i as u32 + 1;
        }
        Uncovered {
            nx,
            by_column,
            head,
            lowest,
            columns: Vec::new(),
        }
    }

    /// How many uncovered cells `[x0, _, x1, y1]` holds (rows from the
    /// current start's up), and their bounding box.
    pub(super) fn count(&self, [x0, _, x1, y1]: [u32; 4]) -> NewCells {
        let mut count = 0;
        let mut bounds = [x1, y1, x0, 0];
        self.lowest.each_below(x0, x1, y1, |x, lowest| {
            let cells = self.run(x, y1);
            count += cells.len();
            let top = self.by_column[cells.end - 1] / self.nx;
            bounds = [
                bounds[0].min(x),
                bounds[1].min(lowest),
                bounds[2].max(x + 1),
                bounds[3].max(top + 1),
            ];
        });
        (count, bounds)
    }

    /// Covers what `count` counts in the same rectangle, telling `covered`
    /// each cell.
    pub(super) fn cover(&mut self, [x0, _, x1, y1]: [u32; 4], mut covered: impl FnMut(u32)) {
        let mut columns = std::mem::take(&mut self.columns);
        columns.clear();
        self.lowest.each_below(x0, x1, y1, |x, _| columns.push(x));
        for &x in &columns {
            let cells = self.run(x, y1);
            for &cell in &self.by_column[cells.clone()] {
                covered(cell);
            }
            let column = &mut self.head[x as usize];
            column.0 = cells.end as u32;
            let next = (cells.end < column.1 as usize).then(|| self.by_column[cells.end] / self.nx);
            self.lowest.set(x, next.unwrap_or(u32::MAX));
        }
        self.columns = columns;
    }

    /// Indices in `by_column` of column `x`'s uncovered cells below row
    /// `y1`.
    fn run(&self, x: u32, y1: u32) -> std::ops::Range<usize> {
        let (start, end) = self.head[x as usize];
        // A column's cells are `x + y·nx` by increasing `y`.
        let limit = u64::from(y1) * u64::from(self.nx) + u64::from(x);
        let len = self.by_column[start as usize..end as usize]
            .iter()
            .take_while(|&&c| u64::from(c) < limit)
            .count();
        start as usize..start as usize + len
    }
}

/// A segment tree of `u32` minima over `0..len`.
pub(super) struct MinTree {
    leaves: usize,
    min: Vec<u32>,
}

impl MinTree {
    /// Every value `u32::MAX`.
    pub(super) fn new(len: u32) -> Self {
        let leaves = (len as usize).next_power_of_two();
        MinTree {
            leaves,
            min: vec![u32::MAX; 2 * leaves],
        }
    }

    /// The bytes `new(len)` holds.
    pub(super) fn bytes(len: u32) -> u64 {
        2 * u64::from(len).next_power_of_two() * 4
    }

    fn set(&mut self, at: u32, value: u32) {
        let mut node = self.leaves + at as usize;
        self.min[node] = value;
        while node > 1 {
            node /= 2;
            self.min[node] = self.min[2 * node].min(self.min[2 * node + 1]);
        }
    }

    /// Calls `f(i, value)` for each `i` in `[lo, hi)` whose value is below
    /// `bound`, in increasing `i`.
    fn each_below(&self, lo: u32, hi: u32, bound: u32, mut f: impl FnMut(u32, u32)) {
        // A few leaves are read faster than a walk down from the root.
        if hi - lo <= 16 {
            for i in lo..hi {
                let value = self.min[self.leaves + i as usize];
                if value < bound {
                    f(i, value);
                }
            }
            return;
        }
        self.visit(1, 0, self.leaves, (lo as usize, hi as usize), bound, &mut f);
    }

    fn visit(
        &self,
        node: usize,
        start: usize,
        end: usize,
        range: (usize, usize),
        bound: u32,
        f: &mut impl FnMut(u32, u32),
    ) {
        if end <= range.0 || range.1 <= start || self.min[node] >= bound {
            return;
        }
        if node >= self.leaves {
            f((node - self.leaves) as u32, self.min[node]);
            return;
        }
        let middle = usize::midpoint(start, end);
        self.visit(2 * node, start, middle, range, bound, f);
        self.visit(2 * node + 1, middle, end, range, bound, f);
    }
}
