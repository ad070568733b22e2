//! The single mesh of a world (docs/meshes.md): the closed solid under the heightmap.

mod boxes;
mod cover;
mod faces;
pub mod invariants;
pub mod naive;
mod staircase;
mod stitch;
mod weld;

pub use boxes::{Block, boxes};
pub use faces::Normal;

use faces::LatticePoint;

use crate::heightmap::Heightmap;
use crate::terrain::Terrain;

/// A triangle mesh as plain buffers, in the grid frame (metres, Z up, origin
/// at the outer corner of cell (0, 0)). Triangles are counter-clockwise seen
/// from outside; every edge is used by exactly two triangles, in opposite
/// directions.
#[derive(Debug, Clone, PartialEq)]
pub struct TriMesh {
    vertices: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    normals: Vec<Normal>,
}

impl TriMesh {
    /// Vertex positions in metres.
    pub fn vertices(&self) -> &[[f32; 3]] {
        &self.vertices
    }

    /// Vertex indices of each triangle.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The outward normal of each triangle (all faces are axis-aligned).
    pub fn face_normals(&self) -> &[Normal] {
        &self.normals
    }

    /// `true` for the mesh of an empty solid.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }
}

/// Lengths that place the lattice in space, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshUnits {
    /// Cell side, metres: the lattice's x and y unit.
    pub block_size: f64,
    /// Step height, metres: the lattice's level unit.
    pub step_height: f64,
    /// Slab under the grid (0: none).
    pub base: f64,
}

impl MeshUnits {
    /// The height in metres of a lattice level: 0 is the ground, `h + 1`
    /// the top of a cell of `h` steps.
    pub(crate) fn z(self, level: u32) -> f64 {
        if level == 0 {
            0.0
        } else {
            self.base + f64::from(level - 1) * self.step_height
        }
    }
}

impl Terrain {
    /// The lengths of this terrain's lattice.
    pub fn mesh_units(&self) -> MeshUnits {
        MeshUnits {
            block_size: self.block_size(),
            step_height: self.step_height(),
            base: self.base(),
        }
    }

    /// The single mesh of this terrain (docs/meshes.md).
    pub fn mesh(&self) -> TriMesh {
        build_mesh(self.heightmap(), self.mesh_units())
    }

    /// The block model of this terrain: boxes whose union is the solid.
    pub fn boxes(&self) -> Vec<Block> {
        boxes(self.heightmap(), self.mesh_units())
    }
}

/// The closed mesh of the solid `{0 ≤ z ≤ base + h·step}` over every cell.
pub fn build_mesh(heights: &Heightmap, units: MeshUnits) -> TriMesh {
    let levels = faces::Levels::new(heights, units.base > 0.0);
    let triangles = stitch::triangulate(&levels, |emit| faces::faces(&levels, emit));
    let (keys, ids, normals) = weld::split_saddles(triangles, &levels);
    let position = |[x, y, level]: LatticePoint| {
        [
            (f64::from(x) * units.block_size) as f32,
            (f64::from(y) * units.block_size) as f32,
            units.z(level) as f32,
        ]
    };
    TriMesh {
        vertices: keys.into_iter().map(position).collect(),
        triangles: ids,
        normals,
    }
}
