//! Checking a triangle mesh against the invariants of docs/meshes.md: closed and
//! consistently oriented, no zero-area triangle, no T-junction; and measuring
//! its volume and bounding box. Works on any mesh, ours or one read from disk.

use std::collections::HashMap;
use std::ops::ControlFlow;

use super::segment_buckets;

/// A way in which a mesh breaks the invariants.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum MeshFault {
    /// The directed edge `a → b` has no twin `b → a`, or is used more than once.
    UnpairedEdge {
        /// Start vertex.
        a: u32,
        /// End vertex.
        b: u32,
        /// How many triangles use `a → b`.
        uses: usize,
        /// How many use `b → a`.
        reverse_uses: usize,
    },
    /// A triangle of (nearly) zero area.
    Degenerate {
        /// The triangle's index.
        triangle: usize,
    },
    /// A vertex lies inside an edge without being one of its ends.
    TJunction {
        /// The index of the vertex inside the edge.
        vertex: u32,
        /// The edge's ends.
        edge: [u32; 2],
    },
    /// Two or more sheets of surface meet at one vertex (it should be one
    /// vertex per sheet, as at a saddle).
    PinchedVertex {
        /// The index of the vertex where the sheets meet.
        vertex: u32,
        /// How many separate fans of triangles meet there.
        fans: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    BadIndex {
        /// The triangle's index.
        triangle: usize,
    },
    /// A vertex with a coordinate that is infinite or not a number.
    NonFinite {
        /// The index of the vertex with the bad coordinate.
        vertex: u32,
    },
    /// A mesh so irregular (vertices crowded where long edges pass) that
    /// looking for T-junctions would take more than
    /// [`MAX_SEARCH_STEPS_PER_ELEMENT`] steps per edge and vertex: no
    /// terrain mesh is like that, a damaged or hostile one can be.
    TooIrregular {
        /// The steps taken when the search gave up.
        search_steps: u64,
    },
}

/// The T-junction search takes at most this many steps (a bucket visited,
/// a vertex tested) per edge and vertex of a mesh, plus
/// [`MIN_SEARCH_STEPS`]. A terrain mesh needs a handful: buckets grow
/// until long edges walk few of them, and its vertices are spread evenly.
/// Past the cap the mesh is reported, not searched, so a hostile mesh
/// cannot make the check run for ever.
pub const MAX_SEARCH_STEPS_PER_ELEMENT: u64 = 256;

/// Search steps always allowed, however small the mesh.
pub const MIN_SEARCH_STEPS: u64 = 1 << 22;

impl std::fmt::Display for MeshFault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            MeshFault::UnpairedEdge {
                a,
                b,
                uses,
                reverse_uses,
            } => write!(
                f,
                "edge {a}->{b} is used {uses} times and {b}->{a} {reverse_uses} times (want once each: a hole or a flipped face)"
            ),
            MeshFault::Degenerate { triangle } => write!(f, "triangle {triangle} has no area"),
            MeshFault::TJunction { vertex, edge } => write!(
                f,
                "vertex {vertex} lies inside edge {}-{} (a T-junction)",
                edge[0], edge[1]
            ),
            MeshFault::PinchedVertex { vertex, fans } => {
                write!(f, "{fans} sheets of surface meet at vertex {vertex}")
            }
            MeshFault::BadIndex { triangle } => {
                write!(
                    f,
                    "triangle {triangle} refers to a vertex that does not exist"
                )
            }
            MeshFault::NonFinite { vertex } => {
                write!(f, "vertex {vertex} has a coordinate that is not finite")
            }
            MeshFault::TooIrregular { search_steps } => write!(
                f,
                "too irregular to search for T-junctions (gave up after {search_steps} steps)"
            ),
        }
    }
}

/// Every fault of `vertices`/`triangles`, in a stable order (empty: the mesh
/// is a closed, oriented, T-junction-free surface of triangles with area).
///
/// For a mesh of unknown origin: a vertex within two `f32` units of the
/// largest coordinate of an edge's inside is a T-junction (a vertex meant to
/// lie on the edge is off it by its rounding alone). A mesh of a terrain's
/// lattice is checked exactly by [`lattice_faults`] instead: there a true
/// corner can be closer than that to a long, thin wall triangle's edge.
pub fn faults(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Vec<MeshFault> {
    let positions: Vec<[f64; 3]> = vertices.iter().map(|&p| point(p)).collect();
    let scale = extent(vertices).max(f64::MIN_POSITIVE);
    let largest = positions
        .iter()
        .flat_map(|p| p.iter().map(|c| c.abs()))
        .fold(0.0, f64::max);
    let tolerance = 2.0 * f64::from(f32::EPSILON) * largest.max(scale * 1e-3);
    let degenerate = |t: [u32; 3]| {
        let [p, q, r] = t.map(|v| positions[v as usize]);
        let c = cross(sub(q, p), sub(r, p));
        dot(c, c).sqrt() <= 1e-10 * scale * scale
    };
    let on_edge = |v: u32, a: u32, b: u32| {
        let (p, q) = (positions[a as usize], positions[b as usize]);
        let (d, w) = (sub(q, p), sub(positions[v as usize], p));
        let t = dot(w, d) / dot(d, d);
        let off = sub(w, d.map(|c| c * t));
        t > 1e-9 && t < 1.0 - 1e-9 && length(off) < tolerance
    };
    checked(&positions, triangles, tolerance, &degenerate, &on_edge)
}

/// Every fault of a mesh whose vertices are points of a lattice, exactly:
/// `points` are the vertices in whole lattice units per axis (see
/// [`MeshUnits::lattice_point`](super::MeshUnits::lattice_point)),
/// `positions` the same in metres (only to sort vertices into buckets).
/// A triangle is degenerate when its corners are collinear, and a vertex
/// is a T-junction when it lies on an edge strictly between its ends, both
/// in integer arithmetic: no tolerance, so no true corner is mistaken for a
/// T-junction however thin the triangle (a corner 23 µm off a 43 m wall
/// edge was, under `f32` tolerances), and none is missed.
///
/// # Panics
/// If `points` and `positions` differ in length.
pub fn lattice_faults(
    points: &[[i128; 3]],
    positions: &[[f64; 3]],
    triangles: &[[u32; 3]],
) -> Vec<MeshFault> {
    assert_eq!(points.len(), positions.len(), "one position per point");
    let isub = |a: [i128; 3], b: [i128; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    // Lattice coordinates stay below 2^80 (`MeshUnits`), so every product
    // below stays far inside i128.
    let collinear = |p: [i128; 3], q: [i128; 3], r: [i128; 3]| {
        let (a, b) = (isub(q, p), isub(r, p));
        a[1] * b[2] == a[2] * b[1] && a[2] * b[0] == a[0] * b[2] && a[0] * b[1] == a[1] * b[0]
    };
    let degenerate = |t: [u32; 3]| {
        let [p, q, r] = t.map(|v| points[v as usize]);
        collinear(p, q, r)
    };
    let on_edge = |v: u32, a: u32, b: u32| {
        let (p, q, w) = (points[a as usize], points[b as usize], points[v as usize]);
        w != p
            && w != q
            && (0..3).all(|i| p[i].min(q[i]) <= w[i] && w[i] <= p[i].max(q[i]))
            && collinear(p, q, w)
    };
    checked(positions, triangles, 0.0, &degenerate, &on_edge)
}

/// The checks of [`faults`] and [`lattice_faults`], with their two tests:
/// is a triangle degenerate, does vertex `v` lie inside edge `a–b` (at
/// most `margin` off it).
fn checked(
    positions: &[[f64; 3]],
    triangles: &[[u32; 3]],
    margin: f64,
    degenerate: &dyn Fn([u32; 3]) -> bool,
    on_edge: &dyn Fn(u32, u32, u32) -> bool,
) -> Vec<MeshFault> {
    let mut faults: Vec<MeshFault> = positions
        .iter()
        .enumerate()
        .filter(|(_, p)| !p.iter().all(|c| c.is_finite()))
        .map(|(v, _)| MeshFault::NonFinite { vertex: v as u32 })
        .collect();
    if !faults.is_empty() {
        // Every measure below would be NaN or infinite.
        return faults;
    }
    let n = positions.len() as u32;
    for (i, t) in triangles.iter().enumerate() {
        if t.iter().any(|&v| v >= n) {
            faults.push(MeshFault::BadIndex { triangle: i });
        }
    }
    if !faults.is_empty() {
        return faults;
    }

    let edges = directed_edges(triangles);
    let count = |edge: (u32, u32)| {
        let first = edges.partition_point(|&(e, _)| e < edge);
        edges[first..]
            .iter()
            .take_while(|&&(e, _)| e == edge)
            .count()
    };
    let mut start = 0;
    while start < edges.len() {
        let edge = edges[start].0;
        let uses = edges[start..]
            .iter()
            .take_while(|&&(e, _)| e == edge)
            .count();
        let reverse_uses = count((edge.1, edge.0));
        if uses != 1 || reverse_uses != 1 {
            faults.push(MeshFault::UnpairedEdge {
                a: edge.0,
                b: edge.1,
                uses,
                reverse_uses,
            });
        }
        start += uses;
    }

    if faults.is_empty() {
        faults.extend(pinched_vertices(triangles, &edges));
    }
    for (i, &t) in triangles.iter().enumerate() {
        if degenerate(t) {
            faults.push(MeshFault::Degenerate { triangle: i });
        }
    }
    // A vertex on another shell's edge opens no crack: each shell (a
    // ramp's wedge beside the blocks') is closed on its own.
    let shell = shells(positions.len(), triangles);
    let same_shell_on_edge =
        |v: u32, a: u32, b: u32| shell[v as usize] == shell[a as usize] && on_edge(v, a, b);
    faults.extend(t_junctions(positions, margin, &edges, &same_shell_on_edge));
    faults
}

/// The shell of each of `vertices` vertices: the root of the vertices its
/// triangles join to it.
fn shells(vertices: usize, triangles: &[[u32; 3]]) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..vertices).collect();
    for t in triangles {
        for k in 1..3 {
            let (a, b) = (
                find(&mut parent, t[0] as usize),
                find(&mut parent, t[k] as usize),
            );
            parent[a.max(b)] = a.min(b);
        }
    }
    (0..vertices).map(|v| find(&mut parent, v)).collect()
}

/// A directed edge `(a, b)` and the corner (3·triangle + slot) holding `a`.
type Edge = ((u32, u32), usize);

/// Every directed edge `a → b` of `triangles` with the corner that holds
/// `a`, sorted: the one list all checks read.
fn directed_edges(triangles: &[[u32; 3]]) -> Vec<Edge> {
    let mut edges: Vec<Edge> = triangles
        .iter()
        .enumerate()
        .flat_map(|(f, t)| (0..3).map(move |k| ((t[k], t[(k + 1) % 3]), f * 3 + k)))
        .collect();
    edges.sort_unstable();
    edges
}

/// Vertices around which the triangles form more than one fan. Needs every
/// directed edge paired (no `UnpairedEdge`): corners of the two triangles on
/// an edge are joined, and each vertex must end up with one group.
fn pinched_vertices(triangles: &[[u32; 3]], edges: &[Edge]) -> Vec<MeshFault> {
    let mut parent: Vec<usize> = (0..triangles.len() * 3).collect();
    let next = |corner: usize| corner - corner % 3 + (corner % 3 + 1) % 3;
    for &((a, b), corner) in edges {
        let twin = edges[edges.partition_point(|&(e, _)| e < (b, a))].1;
        // corner holds a (and next(corner) holds b); twin holds b, next(twin) a.
        for (x, y) in [(corner, next(twin)), (next(corner), twin)] {
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            parent[rx.max(ry)] = rx.min(ry);
        }
    }
    // (vertex, fan) for every corner, sorted and deduplicated: each vertex's
    // fans in one run. Sorting keeps this O(n log n) however many fans meet
    // at one vertex (a per-vertex list searched linearly took 34 s for
    // 312,799 tetrahedra sharing a vertex).
    let mut fans: Vec<(u32, usize)> = (0..triangles.len() * 3)
        .map(|corner| (triangles[corner / 3][corner % 3], find(&mut parent, corner)))
        .collect();
    fans.sort_unstable();
    fans.dedup();
    fans.chunk_by(|x, y| x.0 == y.0)
        .filter(|fans| fans.len() > 1)
        .map(|fans| MeshFault::PinchedVertex {
            vertex: fans[0].0,
            fans: fans.len(),
        })
        .collect()
}

/// The root of `x` in a union–find forest, halving paths on the way.
fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Vertices lying strictly inside an edge (`on_edge`), found through a grid
/// of buckets over `positions`: each edge tests the vertices of the buckets
/// within `margin` of it (the farthest off an edge `on_edge` still calls on
/// it).
fn t_junctions(
    positions: &[[f64; 3]],
    margin: f64,
    edges: &[Edge],
    on_edge: &dyn Fn(u32, u32, u32) -> bool,
) -> Vec<MeshFault> {
    let mut undirected: Vec<(u32, u32)> = edges
        .iter()
        .map(|&((a, b), _)| (a.min(b), a.max(b)))
        .collect();
    undirected.sort_unstable();
    undirected.dedup();
    let shortest = undirected
        .iter()
        .map(|&(a, b)| length(sub(positions[b as usize], positions[a as usize])))
        .filter(|&l| l > 0.0)
        .fold(f64::INFINITY, f64::min);
    if !shortest.is_finite() {
        return Vec::new();
    }
    let budget = MAX_SEARCH_STEPS_PER_ELEMENT
        .saturating_mul((undirected.len() + positions.len()) as u64)
        .saturating_add(MIN_SEARCH_STEPS);
    // Buckets as small as the shortest edge keep few vertices in each; but
    // an edge thousands of times longer (a 65,535-step tower) walks
    // thousands of them. Double the bucket until the walks fit half the
    // budget. Each edge walks the buckets along it (`segment_buckets`), so
    // the walks grow with the edges' lengths, not their boxes' volumes (a
    // long diagonal across a tall wall once walked ~10⁵ buckets of its
    // box). The walks' length is counted before they start (saturating):
    // bounded, whatever the coordinates.
    let visits = |size: f64| {
        undirected
            .iter()
            .map(|&(a, b)| {
                segment_buckets::count(positions[a as usize], positions[b as usize], size)
            })
            .fold(0u128, u128::saturating_add)
    };
    let mut size = shortest;
    while visits(size) > u128::from(budget / 2) && (size * 2.0).is_finite() {
        size *= 2.0;
    }
    let bucket = |p: [f64; 3]| p.map(|c| (c / size).floor() as i64);
    let mut buckets: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for (v, &p) in positions.iter().enumerate() {
        buckets.entry(bucket(p)).or_default().push(v as u32);
    }
    let mut found = Vec::new();
    // Every bucket visited and every vertex tested is a step; past the
    // budget the mesh is reported instead of searched.
    let mut steps = 0u64;
    for &(a, b) in &undirected {
        let (p, q) = (positions[a as usize], positions[b as usize]);
        let walked = segment_buckets::walk(p, q, size, margin, |at| {
            let inside = buckets.get(&at).map_or(&[][..], Vec::as_slice);
            steps = steps.saturating_add(1 + inside.len() as u64);
            if steps > budget {
                return ControlFlow::Break(());
            }
            for &v in inside {
                if v != a && v != b && on_edge(v, a, b) {
                    found.push(MeshFault::TJunction {
                        vertex: v,
                        edge: [a, b],
                    });
                }
            }
            ControlFlow::Continue(())
        });
        if walked.is_break() {
            return vec![MeshFault::TooIrregular {
                search_steps: steps,
            }];
        }
    }
    found.sort_by_key(|f| match f {
        MeshFault::TJunction { vertex, edge } => (*vertex, *edge),
        _ => (0, [0, 0]),
    });
    found
}

/// The enclosed volume (divergence theorem; positive for outward normals).
pub fn volume(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .iter()
        .map(|t| {
            let [p, q, r] = t.map(|v| point(vertices[v as usize]));
            dot(p, cross(q, r)) / 6.0
        })
        .sum()
}

/// The volume a mesh of lattice points encloses, in whole numbers: `6·V`
/// is `base·slab + step·steps` cell areas (the divergence theorem with the
/// field `(0, 0, z)`: each triangle adds its signed area seen from above
/// times its mean height, and a height is `base + (level − 1)·step`). The
/// solid of a terrain is `6·(cells·base + Σh·step)`: compared term by term,
/// exactly, however long the grid (an `f32` sum drifted 1e-5 on a
/// 1×1,000,000 strip).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LatticeVolume {
    /// Six times the cell areas of slab (`base`) enclosed.
    pub slab: i128,
    /// Six times the cell areas of steps (`step_height`) enclosed.
    pub steps: i128,
}

impl LatticeVolume {
    /// The volume of the mesh `triangles` over `levels` (`[x, y, level]`
    /// per vertex, level 0 the ground, `L > 0` at `base + (L − 1)·step`).
    /// Sums stay far inside `i128`: a term is below 2^85, and a mesh has
    /// fewer than 2^32 triangles.
    ///
    /// # Panics
    /// If a triangle names a vertex `levels` does not have.
    pub fn of(levels: &[[u32; 3]], triangles: &[[u32; 3]]) -> Self {
        let mut volume = LatticeVolume { slab: 0, steps: 0 };
        for t in triangles {
            let [p, q, r] = t.map(|v| levels[v as usize].map(i128::from));
            let area2 = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
            let raised = [p, q, r].iter().filter(|c| c[2] > 0).count() as i128;
            let steps: i128 = [p, q, r].iter().map(|c| (c[2] - 1).max(0)).sum();
            volume.slab += area2 * raised;
            volume.steps += area2 * steps;
        }
        volume
    }

    /// The volume of the solid of `cells` raised cells whose heights sum
    /// to `steps` steps.
    pub fn of_solid(cells: u64, steps: u64) -> Self {
        LatticeVolume {
            slab: 6 * i128::from(cells),
            steps: 6 * i128::from(steps),
        }
    }

    /// The volume of a wedge over `cells` cells rising `rise` steps from
    /// its foot (on the slab when `slab`): a ramp's shell.
    pub fn of_wedge(cells: u64, slab: bool, rise: u32) -> Self {
        LatticeVolume {
            slab: 6 * i128::from(cells) * i128::from(slab),
            steps: 3 * i128::from(cells) * i128::from(rise),
        }
    }

    /// The sum of two volumes (a terrain's blocks and its ramps' wedges).
    #[must_use]
    pub fn plus(self, other: LatticeVolume) -> Self {
        LatticeVolume {
            slab: self.slab + other.slab,
            steps: self.steps + other.steps,
        }
    }

    /// Whether the two volumes are the same number of cubic metres for
    /// `units`, exactly: `base·Δslab + step·Δsteps = 0` with `base` and
    /// `step` as whole multiples of their binary unit, reduced by their
    /// greatest common divisor so nothing overflows.
    pub fn same_as(self, other: LatticeVolume, units: super::MeshUnits) -> bool {
        let (_, base, step) = units.height_unit();
        let (d_slab, d_steps) = (self.slab - other.slab, self.steps - other.steps);
        let g = gcd(base, step).max(1);
        let (base, step) = (base / g, step / g);
        // base·Δslab = −step·Δsteps with base, step coprime: Δslab = m·step
        // and Δsteps = −m·base for a whole m.
        if step == 0 {
            return d_slab == 0;
        }
        if d_slab % step != 0 {
            return false;
        }
        let m = d_slab / step;
        m.checked_mul(base).and_then(i128::checked_neg) == Some(d_steps)
    }

    /// In cubic metres, for cells of side `block_size`.
    pub fn cubic_metres(self, units: super::MeshUnits) -> f64 {
        let s = units.block_size;
        s * s * (units.base * self.slab as f64 + units.step_height * self.steps as f64) / 6.0
    }
}

/// The greatest common divisor of two whole numbers ≥ 0 (0 for two 0s).
fn gcd(mut a: i128, mut b: i128) -> i128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.abs()
}

/// `(min, max)` corners of the vertices' bounding box (`None` when empty).
pub fn bounding_box(vertices: &[[f32; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let first = point(*vertices.first()?);
    Some(vertices.iter().fold((first, first), |(lo, hi), &v| {
        (min3(lo, point(v)), max3(hi, point(v)))
    }))
}

fn extent(vertices: &[[f32; 3]]) -> f64 {
    bounding_box(vertices).map_or(0.0, |(lo, hi)| length(sub(hi, lo)))
}

fn point(p: [f32; 3]) -> [f64; 3] {
    p.map(f64::from)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn length(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn min3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])]
}

fn max3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube: 8 vertices, 12 outward triangles.
    fn cube() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let v = (0..8)
            .map(|i| [(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32])
            .collect();
        let t = vec![
            [0, 2, 1],
            [1, 2, 3], // bottom (z = 0), facing down
            [4, 5, 6],
            [5, 7, 6], // top
            [0, 1, 4],
            [1, 5, 4], // y = 0
            [2, 6, 3],
            [3, 6, 7], // y = 1
            [0, 4, 2],
            [2, 4, 6], // x = 0
            [1, 3, 5],
            [3, 7, 5], // x = 1
        ];
        (v, t)
    }

    #[test]
    fn non_finite_and_absurd_coordinates_are_faults_found_at_once() {
        // Once an endless loop: an infinite coordinate cast to a bucket.
        for bad in [f32::INFINITY, f32::NAN, f32::NEG_INFINITY] {
            let (mut v, t) = cube();
            v[3][0] = bad;
            assert_eq!(faults(&v, &t), [MeshFault::NonFinite { vertex: 3 }]);
        }
        // A finite but absurd vertex: buckets grow until the walk is short,
        // and the answer comes at once.
        let (mut v, t) = cube();
        v[7] = [1e30, 1.0, 1.0];
        let _ = faults(&v, &t);
        // Thousands of vertices crowded where thousands of edges pass: the
        // search gives up past its budget instead of testing every pair.
        let n = 6000u32;
        let mut v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        v.extend((0..n).map(|k| [0.5, 1e-3 * (k + 1) as f32, 0.0]));
        let t: Vec<[u32; 3]> = (2..n + 2).map(|k| [0, 1, k]).collect();
        assert!(
            faults(&v, &t)
                .iter()
                .any(|f| matches!(f, MeshFault::TooIrregular { .. }))
        );
    }

    #[test]
    fn a_cube_is_sound_with_volume_one() {
        let (v, t) = cube();
        assert_eq!(faults(&v, &t), []);
        assert!((volume(&v, &t) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_hole_is_found() {
        let (v, mut t) = cube();
        t.pop();
        assert!(
            faults(&v, &t)
                .iter()
                .any(|f| matches!(f, MeshFault::UnpairedEdge { .. }))
        );
    }

    #[test]
    fn a_flipped_triangle_is_found() {
        let (v, mut t) = cube();
        t[3].swap(0, 1);
        assert!(faults(&v, &t).iter().any(|f| matches!(
            f,
            MeshFault::UnpairedEdge { uses: 2, .. }
                | MeshFault::UnpairedEdge {
                    reverse_uses: 2,
                    ..
                }
        )));
    }

    #[test]
    fn a_t_junction_is_found() {
        // Split the top's edge 4–5 at its midpoint on one side only.
        let (mut v, mut t) = cube();
        v.push([0.5, 0.0, 1.0]);
        let mid = 8;
        t.retain(|&tri| tri != [4, 5, 6]);
        t.extend([[4, mid, 6], [mid, 5, 6]]);
        let found = faults(&v, &t);
        assert!(
            found.contains(&MeshFault::TJunction {
                vertex: mid,
                edge: [4, 5]
            }),
            "{found:?}"
        );
    }

    /// `vertices` as lattice points (whole numbers) and their positions.
    fn on_lattice(v: &[[f32; 3]]) -> (Vec<[i128; 3]>, Vec<[f64; 3]>) {
        let points: Vec<[i128; 3]> = v.iter().map(|p| p.map(|c| c as i128)).collect();
        let positions = v.iter().map(|&p| point(p)).collect();
        (points, positions)
    }

    #[test]
    fn on_the_lattice_a_t_junction_and_a_flat_triangle_are_found_exactly() {
        // The cube doubled (its top's edge 4–5 from x = 0 to 2), split at x = 1.
        let (mut v, mut t) = cube();
        for p in &mut v {
            *p = p.map(|c| c * 2.0);
        }
        v.push([1.0, 0.0, 2.0]);
        t.retain(|&tri| tri != [4, 5, 6]);
        t.extend([[4, 8, 6], [8, 5, 6]]);
        let (points, positions) = on_lattice(&v);
        let found = lattice_faults(&points, &positions, &t);
        assert!(
            found.contains(&MeshFault::TJunction {
                vertex: 8,
                edge: [4, 5]
            }),
            "{found:?}"
        );
        let (v, mut t) = cube();
        t.push([0, 1, 1]);
        let (points, positions) = on_lattice(&v);
        assert!(
            lattice_faults(&points, &positions, &t)
                .contains(&MeshFault::Degenerate { triangle: 12 })
        );
        let (v, t) = cube();
        let (points, positions) = on_lattice(&v);
        assert_eq!(lattice_faults(&points, &positions, &t), []);
    }

    #[test]
    fn two_cubes_sharing_a_corner_vertex_are_pinched() {
        // A second cube at (1,1,1)..(2,2,2) whose corner 0 is the first's corner 7.
        let (mut v, mut t) = cube();
        let (v2, t2) = cube();
        let offset = v.len() as u32;
        v.extend(v2.iter().map(|p| p.map(|c| c + 1.0)));
        t.extend(
            t2.iter()
                .map(|tri| tri.map(|i| if i == 0 { 7 } else { i + offset })),
        );
        assert_eq!(
            faults(&v, &t),
            [MeshFault::PinchedVertex { vertex: 7, fans: 2 }]
        );
        // With its own copy of that corner it is two sound cubes.
        let (mut v, mut t) = cube();
        v.extend(v2.iter().map(|p| p.map(|c| c + 1.0)));
        t.extend(t2.iter().map(|tri| tri.map(|i| i + offset)));
        assert_eq!(faults(&v, &t), []);
    }

    #[test]
    fn many_tetrahedra_sharing_one_vertex_are_one_pinch_found_in_n_log_n() {
        // A forged OBJ's shape: closed tetrahedra whose apex is vertex 0.
        // Each fan of vertex 0 was looked up in a list of all its fans
        // (312,799 tetrahedra: 34 s in release; these 100,000 would take
        // minutes in a debug test); sorted, it takes a moment. (The
        // T-junction search after it has a budget of its own, tested below.)
        let tetrahedra = 100_000u32;
        let mut t = Vec::new();
        for i in 0..tetrahedra {
            let [a, b, c] = [1, 2, 3].map(|k| 3 * i + k);
            t.extend([[0, b, a], [0, a, c], [0, c, b], [a, b, c]]);
        }
        assert_eq!(
            pinched_vertices(&t, &directed_edges(&t)),
            [MeshFault::PinchedVertex {
                vertex: 0,
                fans: tetrahedra as usize
            }]
        );
    }

    #[test]
    fn a_degenerate_triangle_is_found() {
        let (mut v, mut t) = cube();
        v.push([0.5, 0.0, 0.0]);
        t.push([0, 8, 1]);
        assert!(faults(&v, &t).contains(&MeshFault::Degenerate { triangle: 12 }));
    }
}
