//! USD ASCII (`.usda`): one layer whose default prim is the terrain mesh,
//! Z up, metres, a static collider of its own (`PhysicsCollisionAPI`, and
//! `PhysicsMeshCollisionAPI` with approximation `none`: the exact
//! triangles, not a convex hull). So the file is a whole asset: Isaac
//! Lab's `TerrainImporterCfg(terrain_type="usd")` and Isaac Sim's
//! drag-and-drop reference it alone and collide with it.

use std::fmt::Write as _;

use super::text::{CoordinateText, push_int};
use crate::Globals;
use crate::mesh::TriMesh;
use crate::mesh::invariants::bounding_box;

const FMT: &str = "writing to a String cannot fail";

/// The `.usda` text of a layer holding `mesh` as the `Mesh` prim `terrain`,
/// displayed as the scheme's globals say (`look`).
///
/// # Panics
/// Never: formatting into a `String` cannot fail.
pub fn usda(mesh: &TriMesh, globals: &Globals) -> String {
    let mut out = String::with_capacity(mesh.vertices().len() * 32 + mesh.triangles().len() * 24);
    writeln!(
        out,
        "#usda 1.0\n(\n    defaultPrim = \"terrain\"\n    doc = \"rse {} terrain: {} vertices, {} triangles\"\n    metersPerUnit = 1\n    upAxis = \"Z\"\n)\n",
        crate::VERSION,
        mesh.vertices().len(),
        mesh.triangles().len()
    )
    .expect(FMT);
    out.push_str(
        "def Mesh \"terrain\" (\n    prepend apiSchemas = [\"PhysicsCollisionAPI\", \"PhysicsMeshCollisionAPI\"]\n)\n{\n    uniform token physics:approximation = \"none\"\n",
    );
    if let Some((lo, hi)) = bounding_box(mesh.vertices()) {
        // The box of f32 points, exactly: back to f32 before printing.
        let [lo, hi] = [lo, hi].map(|p| p.map(|c| c as f32));
        writeln!(
            out,
            "    float3[] extent = [({}, {}, {}), ({}, {}, {})]",
            lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
        )
        .expect(FMT);
    }
    out.push_str("    int[] faceVertexCounts = [");
    for i in 0..mesh.triangles().len() {
        out.push_str(if i == 0 { "3" } else { ", 3" });
    }
    out.push_str("]\n    int[] faceVertexIndices = [");
    for (i, &v) in mesh.triangles().iter().flatten().enumerate() {
        out.push_str(separator(i));
        push_int(&mut out, v);
    }
    out.push_str("]\n    uniform token orientation = \"rightHanded\"\n    point3f[] points = [");
    let coordinates = CoordinateText::new(mesh.vertices());
    for (i, &point) in mesh.vertices().iter().enumerate() {
        out.push_str(separator(i));
        out.push('(');
        coordinates.push_point(&mut out, point, ", ");
        out.push(')');
    }
    out.push_str("]\n");
    out.push_str(&super::look::usd_display(globals));
    out.push_str("    uniform token subdivisionScheme = \"none\"\n}\n");
    out
}

/// What goes before item `i` of a list.
fn separator(i: usize) -> &'static str {
    if i == 0 { "" } else { ", " }
}
