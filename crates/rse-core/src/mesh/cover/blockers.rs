//! The cells too low for the level being covered, as a segment tree of
//! bitsets: how far a rectangle of allowed cells reaches in any direction,
//! in time that grows with its reach over 64 and the tree's depth, not with
//! its area.
//!
//! The tree runs along the grid's shorter axis and each node holds one bit
//! per cell along the longer: bit `b` of a node is set when some cell of its
//! span on the tree's axis, at `b` on the other, blocks. Bits only ever get
//! set (levels are covered lowest first, so a cell that blocks one level
//! blocks every higher one), and a node's bits are the union of its
//! children's, so an insertion stops at the first node that already has its
//! bit. About half a byte a cell.

/// Leaves read one by one before the tree is walked.
const NEAR: u32 = 8;

/// Blocking cells, asked about in grid terms (`x` along a row, `y` up).
pub(super) struct Blockers {
    /// The tree runs along `y` (rows) and the bits along `x`.
    transposed: bool,
    /// Leaves of the tree: its axis' length rounded up to a power of two.
    leaves: usize,
    /// Length of the bits' axis.
    bits_len: u32,
    /// Length of the tree's axis.
    tree_len: u32,
    /// Words a node.
    words: usize,
    /// Node `i` (1 is the root, leaves from `leaves`) at
    /// `[i * words, (i + 1) * words)`.
    bits: Vec<u64>,
}

impl Blockers {
    /// An empty set over an `nx` × `ny` grid.
    pub(super) fn new(nx: u32, ny: u32) -> Self {
        let transposed = ny < nx;
        let (tree_len, bits_len) = if transposed { (ny, nx) } else { (nx, ny) };
        let leaves = (tree_len as usize).next_power_of_two();
        let words = (bits_len as usize).div_ceil(64);
        Blockers {
            transposed,
            leaves,
            bits_len,
            tree_len,
            words,
            bits: vec![0; 2 * leaves * words],
        }
    }

    /// The bytes `new(nx, ny)` holds.
    pub(super) fn bytes(nx: u32, ny: u32) -> u64 {
        let (tree_len, bits_len) = if ny < nx { (ny, nx) } else { (nx, ny) };
        let leaves = u64::from(tree_len).next_power_of_two();
        2 * leaves * u64::from(bits_len).div_ceil(64) * 8
    }

    /// Marks cell `(x, y)` as blocking.
    pub(super) fn insert(&mut self, x: u32, y: u32) {
        let (a, b) = self.oriented(x, y);
        let (word, mask) = (b as usize / 64, 1u64 << (b % 64));
        let mut node = self.leaves + a as usize;
        loop {
            let slot = &mut self.bits[node * self.words + word];
            if *slot & mask != 0 {
                break;
            }
            *slot |= mask;
            if node == 1 {
                break;
            }
            node /= 2;
        }
    }

    /// The first column `x ≥ from` holding a blocking cell in rows
    /// `[y0, y1)`, or the grid's width.
    pub(super) fn next_x(&self, from: u32, y0: u32, y1: u32) -> u32 {
        if self.transposed {
            self.next_bit(y0, y1, from)
        } else {
            self.next_leaf(from, y0, y1)
        }
    }

    /// The last column `x < before` holding a blocking cell in rows
    /// `[y0, y1)`.
    pub(super) fn prev_x(&self, before: u32, y0: u32, y1: u32) -> Option<u32> {
        if self.transposed {
            self.prev_bit(y0, y1, before)
        } else {
            self.prev_leaf(before, y0, y1)
        }
    }

    /// The first row `y ≥ from` holding a blocking cell in columns
    /// `[x0, x1)`, or the grid's height.
    pub(super) fn next_y(&self, from: u32, x0: u32, x1: u32) -> u32 {
        if self.transposed {
            self.next_leaf(from, x0, x1)
        } else {
            self.next_bit(x0, x1, from)
        }
    }

    /// `(x, y)` as (tree axis, bits axis).
    fn oriented(&self, x: u32, y: u32) -> (u32, u32) {
        if self.transposed { (y, x) } else { (x, y) }
    }

    fn node(&self, node: usize) -> &[u64] {
        &self.bits[node * self.words..(node + 1) * self.words]
    }

    /// The first bit `≥ from` set in some leaf of `[a0, a1)`, or the bits'
    /// length.
    fn next_bit(&self, a0: u32, a1: u32, from: u32) -> u32 {
        let mut best = self.bits_len;
        for node in Span::new(self.leaves, a0, a1).in_order() {
            if let Some(b) = first_set(self.node(node), from, best) {
                best = b;
            }
        }
        best
    }

    /// The last bit `< before` set in some leaf of `[a0, a1)`.
    fn prev_bit(&self, a0: u32, a1: u32, before: u32) -> Option<u32> {
        let mut best: Option<u32> = None;
        for node in Span::new(self.leaves, a0, a1).in_order() {
            let floor = best.map_or(0, |b| b + 1);
            if let Some(b) = last_set(self.node(node), floor, before) {
                best = Some(b);
            }
        }
        best
    }

    /// The first leaf `≥ from` with a bit set in `[b0, b1)`, or the tree
    /// axis' length.
    fn next_leaf(&self, from: u32, b0: u32, b1: u32) -> u32 {
        let hit = |node: usize| first_set(self.node(node), b0, b1).is_some();
        // Most answers are a few leaves away: read those before the tree.
        let near = self.tree_len.min(from.saturating_add(NEAR));
        if let Some(a) = (from..near).find(|&a| hit(self.leaves + a as usize)) {
            return a;
        }
        Span::new(self.leaves, near, self.tree_len)
            .in_order()
            .find(|&node| hit(node))
            .map_or(self.tree_len, |node| self.descend(node, hit, true) as u32)
    }

    /// The last leaf `< before` with a bit set in `[b0, b1)`.
    fn prev_leaf(&self, before: u32, b0: u32, b1: u32) -> Option<u32> {
        let hit = |node: usize| first_set(self.node(node), b0, b1).is_some();
        let near = before.saturating_sub(NEAR);
        if let Some(a) = (near..before)
            .rev()
            .find(|&a| hit(self.leaves + a as usize))
        {
            return Some(a);
        }
        Span::new(self.leaves, 0, near)
            .in_order()
            .rev()
            .find(|&node| hit(node))
            .map(|node| self.descend(node, hit, false) as u32)
    }

    /// The leaf under `node` that `hit` leads to, the leftmost (`first`) or
    /// the rightmost; `node` is a hit.
    fn descend(&self, mut node: usize, hit: impl Fn(usize) -> bool, first: bool) -> usize {
        while node < self.leaves {
            let (near, far) = if first {
                (2 * node, 2 * node + 1)
            } else {
                (2 * node + 1, 2 * node)
            };
            node = if hit(near) { near } else { far };
        }
        node - self.leaves
    }
}

/// The nodes whose spans together are exactly `[lo, hi)`, at most two a
/// depth, for a tree of `leaves` leaves.
struct Span {
    /// From the left end inwards, in order (one a depth at most: a tree
    /// of `u32` leaves is 33 deep).
    left: [u32; 33],
    left_len: usize,
    /// From the right end inwards, in reverse order.
    right: [u32; 33],
    right_len: usize,
}

impl Span {
    fn new(leaves: usize, lo: u32, hi: u32) -> Self {
        let mut span = Span {
            left: [0; 33],
            left_len: 0,
            right: [0; 33],
            right_len: 0,
        };
        let (mut l, mut r) = (leaves + lo as usize, leaves + hi as usize);
        while l < r {
            if l & 1 == 1 {
                span.left[span.left_len] = l as u32;
                span.left_len += 1;
                l += 1;
            }
            if r & 1 == 1 {
                r -= 1;
                span.right[span.right_len] = r as u32;
                span.right_len += 1;
            }
            l /= 2;
            r /= 2;
        }
        span
    }

    /// The nodes left to right.
    fn in_order(&self) -> impl DoubleEndedIterator<Item = usize> + '_ {
        self.left[..self.left_len]
            .iter()
            .chain(self.right[..self.right_len].iter().rev())
            .map(|&node| node as usize)
    }
}

/// The first set bit in `[from, to)` of `words`.
fn first_set(words: &[u64], from: u32, to: u32) -> Option<u32> {
    if from >= to {
        return None;
    }
    let (mut w, last) = (from as usize / 64, (to as usize - 1) / 64);
    let mut word = words[w] & (u64::MAX << (from % 64));
    loop {
        if word != 0 {
            let b = (w * 64) as u32 + word.trailing_zeros();
            return (b < to).then_some(b);
        }
        w += 1;
        if w > last {
            return None;
        }
        word = words[w];
    }
}

/// The last set bit in `[from, to)` of `words`.
fn last_set(words: &[u64], from: u32, to: u32) -> Option<u32> {
    if from >= to {
        return None;
    }
    let (first, mut w) = (from as usize / 64, (to as usize - 1) / 64);
    let top = (to - 1) % 64;
    let mut word = words[w] & (u64::MAX >> (63 - top));
    loop {
        if word != 0 {
            let b = (w * 64) as u32 + 63 - word.leading_zeros();
            return (b >= from).then_some(b);
        }
        if w == first {
            return None;
        }
        w -= 1;
        word = words[w];
    }
}

#[cfg(test)]
mod tests {
    use super::Blockers;
    use proptest::prelude::*;

    proptest! {
        /// Every query agrees with a scan of the cells, either way round.
        #[test]
        fn queries_match_a_scan(
            (nx, ny, blocked) in (1u32..140, 1u32..140).prop_flat_map(|(nx, ny)| {
                (Just(nx), Just(ny), proptest::collection::vec(proptest::bool::weighted(0.03), (nx * ny) as usize))
            }),
            picks in proptest::collection::vec((0u32..140, 0u32..140, 0u32..140, 0u32..140), 20),
        ) {
            let mut tree = Blockers::new(nx, ny);
            for (i, &b) in blocked.iter().enumerate() {
                if b {
                    tree.insert(i as u32 % nx, i as u32 / nx);
                }
            }
            let at = |x: u32, y: u32| blocked[(y * nx + x) as usize];
            for (p, q, r, s) in picks {
                let (x0, x1) = { let (a, b) = (p % (nx + 1), q % (nx + 1)); (a.min(b), a.max(b)) };
                let (y0, y1) = { let (a, b) = (r % (ny + 1), s % (ny + 1)); (a.min(b), a.max(b)) };
                let column = |x: u32| (y0..y1).any(|y| at(x, y));
                let row = |y: u32| (x0..x1).any(|x| at(x, y));
                prop_assert_eq!(tree.next_x(x0, y0, y1), (x0..nx).find(|&x| column(x)).unwrap_or(nx));
                prop_assert_eq!(tree.prev_x(x1, y0, y1), (0..x1).rev().find(|&x| column(x)));
                prop_assert_eq!(tree.next_y(y0, x0, x1), (y0..ny).find(|&y| row(y)).unwrap_or(ny));
            }
        }
    }
}
