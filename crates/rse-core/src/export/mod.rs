//! Writing meshes to the files simulators load: OBJ (+ MTL), binary STL,
//! GLB, and USD ASCII.
//!
//! Writers build bytes in memory; where they go is the caller's business.

mod glb;
mod look;
mod obj;
mod stl;
mod text;
mod usda;

pub use glb::glb;
pub use look::mtl;
pub use obj::{MATERIAL, obj};
pub use stl::stl;
pub use usda::usda;

/// A mesh file format, chosen by file suffix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ with `vn` normals and an MTL material.
    Obj,
    /// Binary STL.
    Stl,
    /// glTF 2.0 binary, Y up, vertex colours by height.
    Glb,
}

impl MeshFormat {
    /// The format for a path's suffix (`.obj`, `.stl`, `.glb`, any case).
    pub fn from_path(path: &std::path::Path) -> Option<Self> {
        let suffix = path.extension()?.to_str()?.to_ascii_lowercase();
        match suffix.as_str() {
            "obj" => Some(MeshFormat::Obj),
            "stl" => Some(MeshFormat::Stl),
            "glb" => Some(MeshFormat::Glb),
            _ => None,
        }
    }
}
