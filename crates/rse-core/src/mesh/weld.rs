//! From triangles of lattice points to an index mesh in which every edge is
//! used by exactly two faces, in opposite directions.
//!
//! Where two cells touch only along a vertical corner line (a saddle: the
//! diagonal cells higher than the other two), four walls meet at that line.
//! Their triangles are paired by the solid quadrant they bound, and the
//! corners of triangles that are joined across an edge are welded into one
//! vertex (union–find); so the line is there twice, once for each cell.

use super::TriMesh;
use super::faces::{Key, Normal};
use super::stitch::Triangle;

/// Welds `triangles` into a mesh; `position` places a lattice point in metres.
pub(crate) fn weld(triangles: &[Triangle], position: impl Fn(Key) -> [f32; 3]) -> TriMesh {
    // Number the distinct lattice points.
    let mut keys: Vec<Key> = triangles.iter().flat_map(|t| t.corners).collect();
    keys.sort_unstable();
    keys.dedup();
    let id = |k: &Key| keys.binary_search(k).expect("every corner is a key") as u32;
    let faces: Vec<[u32; 3]> = triangles
        .iter()
        .map(|t| t.corners.map(|k| id(&k)))
        .collect();

    // Every edge, undirected, with the triangle and slot that use it.
    let mut edges: Vec<EdgeUse> = Vec::with_capacity(faces.len() * 3);
    for (f, face) in faces.iter().enumerate() {
        for slot in 0..3 {
            let (a, b) = (face[slot], face[(slot + 1) % 3]);
            edges.push(EdgeUse {
                lo: a.min(b),
                hi: a.max(b),
                forward: a < b,
                face: f as u32,
                slot: slot as u8,
            });
        }
    }
    edges.sort_unstable_by_key(|e| (e.lo, e.hi, e.face, e.slot));

    let mut corners = UnionFind::new(faces.len() * 3);
    let mut start = 0;
    while start < edges.len() {
        let mut end = start + 1;
        while end < edges.len()
            && (edges[end].lo, edges[end].hi) == (edges[start].lo, edges[start].hi)
        {
            end += 1;
        }
        let group = &edges[start..end];
        let (forward, backward): (Vec<&EdgeUse>, Vec<&EdgeUse>) =
            group.iter().partition(|e| e.forward);
        assert!(
            forward.len() == backward.len() && (forward.len() == 1 || forward.len() == 2),
            "mesh builder bug: an edge used {} times forward and {} backward",
            forward.len(),
            backward.len()
        );
        for f in &forward {
            let g = if forward.len() == 1 {
                backward[0]
            } else {
                let quadrant = quadrant(triangles, &keys, f);
                *backward
                    .iter()
                    .find(|g| super::weld::quadrant(triangles, &keys, g) == quadrant)
                    .expect("mesh builder bug: saddle walls do not pair by quadrant")
            };
            // f runs a→b at its slot, g runs b→a: weld the a's and the b's.
            let fc = |k: u8| f.face as usize * 3 + usize::from(k % 3);
            let gc = |k: u8| g.face as usize * 3 + usize::from(k % 3);
            corners.union(fc(f.slot), gc(g.slot + 1));
            corners.union(fc(f.slot + 1), gc(g.slot));
        }
        start = end;
    }

    // One vertex per class of welded corners, numbered in order of first use.
    let mut vertex_of_class = vec![u32::MAX; faces.len() * 3];
    let mut vertices = Vec::new();
    let mut out_faces = Vec::with_capacity(faces.len());
    for (f, face) in faces.iter().enumerate() {
        let mut out = [0u32; 3];
        for slot in 0..3 {
            let class = corners.find(f * 3 + slot);
            if vertex_of_class[class] == u32::MAX {
                vertex_of_class[class] = vertices.len() as u32;
                vertices.push(position(keys[face[slot] as usize]));
            }
            out[slot] = vertex_of_class[class];
        }
        out_faces.push(out);
    }
    TriMesh {
        vertices,
        triangles: out_faces,
        normals: triangles.iter().map(|t| t.normal).collect(),
    }
}

#[derive(Clone, Copy)]
struct EdgeUse {
    lo: u32,
    hi: u32,
    forward: bool,
    face: u32,
    slot: u8,
}

/// For a wall triangle at a vertical corner line: the quadrant (signs of x
/// and y around the line) of the solid it bounds.
fn quadrant(triangles: &[Triangle], keys: &[Key], edge: &EdgeUse) -> (i8, i8) {
    let t = &triangles[edge.face as usize];
    let line = keys[edge.lo as usize];
    let third = t.corners[(usize::from(edge.slot) + 2) % 3];
    let side = |a: u32, b: u32| if a > b { 1 } else { -1 };
    match t.normal {
        // Solid lies behind the outward normal.
        Normal::PosX => (-1, side(third[1], line[1])),
        Normal::NegX => (1, side(third[1], line[1])),
        Normal::PosY => (side(third[0], line[0]), -1),
        Normal::NegY => (side(third[0], line[0]), 1),
        Normal::PosZ | Normal::NegZ => unreachable!("horizontal faces never meet at a saddle"),
    }
}

/// Disjoint sets over `0..n`, with path halving.
struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n as u32).collect(),
        }
    }

    fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] as usize != x {
            let grand = self.parent[self.parent[x] as usize];
            self.parent[x] = grand;
            x = grand as usize;
        }
        x
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        // The smaller root wins, so the result does not depend on call order.
        if a < b {
            self.parent[b] = a as u32;
        } else {
            self.parent[a] = b as u32;
        }
    }
}
