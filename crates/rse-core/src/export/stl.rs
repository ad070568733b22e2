//! Binary STL: an 80-byte header, the triangle count, then per triangle its
//! normal, three corners (little-endian `f32`) and a zero attribute.

use crate::mesh::TriMesh;

/// The binary STL bytes of `mesh`.
///
/// # Panics
/// If the mesh has 2³² triangles or more, which STL cannot count.
pub fn stl(mesh: &TriMesh) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * mesh.triangles().len());
    let mut header = format!("rse {} terrain, metres, Z up", crate::VERSION).into_bytes();
    header.resize(80, b' ');
    out.extend_from_slice(&header);
    let count =
        u32::try_from(mesh.triangles().len()).expect("meshes have fewer than 2^32 triangles");
    out.extend_from_slice(&count.to_le_bytes());
    for (t, normal) in mesh.triangles().iter().zip(mesh.face_normals()) {
        let corners = t.map(|v| mesh.vertices()[v as usize]);
        for value in normal.vector().iter().chain(corners.iter().flatten()) {
            out.extend_from_slice(&value.to_le_bytes());
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}
