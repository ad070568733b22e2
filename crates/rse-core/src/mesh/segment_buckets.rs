//! The buckets of a cubic grid that a segment passes through, for the
//! T-junction search: a long edge walks the buckets along it, not every
//! bucket of its bounding box (a diagonal edge across a wall 600 steps
//! high and 999 cells long has a box of ~10⁵ buckets, a path of ~10³).

use std::ops::ControlFlow;

/// The buckets of side `size` within `margin` of the segment `p`–`q`,
/// a superset of them, each given to `visit` once (it may stop the walk).
///
/// The walk goes slab by slab along the segment's longest axis; in each
/// slab the other two coordinates move at most one bucket, so a segment of
/// `n` buckets along that axis visits at most `9n` (`4n` but where it grazes
/// bucket borders). Rounding cannot skip a bucket: each slab's range is
/// widened by `margin` plus a hair (none along an axis the segment does
/// not move on: there it is the vertex's own coordinate), and clamped to the buckets of the segment's ends, which
/// hold every point between them.
pub(crate) fn walk(
    p: [f64; 3],
    q: [f64; 3],
    size: f64,
    margin: f64,
    mut visit: impl FnMut([i64; 3]) -> ControlFlow<()>,
) -> ControlFlow<()> {
    let bucket = |c: f64| (c / size).floor() as i64;
    let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
    let long = (0..3)
        .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
        .unwrap_or(0);
    let ends = |i: usize| {
        (
            bucket(p[i].min(q[i]) - margin),
            bucket(p[i].max(q[i]) + margin),
        )
    };
    // An axis the segment does not move on has one range for every slab,
    // its coordinate `p[i]` itself (a vertex on the segment has the very
    // same value, so no hair is added): worked out once. Most terrain
    // edges run along an axis; widened and recomputed slab by slab, such
    // an edge on a bucket border walked four buckets a slab instead of one
    // and checking a tall random field took twice as long.
    let fixed = |i: usize| (d[i] == 0.0).then(|| ends(i));
    let fixed = [fixed(0), fixed(1), fixed(2)];
    let (first, last) = ends(long);
    if (0..3).all(|i| i == long || fixed[i].is_some()) {
        // Along one axis (or a point): its box is its path.
        let range = std::array::from_fn(|i| fixed[i].unwrap_or((first, last)));
        return visit_box(range, &mut visit);
    }
    for slab in first..=last {
        let mut range = [(slab, slab); 3];
        // The stretch of the segment whose long coordinate is in this slab.
        let (t0, t1) = if d[long] == 0.0 {
            (0.0, 1.0)
        } else {
            let a = (slab as f64 * size - margin - p[long]) / d[long];
            let b = ((slab + 1) as f64 * size + margin - p[long]) / d[long];
            (a.min(b).clamp(0.0, 1.0), a.max(b).clamp(0.0, 1.0))
        };
        for (i, r) in range.iter_mut().enumerate().filter(|&(i, _)| i != long) {
            if let Some(same) = fixed[i] {
                *r = same;
                continue;
            }
            let (a, b) = (p[i] + t0 * d[i], p[i] + t1 * d[i]);
            let hair = 1e-9 * (a.abs() + b.abs() + size);
            let (lo, hi) = ends(i);
            *r = (
                bucket(a.min(b) - margin - hair).clamp(lo, hi),
                bucket(a.max(b) + margin + hair).clamp(lo, hi),
            );
        }
        visit_box(range, &mut visit)?;
    }
    ControlFlow::Continue(())
}

/// Gives `visit` every bucket of the box `[(lo, hi); 3]`, x slowest.
fn visit_box(
    [(x0, x1), (y0, y1), (z0, z1)]: [(i64, i64); 3],
    visit: &mut impl FnMut([i64; 3]) -> ControlFlow<()>,
) -> ControlFlow<()> {
    for x in x0..=x1 {
        for y in y0..=y1 {
            for z in z0..=z1 {
                visit([x, y, z])?;
            }
        }
    }
    ControlFlow::Continue(())
}

/// About how many buckets [`walk`] visits for `p`–`q`, counted without
/// walking (saturating): one, and two for each bucket border crossed. The
/// search picks its bucket size by this sum over every edge.
pub(crate) fn count(p: [f64; 3], q: [f64; 3], size: f64) -> u128 {
    let bucket = |c: f64| (c / size).floor() as i64;
    (0..3).fold(1u128, |n, i| {
        let crossed = (i128::from(bucket(p[i].max(q[i]))) - i128::from(bucket(p[i].min(q[i]))))
            .unsigned_abs();
        n.saturating_add(crossed.saturating_mul(2))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn buckets(p: [f64; 3], q: [f64; 3], size: f64) -> Vec<[i64; 3]> {
        let mut seen = Vec::new();
        let _ = walk(p, q, size, 0.0, |b| {
            seen.push(b);
            ControlFlow::Continue(())
        });
        seen
    }

    /// Every point of a segment (sampled finely) lies in a bucket walked,
    /// and a long diagonal walks a path, not its bounding box.
    #[test]
    fn a_diagonal_walks_its_path_and_misses_no_point() {
        let (p, q) = ([4.0, 0.0, 0.0], [4.0, 999.0, 600.0]);
        let seen = buckets(p, q, 1.0);
        assert!(seen.len() <= 4 * 1000, "{}", seen.len());
        assert!(count(p, q, 1.0) >= seen.len() as u128 / 2);
        for k in 0..=10_000 {
            let t = f64::from(k) / 10_000.0;
            let point = [4.0, 999.0 * t, 600.0 * t].map(|c: f64| c.floor() as i64);
            assert!(seen.contains(&point), "{point:?} at t = {t}");
        }
    }

    /// A segment along an axis, a point, and one through bucket corners.
    #[test]
    fn axis_segments_points_and_corners() {
        assert_eq!(buckets([0.5; 3], [0.5; 3], 1.0), vec![[0, 0, 0]]);
        assert_eq!(
            buckets([0.5, 0.5, 0.5], [2.5, 0.5, 0.5], 1.0),
            vec![[0, 0, 0], [1, 0, 0], [2, 0, 0]]
        );
        let through = buckets([0.0; 3], [3.0; 3], 1.0);
        for i in 0..=3 {
            assert!(through.contains(&[i, i, i]), "{through:?}");
        }
    }

    /// The walk stops when asked.
    #[test]
    fn the_walk_stops_when_told() {
        let mut n = 0;
        let stopped = walk([0.0; 3], [100.0, 0.0, 0.0], 1.0, 0.0, |_| {
            n += 1;
            if n == 5 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        });
        assert!(stopped.is_break() && n == 5);
    }
}
