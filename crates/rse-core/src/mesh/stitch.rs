//! Triangulating the boundary faces without T-junctions.
//!
//! Every lattice point that is a corner of any face is inserted into every
//! face edge it lies on, so two faces that share a stretch of edge split it
//! at the same points. Each rectangle, now a convex polygon whose extra
//! points lie on its sides, is triangulated by a zipper that never makes a
//! zero-area triangle and adds no point; each staircase wall by the sweep of
//! [`super::staircase`].

use super::faces::{Face, LatticePoint, Levels, Normal};
use super::staircase::{self, Point};
use rayon::prelude::*;

/// The lattice points that are corners of the boundary's rectangles, with
/// ids in order of first use. Every point at grid corner `(x, y)` lies at the
/// ground or at the top of one of the four cells around it, so each grid
/// corner has at most five slots: lookups are array indexing, not hashing.
pub(crate) struct Corners {
    width: usize,
    /// Per grid corner: its candidate levels, distinct (padded with `NONE`),
    /// each with its point's id, or `NONE` while it is no corner. One array
    /// so that a lookup reads one cache line.
    slots: Vec<[(u32, u32); 5]>,
    /// Per id: the point.
    pub keys: Vec<LatticePoint>,
}

const NONE: u32 = u32::MAX;

impl Corners {
    fn new(levels: &Levels) -> Self {
        let width = levels.nx() as usize + 1;
        let mut all = Vec::with_capacity(width * (levels.ny() as usize + 1));
        for y in 0..=levels.ny() {
            for x in 0..=levels.nx() {
                let [sw, se, nw, ne] = levels.around(x, y);
                let mut slots = [(NONE, NONE); 5];
                let mut n = 0;
                for c in [0, sw, se, nw, ne] {
                    if !slots[..n].iter().any(|&(l, _)| l == c) {
                        slots[n].0 = c;
                        n += 1;
                    }
                }
                all.push(slots);
            }
        }
        Corners {
            width,
            slots: all,
            keys: Vec::new(),
        }
    }

    /// The grid corner and slot of `key`, if its level is one of the corner's.
    fn find(&self, key: LatticePoint) -> Option<(usize, usize)> {
        let corner = key[1] as usize * self.width + key[0] as usize;
        let slot = self.slots[corner].iter().position(|&(l, _)| l == key[2])?;
        Some((corner, slot))
    }

    /// The id of `key`, numbering it if it is new.
    fn insert(&mut self, key: LatticePoint) -> u32 {
        let (corner, slot) = self
            .find(key)
            .expect("a corner's level is the ground or a neighbouring top");
        let id = &mut self.slots[corner][slot].1;
        if *id == NONE {
            *id = self.keys.len() as u32;
            self.keys.push(key);
        }
        *id
    }

    fn get(&self, key: LatticePoint) -> Option<u32> {
        let (corner, slot) = self.find(key)?;
        let id = self.slots[corner][slot].1;
        (id != NONE).then_some(id)
    }

    /// Clears `out`, then pushes the chain through `corners` (each edge
    /// between two in a row axis-aligned): each corner, and between two the
    /// corners that lie on the edge joining them.
    fn chain(
        &self,
        corners: impl IntoIterator<Item = (u32, LatticePoint)>,
        out: &mut Vec<(u32, LatticePoint)>,
    ) {
        out.clear();
        let mut previous: Option<LatticePoint> = None;
        for (id, key) in corners {
            if let Some(p) = previous {
                self.between(p, key, out);
            }
            out.push((id, key));
            previous = Some(key);
        }
    }

    /// Pushes the corners strictly between `p` and `q` (which differ in one
    /// coordinate), in order from `p` to `q`.
    fn between(&self, p: LatticePoint, q: LatticePoint, out: &mut Vec<(u32, LatticePoint)>) {
        let axis = (0..3).find(|&a| p[a] != q[a]).expect("an edge has length");
        let (lo, hi) = (p[axis].min(q[axis]), p[axis].max(q[axis]));
        let start = out.len();
        if axis == 2 {
            let corner = p[1] as usize * self.width + p[0] as usize;
            for &(level, id) in &self.slots[corner] {
                if level > lo && level < hi && id != NONE {
                    out.push((id, [p[0], p[1], level]));
                }
            }
            // Slots are not in level order; at most three points lie between.
            out[start..].sort_unstable_by_key(|&(_, k)| k[2]);
        } else {
            for c in lo + 1..hi {
                let mut k = p;
                k[axis] = c;
                if let Some(id) = self.get(k) {
                    out.push((id, k));
                }
            }
        }
        if p[axis] > q[axis] {
            out[start..].reverse();
        }
    }
}

/// Triangles of lattice point ids, counter-clockwise seen from outside, with
/// the outward normal of each.
pub(crate) struct Triangles {
    pub corners: Corners,
    pub ids: Vec<[u32; 3]>,
    pub normals: Vec<Normal>,
}

/// A face as kept between numbering and triangulating: corner ids only, in
/// 20 bytes (a large random field has millions of faces).
enum Numbered {
    Rect([u32; 4], Normal),
    /// The outline's ids are `outlines[start..end]`, split as in the face.
    Staircase {
        start: u32,
        split: u32,
        end: u32,
        normal: Normal,
        axes: [u8; 2],
    },
}

/// Triangulates every face that `faces` emits, in order.
pub(crate) fn triangulate(levels: &Levels, faces: impl FnOnce(&mut dyn FnMut(Face))) -> Triangles {
    let mut corners = Corners::new(levels);
    // Numbering every corner before any face is split, so that the
    // splitting sees all of them; each face keeps only its corners' ids.
    // Sized for a random field (about two faces per cell and one outline
    // corner), so that these large buffers are not copied as they grow; up
    // to a cap, as a flat field of 10⁸ cells has a handful of faces.
    let cells = (levels.nx() as usize * levels.ny() as usize).min(1 << 24);
    let mut numbered = Vec::with_capacity(2 * cells);
    let mut outlines = Vec::with_capacity(cells);
    faces(&mut |face: Face| match face {
        Face::Rect(rect) => {
            numbered.push(Numbered::Rect(
                rect.corners.map(|k| corners.insert(k)),
                rect.normal,
            ));
        }
        Face::Staircase {
            outline,
            split,
            normal,
            axes,
        } => {
            let start = outlines.len();
            outlines.extend(outline.iter().map(|&k| corners.insert(k)));
            numbered.push(Numbered::Staircase {
                start: start as u32,
                split: (start + split) as u32,
                end: outlines.len() as u32,
                normal,
                axes,
            });
        }
    });
    // Faces are triangulated independently of each other: a large mesh is
    // cut into runs of faces of a fixed length, triangulated in parallel and
    // joined in order, so the output does not depend on the thread count.
    let (ids, normals) = if numbered.len() <= FACES_PER_TASK {
        triangulate_faces(levels, &corners, &outlines, &numbered)
    } else {
        let parts: Vec<_> = numbered
            .par_chunks(FACES_PER_TASK)
            .map(|faces| triangulate_faces(levels, &corners, &outlines, faces))
            .collect();
        let total = parts.iter().map(|(t, _)| t.len()).sum();
        let (mut ids, mut normals) = (Vec::with_capacity(total), Vec::with_capacity(total));
        for (t, n) in parts {
            ids.extend_from_slice(&t);
            normals.extend_from_slice(&n);
        }
        (ids, normals)
    };
    Triangles {
        corners,
        ids,
        normals,
    }
}

/// Faces per parallel task: small meshes (a 50×50 field has about 5,000
/// faces) stay on the calling thread.
const FACES_PER_TASK: usize = 1 << 16;

/// The triangles of `faces`, in order, with their normals.
fn triangulate_faces(
    levels: &Levels,
    corners: &Corners,
    outlines: &[u32],
    faces: &[Numbered],
) -> (Vec<[u32; 3]>, Vec<Normal>) {
    // About three triangles a face on a random field; reserved once, as
    // growing copies the largest buffers of the build.
    let mut triangles = Vec::with_capacity(faces.len() * 4);
    let mut normals = Vec::with_capacity(faces.len() * 4);
    let (mut ab, mut ad) = (Vec::new(), Vec::new());
    let mut staircase = StaircaseBuffers::default();
    for face in faces {
        match *face {
            Numbered::Rect(ids, normal) => {
                let [a, b, c, d] = ids.map(|id| (id, corners.keys[id as usize]));
                // Two chains from corner a to the opposite corner c: through b and
                // through d, each with the points on its sides.
                corners.chain([a, b, c], &mut ab);
                corners.chain([a, d, c], &mut ad);
                zip(&ab, &ad, &mut triangles);
                normals.resize(triangles.len(), normal);
            }
            Numbered::Staircase {
                start,
                split,
                end,
                normal,
                axes,
            } => {
                let [start, split, end] = [start, split, end].map(|i| i as usize);
                let edges = [&outlines[start..split], &outlines[split..end]];
                staircase.triangulate(levels, corners, edges, axes, normal, &mut triangles);
                normals.resize(triangles.len(), normal);
            }
        }
    }
    (triangles, normals)
}

/// Buffers for triangulating staircase walls, reused from one to the next.
#[derive(Default)]
struct StaircaseBuffers {
    keyed: Vec<(u32, LatticePoint)>,
    low: Vec<Point>,
    high: Vec<Point>,
    scratch: staircase::Scratch,
}

impl StaircaseBuffers {
    /// Appends the triangles of the staircase whose low-`w` and high-`w`
    /// edges have the corner ids `edges` in the plane of `axes` (see
    /// [`Face::Staircase`]), counter-clockwise seen from the side `normal`
    /// points to.
    fn triangulate(
        &mut self,
        levels: &Levels,
        corners: &Corners,
        [low, high]: [&[u32]; 2],
        axes: [u8; 2],
        normal: Normal,
        out: &mut Vec<[u32; 3]>,
    ) {
        // Both chains from the first corner of the low edge to its last:
        // the low edge; and across the first end, along the high edge and
        // back across the last end.
        let ends = [low[0], low[low.len() - 1]];
        let high = ends[..1].iter().chain(high).chain(&ends[1..]);
        let axes = axes.map(usize::from);
        chain_points(
            corners,
            levels,
            axes,
            low.iter().copied(),
            &mut self.keyed,
            &mut self.low,
        );
        chain_points(
            corners,
            levels,
            axes,
            high.copied(),
            &mut self.keyed,
            &mut self.high,
        );

        let first = out.len();
        staircase::triangulate(&self.low, &self.high, &mut self.scratch, out);
        // Counter-clockwise in (u, w) is seen from the side of u × w.
        let seen_from = match axes {
            [1, 2] => Normal::PosX,
            [0, 2] => Normal::NegY,
            [1, 0] => Normal::NegZ,
            _ => unreachable!("staircases are walls, tops and the bottom"),
        };
        if seen_from != normal {
            for t in &mut out[first..] {
                t.swap(1, 2);
            }
        }
    }
}

/// The points of the chain through the corners `ids`, with every point
/// other faces put on it, as `(u, w)` points in the plane of `axes`.
/// Heights are in steps, linear in z, so that turns are those of space.
fn chain_points(
    corners: &Corners,
    levels: &Levels,
    [u, w]: [usize; 2],
    ids: impl Iterator<Item = u32>,
    keyed: &mut Vec<(u32, LatticePoint)>,
    points: &mut Vec<Point>,
) {
    corners.chain(ids.map(|id| (id, corners.keys[id as usize])), keyed);
    let coordinate = |k: LatticePoint, axis: usize| {
        if axis == 2 {
            levels.steps(k[2]).expect("staircases have whole steps")
        } else {
            i64::from(k[axis])
        }
    };
    points.clear();
    points.extend(keyed.iter().map(|&(id, k)| Point {
        id,
        u: coordinate(k, u),
        w: coordinate(k, w),
    }));
}

/// Triangulates the convex polygon `a … c` (chain `ab`, counter-clockwise)
/// `c … a` (chain `ad` reversed). Every point of `ab` but its ends is on the
/// sides a–b or b–c, every point of `ad` on a–d or d–c; three points are
/// collinear only on one side, so a triangle with points of both chains,
/// none of them `a` or `c`, always has area. The first triangle is
/// `(a, ab[1], ad[1])`, the last `(ab[n−2], c, ad[m−2])`; between, the chain
/// whose next point is nearer to `a` advances.
fn zip(ab: &[(u32, LatticePoint)], ad: &[(u32, LatticePoint)], out: &mut Vec<[u32; 3]>) {
    let (n, m) = (ab.len(), ad.len());
    let a = ab[0].1;
    let progress = |p: LatticePoint| (0..3).map(|k| p[k].abs_diff(a[k])).sum::<u32>();
    out.push([ab[0].0, ab[1].0, ad[1].0]);
    let (mut i, mut j) = (1, 1);
    while i < n - 2 || j < m - 2 {
        let advance_ab =
            j == m - 2 || (i < n - 2 && progress(ab[i + 1].1) <= progress(ad[j + 1].1));
        if advance_ab {
            out.push([ab[i].0, ab[i + 1].0, ad[j].0]);
            i += 1;
        } else {
            out.push([ab[i].0, ad[j + 1].0, ad[j].0]);
            j += 1;
        }
    }
    out.push([ab[n - 2].0, ab[n - 1].0, ad[m - 2].0]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heightmap::Heightmap;
    use crate::mesh::faces::Rect;

    fn area2(keys: &[LatticePoint], t: [u32; 3]) -> i64 {
        let [p, q, r] = t.map(|id| keys[id as usize].map(i64::from));
        let u = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
        let c = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        c[0] * c[0] + c[1] * c[1] + c[2] * c[2]
    }

    fn top(x0: u32, y0: u32, x1: u32, y1: u32) -> Rect {
        Rect {
            corners: [[x0, y0, 1], [x1, y0, 1], [x1, y1, 1], [x0, y1, 1]],
            normal: Normal::PosZ,
        }
    }

    #[test]
    fn a_bare_rectangle_is_two_triangles() {
        let levels = Levels::new(&Heightmap::from_cells(5, 3, vec![0; 15]).unwrap(), true);
        let t = triangulate(&levels, |emit| emit(Face::Rect(top(0, 0, 5, 3))));
        assert_eq!(t.ids.len(), 2);
        assert!(t.ids.iter().all(|&id| area2(&t.corners.keys, id) > 0));
    }

    #[test]
    fn points_on_every_side_give_k_minus_2_triangles_with_area() {
        // A big top with small neighbours whose corners land on its sides.
        let levels = Levels::new(&Heightmap::from_cells(8, 8, vec![0; 64]).unwrap(), true);
        let rects = [top(0, 0, 6, 6), top(2, 6, 3, 7), top(6, 1, 7, 4)];
        let Triangles {
            corners, ids: t, ..
        } = triangulate(&levels, |emit| {
            for rect in rects {
                emit(Face::Rect(rect));
            }
        });
        // big: 4 corners + (2,6), (3,6) + (6,1), (6,4) = 8 points → 6 triangles
        let keys = &corners.keys;
        let inside = |t: &&[u32; 3]| {
            t.iter()
                .all(|&id| keys[id as usize][0] <= 6 && keys[id as usize][1] <= 6)
        };
        assert_eq!(t.iter().filter(inside).count(), 6);
        assert!(t.iter().all(|&t| area2(keys, t) > 0), "{t:?}");
    }
}
