//! Triangulating a staircase: a polygon monotone along one lattice axis,
//! keeping every point on its boundary and adding none. Walls (the wall
//! segments along one grid line that face the same way and overlap) and
//! the pieces of tops and of the bottom (one run of cells per row) are
//! staircases.
//!
//! Cutting such a polygon into rectangles puts points on its straight
//! edges where the rectangles meet, which the neighbouring faces must then
//! share; as one polygon its edges have only the points other faces put
//! there. The classic sweep with a stack of reflex vertices (de Berg et al.,
//! *Computational Geometry*, §3.3) triangulates it in linear time. Ties in
//! the sweep direction need care: the sides and steps are swept in boundary
//! order, and where both chains have points on one line across the sweep
//! and one of them steps there, the polygon is first cut along that line
//! (between the low chain's highest and the high chain's lowest point
//! there, always inside), so that no triangle has three points on one line.

/// A point of the polygon in its own plane: `u` along the sweep, `w` across.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Point {
    pub id: u32,
    pub u: i64,
    pub w: i64,
}

/// Reusable buffers, so that a mesh of millions of faces allocates once.
#[derive(Default)]
pub(crate) struct Scratch {
    piece: Vec<Point>,
    stack: Vec<(Point, Chain)>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Chain {
    Bottom,
    Top,
}

/// Triangulates the polygon whose boundary is `bottom` and `top`, both
/// from its first end (lowest `u`) to its last, sharing their first and
/// last points: the bottom along its low-`w` edge, the top up its first
/// side, along its high-`w` edge and down its last side (in a wall, `w` is
/// up). `u` never decreases along either, and the top is above the bottom
/// everywhere between the ends. Appends triangles counter-clockwise in
/// `(u, w)`: as many as points minus two.
pub(crate) fn triangulate(
    bottom: &[Point],
    top: &[Point],
    scratch: &mut Scratch,
    out: &mut Vec<[u32; 3]>,
) {
    debug_assert!(bottom.len() >= 2 && top.len() >= 3);
    debug_assert!(bottom[0] == top[0] && bottom[bottom.len() - 1] == top[top.len() - 1]);
    // Cut where both chains have points on one line across the sweep (a
    // vertical one in a wall) and one of them steps there: between the
    // bottom's highest and the top's lowest point on that line.
    let (mut from_bottom, mut from_top) = (0, 0);
    let (mut b, mut t) = (1, 1);
    while b < bottom.len() - 1 {
        let u = bottom[b].u;
        let b_end = b + bottom[b..].iter().take_while(|p| p.u == u).count();
        while top[t].u < u {
            t += 1;
        }
        let t_end = t + top[t..].iter().take_while(|p| p.u == u).count();
        let b_end = b_end.min(bottom.len() - 1);
        if t_end > t && (b_end - b > 1 || t_end - t > 1) {
            let low = (b..b_end)
                .max_by_key(|&i| bottom[i].w)
                .expect("points here");
            let high = (t..t_end).min_by_key(|&i| top[i].w).expect("points here");
            piece(
                &bottom[from_bottom..=low],
                &top[from_top..=high],
                scratch,
                out,
            );
            (from_bottom, from_top) = (low, high);
        }
        b = b_end;
    }
    piece(&bottom[from_bottom..], &top[from_top..], scratch, out);
}

/// One piece, whose ends are joined by the cuts: `top` is closed by the
/// cut from the bottom's first point to its own first point, and from its
/// last to the bottom's last, where those differ. A cut through a step of
/// the bottom leaves the bottom with a vertical stretch at that end; the
/// sweep wants each end's whole vertical side in the top chain, from its
/// lowest point, so such a stretch moves over.
fn piece(bottom: &[Point], top: &[Point], scratch: &mut Scratch, out: &mut Vec<[u32; 3]>) {
    let n = bottom.len();
    let (first_u, last_u) = (bottom[0].u, bottom[n - 1].u);
    let lead = bottom.iter().take_while(|p| p.u == first_u).count() - 1;
    let tail = bottom.iter().rev().take_while(|p| p.u == last_u).count() - 1;
    let closed = top[0] == bottom[0] && top[top.len() - 1] == bottom[n - 1];
    if lead == 0 && tail == 0 && closed {
        // The whole polygon, uncut: the usual case.
        sweep(bottom, top, &mut scratch.stack, out);
        return;
    }
    let chain = &mut scratch.piece;
    chain.clear();
    chain.extend(bottom[..=lead].iter().rev());
    if top[0] == bottom[0] {
        chain.extend_from_slice(&top[1..]);
    } else {
        chain.extend_from_slice(top);
    }
    if top[top.len() - 1] != bottom[n - 1] {
        chain.push(bottom[n - 1]);
    }
    chain.extend(bottom[n - 1 - tail..n - 1].iter().rev());
    sweep(
        &bottom[lead..n - tail],
        &scratch.piece,
        &mut scratch.stack,
        out,
    );
}

/// Twice the signed area of `(p, q, r)`: positive counter-clockwise.
fn orient(p: Point, q: Point, r: Point) -> i64 {
    (q.u - p.u) * (r.w - p.w) - (q.w - p.w) * (r.u - p.u)
}

/// Appends the triangle `(p, q, r)` turned counter-clockwise.
fn push_ccw(p: Point, q: Point, r: Point, out: &mut Vec<[u32; 3]>) {
    let area = orient(p, q, r);
    debug_assert!(area != 0, "zero-area triangle {p:?} {q:?} {r:?}");
    out.push(if area > 0 {
        [p.id, q.id, r.id]
    } else {
        [p.id, r.id, q.id]
    });
}

/// The monotone sweep over one piece, with no vertical line that has
/// points of both chains and a step.
fn sweep(
    bottom: &[Point],
    top: &[Point],
    stack: &mut Vec<(Point, Chain)>,
    out: &mut Vec<[u32; 3]>,
) {
    // Interior points of both chains by `u`, each chain in boundary order;
    // on a tie (one point of each chain, no step) the bottom's first.
    let (inner_bottom, inner_top) = (&bottom[1..bottom.len() - 1], &top[1..top.len() - 1]);
    let (mut i, mut j) = (0, 0);
    let order = std::iter::from_fn(|| {
        let take_bottom = match (inner_bottom.get(i), inner_top.get(j)) {
            (None, None) => return None,
            (Some(b), Some(t)) => b.u <= t.u,
            (b, _) => b.is_some(),
        };
        Some(if take_bottom {
            i += 1;
            (inner_bottom[i - 1], Chain::Bottom)
        } else {
            j += 1;
            (inner_top[j - 1], Chain::Top)
        })
    });

    stack.clear();
    stack.push((bottom[0], Chain::Bottom));
    for (v, chain) in order {
        let &(top_point, top_chain) = stack.last().expect("the stack holds the first point");
        if stack.len() > 1 && chain != top_chain {
            // The whole stack is in sight of v: fan to it.
            for pair in stack.windows(2) {
                push_ccw(v, pair[0].0, pair[1].0, out);
            }
            stack.clear();
            stack.push((top_point, top_chain));
        } else if stack.len() > 1 {
            // Cut off the corners v sees past: convex turns of its chain.
            let mut last = stack.pop().expect("checked").0;
            while let Some(&(s, _)) = stack.last() {
                let turn = orient(s, last, v);
                let inside = match chain {
                    Chain::Top => turn < 0,
                    Chain::Bottom => turn > 0,
                };
                if !inside {
                    break;
                }
                push_ccw(v, last, s, out);
                last = stack.pop().expect("checked").0;
            }
            stack.push((last, chain));
        }
        stack.push((v, chain));
    }
    let end = bottom[bottom.len() - 1];
    for pair in stack.windows(2) {
        push_ccw(end, pair[0].0, pair[1].0, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::{HashMap, HashSet};

    /// The boundary of a wall whose segment `k` spans `spans[k]` (u = k..k+1):
    /// its corners, and the lattice points between them that `keep` picks
    /// (as if other faces had put points there).
    fn polygon(spans: &[(i64, i64)], mut keep: impl FnMut() -> bool) -> (Vec<Point>, Vec<Point>) {
        let mut next = 0;
        let mut point = |u, w| {
            next += 1;
            Point { id: next, u, w }
        };
        let n = spans.len();
        let corners = |side: fn((i64, i64)) -> i64| {
            let mut c = vec![(0, side(spans[0]))];
            for k in 1..n {
                let (a, b) = (side(spans[k - 1]), side(spans[k]));
                if a != b {
                    c.extend([(k as i64, a), (k as i64, b)]);
                }
            }
            c.push((n as i64, side(spans[n - 1])));
            c
        };
        let bottom_corners = corners(|s| s.0);
        let mut top_corners = vec![bottom_corners[0]];
        top_corners.extend(corners(|s| s.1));
        top_corners.push(bottom_corners[bottom_corners.len() - 1]);
        let mut chain = |corners: &[(i64, i64)], first: Option<Point>, last: Option<Point>| {
            let mut out = vec![first.unwrap_or_else(|| point(corners[0].0, corners[0].1))];
            for (i, pair) in corners.windows(2).enumerate() {
                let ((u0, w0), (u1, w1)) = (pair[0], pair[1]);
                for k in 1..(u1 - u0).abs().max((w1 - w0).abs()) {
                    if keep() {
                        out.push(point(
                            u0 + k * (u1 - u0).signum(),
                            w0 + k * (w1 - w0).signum(),
                        ));
                    }
                }
                let end = i + 2 == corners.len();
                out.push(match last {
                    Some(p) if end => p,
                    _ => point(u1, w1),
                });
            }
            out
        };
        let bottom = chain(&bottom_corners, None, None);
        let top = chain(
            &top_corners,
            Some(bottom[0]),
            Some(bottom[bottom.len() - 1]),
        );
        (bottom, top)
    }

    /// Triangles are counter-clockwise with area, cover the polygon's area
    /// exactly, and use each boundary edge once and every other edge twice
    /// in opposite directions: a triangulation of this polygon.
    fn assert_triangulates(bottom: &[Point], top: &[Point], tris: &[[u32; 3]]) {
        let all: HashMap<u32, Point> = bottom.iter().chain(top).map(|p| (p.id, *p)).collect();
        assert_eq!(tris.len(), all.len() - 2, "points minus two triangles");
        let mut area = 0;
        let mut edges = HashMap::new();
        for t in tris {
            let [p, q, r] = t.map(|id| all[&id]);
            let a = orient(p, q, r);
            assert!(a > 0, "{p:?} {q:?} {r:?}");
            area += a;
            for (x, y) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *edges.entry((x, y)).or_insert(0) += 1;
            }
        }
        let under = |chain: &[Point]| -> i64 {
            chain
                .windows(2)
                .map(|p| (p[1].u - p[0].u) * (p[0].w + p[1].w))
                .sum()
        };
        assert_eq!(
            area,
            under(top) - under(bottom),
            "the triangles cover the polygon once"
        );
        // The boundary counter-clockwise: bottom left to right, top backwards.
        let mut boundary = HashSet::new();
        for p in bottom.windows(2) {
            boundary.insert((p[0].id, p[1].id));
        }
        for p in top.windows(2) {
            boundary.insert((p[1].id, p[0].id));
        }
        for (&(x, y), &n) in &edges {
            assert_eq!(n, 1, "edge {x}-{y} used once per direction");
            let twin = edges.contains_key(&(y, x));
            assert!(
                boundary.contains(&(x, y)) != twin,
                "edge {x}-{y}: on the boundary xor inside"
            );
        }
        assert!(
            boundary.iter().all(|e| edges.contains_key(e)),
            "every boundary edge used"
        );
    }

    fn run(spans: &[(i64, i64)], keep: impl FnMut() -> bool) -> usize {
        let (bottom, top) = polygon(spans, keep);
        let mut out = Vec::new();
        triangulate(&bottom, &top, &mut Scratch::default(), &mut out);
        assert_triangulates(&bottom, &top, &out);
        out.len()
    }

    #[test]
    fn a_valley_between_two_towers_is_six_triangles() {
        assert_eq!(run(&[(0, 3), (0, 1), (0, 3)], || false), 6);
    }

    #[test]
    fn points_under_steps_steps_on_both_sides_and_flat_edges() {
        run(&[(0, 3), (0, 1), (0, 3)], || true);
        run(&[(0, 2), (0, 2), (0, 5), (0, 5), (0, 1)], || true);
        run(&[(1, 3), (0, 2), (1, 4), (3, 5)], || false);
        run(&[(1, 3), (0, 2), (1, 4), (3, 5)], || true);
        run(&[(2, 4), (0, 4), (1, 3), (1, 6)], || true);
    }

    proptest! {
        #[test]
        fn any_staircase_wall_is_triangulated(
            raw in proptest::collection::vec((0i64..6, 1i64..6), 1..12),
            mask in proptest::collection::vec(any::<bool>(), 200),
        ) {
            // Segments overlapping their neighbours, as a wall run has them.
            let mut spans: Vec<(i64, i64)> = Vec::new();
            for (lo, len) in raw {
                let (mut lo, mut hi) = (lo, lo + len);
                if let Some(&(plo, phi)) = spans.last()
                    && lo.max(plo) >= hi.min(phi)
                {
                    (lo, hi) = (plo, (plo + 1).max(hi.min(phi + len)));
                }
                spans.push((lo, hi));
            }
            let mut k = 0;
            run(&spans, || {
                k += 1;
                mask[k % mask.len()]
            });
        }
    }
}
