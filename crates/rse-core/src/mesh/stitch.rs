//! Triangulating the boundary rectangles without T-junctions.
//!
//! Every lattice point that is a corner of any rectangle is inserted into
//! every rectangle edge it lies on, so two faces that share a stretch of edge
//! split it at the same points. Each rectangle, now a convex polygon whose
//! extra points lie on its sides, is triangulated by a zipper that never
//! makes a zero-area triangle and adds no point.

use super::faces::{Key, Normal, Rect};

/// A triangle of lattice points, counter-clockwise seen from outside.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Triangle {
    pub corners: [Key; 3],
    pub normal: Normal,
}

/// The corners of all rectangles, sorted by the axis-aligned line they are on.
struct Lines {
    /// One list per axis `a`: `(the other two coordinates, coordinate a)`, sorted.
    by_axis: [Vec<([u32; 2], u32)>; 3],
}

impl Lines {
    fn new(rects: &[Rect]) -> Self {
        let by_axis = std::array::from_fn(|axis| {
            let mut points: Vec<([u32; 2], u32)> = rects
                .iter()
                .flat_map(|r| r.corners)
                .map(|p| (others(p, axis), p[axis]))
                .collect();
            points.sort_unstable();
            points.dedup();
            points
        });
        Lines { by_axis }
    }

    /// The corners strictly between `p` and `q` (which differ in one
    /// coordinate), in order from `p` to `q`.
    fn between(&self, p: Key, q: Key, out: &mut Vec<Key>) {
        let axis = (0..3).find(|&a| p[a] != q[a]).expect("an edge has length");
        let line = others(p, axis);
        let (lo, hi) = (p[axis].min(q[axis]), p[axis].max(q[axis]));
        let list = &self.by_axis[axis];
        let first = list.partition_point(|&(l, c)| (l, c) <= (line, lo));
        let last = list.partition_point(|&(l, c)| (l, c) < (line, hi));
        let start = out.len();
        out.extend(list[first..last].iter().map(|&(_, c)| with(p, axis, c)));
        if p[axis] > q[axis] {
            out[start..].reverse();
        }
    }
}

/// The two coordinates of `p` other than `axis`.
fn others(p: Key, axis: usize) -> [u32; 2] {
    match axis {
        0 => [p[1], p[2]],
        1 => [p[0], p[2]],
        _ => [p[0], p[1]],
    }
}

fn with(mut p: Key, axis: usize, value: u32) -> Key {
    p[axis] = value;
    p
}

/// Triangulates every rectangle, in order.
pub(crate) fn triangulate(rects: &[Rect]) -> Vec<Triangle> {
    let lines = Lines::new(rects);
    let mut triangles = Vec::with_capacity(rects.len() * 3);
    let (mut ab, mut ad) = (Vec::new(), Vec::new());
    for rect in rects {
        let [a, b, c, d] = rect.corners;
        // Two chains from corner a to the opposite corner c: through b and
        // through d, each with the points on its sides.
        ab.clear();
        ab.push(a);
        lines.between(a, b, &mut ab);
        ab.push(b);
        lines.between(b, c, &mut ab);
        ab.push(c);
        ad.clear();
        ad.push(a);
        lines.between(a, d, &mut ad);
        ad.push(d);
        lines.between(d, c, &mut ad);
        ad.push(c);
        zip(&ab, &ad, rect.normal, &mut triangles);
    }
    triangles
}

/// Triangulates the convex polygon `a … c` (chain `ab`, counter-clockwise)
/// `c … a` (chain `ad` reversed). Every point of `ab` but its ends is on the
/// sides a–b or b–c, every point of `ad` on a–d or d–c; three points are
/// collinear only on one side, so a triangle with points of both chains,
/// none of them `a` or `c`, always has area. The first triangle is
/// `(a, ab[1], ad[1])`, the last `(ab[n−2], c, ad[m−2])`; between, the chain
/// whose next point is nearer to `a` advances.
fn zip(ab: &[Key], ad: &[Key], normal: Normal, out: &mut Vec<Triangle>) {
    let (n, m) = (ab.len(), ad.len());
    let tri = |corners| Triangle { corners, normal };
    let progress = |p: Key| {
        let a = ab[0];
        (0..3).map(|k| p[k].abs_diff(a[k])).sum::<u32>()
    };
    out.push(tri([ab[0], ab[1], ad[1]]));
    let (mut i, mut j) = (1, 1);
    while i < n - 2 || j < m - 2 {
        let advance_ab = j == m - 2 || (i < n - 2 && progress(ab[i + 1]) <= progress(ad[j + 1]));
        if advance_ab {
            out.push(tri([ab[i], ab[i + 1], ad[j]]));
            i += 1;
        } else {
            out.push(tri([ab[i], ad[j + 1], ad[j]]));
            j += 1;
        }
    }
    out.push(tri([ab[n - 2], ab[n - 1], ad[m - 2]]));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area2(t: &Triangle) -> i64 {
        // twice the area in the lattice, via the cross product's length²
        let [p, q, r] = t.corners.map(|k| k.map(i64::from));
        let u = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
        let c = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        c[0] * c[0] + c[1] * c[1] + c[2] * c[2]
    }

    #[test]
    fn a_bare_rectangle_is_two_triangles() {
        let rect = Rect {
            corners: [[0, 0, 1], [5, 0, 1], [5, 3, 1], [0, 3, 1]],
            normal: Normal::PosZ,
        };
        let t = triangulate(&[rect]);
        assert_eq!(t.len(), 2);
        assert!(t.iter().all(|t| area2(t) > 0));
    }

    #[test]
    fn points_on_every_side_give_k_minus_2_triangles_with_area() {
        // A big top with four small neighbours whose corners land on its sides.
        let big = Rect {
            corners: [[0, 0, 1], [6, 0, 1], [6, 6, 1], [0, 6, 1]],
            normal: Normal::PosZ,
        };
        let small = |x0, y0, x1, y1| Rect {
            corners: [[x0, y0, 1], [x1, y0, 1], [x1, y1, 1], [x0, y1, 1]],
            normal: Normal::PosZ,
        };
        let rects = [big, small(2, 6, 3, 7), small(6, 1, 7, 4)];
        let t = triangulate(&rects);
        // big: 4 corners + (2,6), (3,6) + (6,1), (6,4) = 8 points → 6 triangles
        let inside = |t: &&Triangle| t.corners.iter().all(|c| c[0] <= 6 && c[1] <= 6);
        assert_eq!(t.iter().filter(inside).count(), 6);
        assert!(t.iter().all(|t| area2(t) > 0), "{t:?}");
    }
}
