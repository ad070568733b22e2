//! Wavefront OBJ: `v` positions, the six axis normals as `vn` (then each
//! ramp plane's), faces as `f v//vn` (Gazebo's loader drops a mesh without
//! normals), and a material.

use std::fmt::Write as _;

use super::text::{CoordinateText, push_int};
use crate::mesh::{Normal, TriMesh};

/// The material name used by [`obj`] and defined by [`mtl`](super::mtl).
pub const MATERIAL: &str = "rse_terrain";

const FMT: &str = "writing to a String cannot fail";

/// The OBJ text of `mesh`; `mtl_file` is the material library it names
/// (written beside it by the caller), or `None` for no material.
///
/// # Panics
/// Never: formatting into a `String` cannot fail.
pub fn obj(mesh: &TriMesh, mtl_file: Option<&str>) -> String {
    // A corner's normal reference, `//1` to `//6`, written as one piece.
    const NORMAL_REFS: [&str; 6] = ["//1", "//2", "//3", "//4", "//5", "//6"];
    let mut out = String::with_capacity(mesh.vertices().len() * 24 + mesh.triangles().len() * 24);
    writeln!(
        out,
        "# rse {} terrain: {} vertices, {} triangles, metres, Z up",
        crate::VERSION,
        mesh.vertices().len(),
        mesh.triangles().len()
    )
    .expect(FMT);
    if let Some(file) = mtl_file {
        writeln!(out, "mtllib {file}").expect(FMT);
    }
    out.push_str("o terrain\n");
    let coordinates = CoordinateText::new(mesh.vertices());
    for &point in mesh.vertices() {
        out.push_str("v ");
        coordinates.push_point(&mut out, point, " ");
        out.push('\n');
    }
    // The six axis normals, then each tilted one in the order of its
    // first face: a mesh without ramps writes what it always did.
    let mut normals: Vec<Normal> = Normal::ALL.to_vec();
    for normal in mesh.face_normals() {
        if !normals.contains(normal) {
            normals.push(*normal);
        }
    }
    for normal in &normals {
        let [x, y, z] = normal.vector();
        writeln!(out, "vn {x} {y} {z}").expect(FMT);
    }
    if mtl_file.is_some() {
        writeln!(out, "usemtl {MATERIAL}").expect(FMT);
    }
    for (t, normal) in mesh.triangles().iter().zip(mesh.face_normals()) {
        let n = normals
            .iter()
            .position(|m| m == normal)
            .expect("every face's normal is listed");
        out.push('f');
        for v in t {
            out.push(' ');
            push_int(&mut out, v + 1);
            if let Some(text) = NORMAL_REFS.get(n) {
                out.push_str(text);
            } else {
                out.push_str("//");
                push_int(&mut out, n as u32 + 1);
            }
        }
        out.push('\n');
    }
    out
}
