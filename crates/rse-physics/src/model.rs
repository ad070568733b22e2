//! The terrain as the physics engine gets it: one static mesh or a set of
//! static boxes, read from a world's files or made from its terrain.

use rse_core::Terrain;

use crate::report::ColliderKind;

/// The terrain as the simulator gets it.
#[derive(Debug, Clone)]
pub enum TerrainModel {
    /// One static triangle mesh (metres, grid frame).
    Mesh {
        /// Vertex positions.
        vertices: Vec<[f32; 3]>,
        /// Triangles, counter-clockwise from outside.
        triangles: Vec<[u32; 3]>,
    },
    /// Static boxes: `(centre, half size)` in metres.
    Boxes(Vec<([f64; 3], [f64; 3])>),
}

impl TerrainModel {
    /// Mesh or boxes.
    pub fn kind(&self) -> ColliderKind {
        match self {
            TerrainModel::Mesh { .. } => ColliderKind::Mesh,
            TerrainModel::Boxes(_) => ColliderKind::Boxes,
        }
    }

    /// The single mesh of `terrain`.
    pub fn mesh_of(terrain: &Terrain) -> Self {
        let mesh = terrain.mesh();
        TerrainModel::Mesh {
            vertices: mesh.vertices().to_vec(),
            triangles: mesh.triangles().to_vec(),
        }
    }

    /// `true` for a terrain with nothing in it.
    pub fn is_empty(&self) -> bool {
        match self {
            TerrainModel::Mesh { triangles, .. } => triangles.is_empty(),
            TerrainModel::Boxes(boxes) => boxes.is_empty(),
        }
    }

    /// The box set of `terrain`.
    pub fn boxes_of(terrain: &Terrain) -> Self {
        TerrainModel::Boxes(
            terrain
                .boxes()
                .iter()
                .map(|b| (b.center, b.half_size))
                .collect(),
        )
    }
}
