//! glTF 2.0 binary (GLB): one mesh, Y up as glTF requires (our Z up becomes
//! Y, our Y becomes −Z), vertex colours by height in the preview's palette.
//! No normals are written: glTF viewers then shade faces flat, which is what
//! a step field is.

use serde_json::json;

use crate::mesh::TriMesh;
use crate::preview::palette;

/// The GLB bytes of `mesh`.
///
/// # Panics
/// If the mesh has 2³² vertices or more, which no valid grid yields.
pub fn glb(mesh: &TriMesh) -> Vec<u8> {
    let vertices = mesh.vertices();
    let mut bin = Vec::new();
    let mut json = json!({
        "asset": { "version": "2.0", "generator": format!("rse {}", crate::VERSION) },
        "scene": 0,
        "scenes": [{ "nodes": [] }],
    });
    if !mesh.is_empty() {
        let (lo_z, hi_z) = vertices
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v[2]), hi.max(v[2]))
            });
        let to_y_up = |[x, y, z]: [f32; 3]| [x, z, -y];
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for &v in vertices {
            let p = to_y_up(v);
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
                bin.extend_from_slice(&p[k].to_le_bytes());
            }
        }
        let positions_len = bin.len();
        // Heights mapped to 0..=1000 so the palette's integer maths applies.
        let span = hi_z - lo_z;
        for v in vertices {
            let t = if span > 0.0 {
                ((v[2] - lo_z) / span * 1000.0).round() as u16
            } else {
                0
            };
            let [r, g, b] = palette(t, 0, 1000);
            bin.extend_from_slice(&[r, g, b, 255]);
        }
        let colours_len = bin.len() - positions_len;
        for t in mesh.triangles() {
            for v in t {
                bin.extend_from_slice(&v.to_le_bytes());
            }
        }
        let indices_len = bin.len() - positions_len - colours_len;
        json["scenes"][0]["nodes"] = json!([0]);
        json["nodes"] = json!([{ "mesh": 0, "name": "terrain" }]);
        json["meshes"] = json!([{
            "name": "terrain",
            "primitives": [{ "attributes": { "POSITION": 0, "COLOR_0": 1 }, "indices": 2, "mode": 4 }],
        }]);
        json["buffers"] = json!([{ "byteLength": bin.len() }]);
        json["bufferViews"] = json!([
            { "buffer": 0, "byteOffset": 0, "byteLength": positions_len, "target": 34962 },
            { "buffer": 0, "byteOffset": positions_len, "byteLength": colours_len, "target": 34962 },
            { "buffer": 0, "byteOffset": positions_len + colours_len, "byteLength": indices_len, "target": 34963 },
        ]);
        json["accessors"] = json!([
            { "bufferView": 0, "componentType": 5126, "count": vertices.len(), "type": "VEC3", "min": min, "max": max },
            { "bufferView": 1, "componentType": 5121, "normalized": true, "count": vertices.len(), "type": "VEC4" },
            { "bufferView": 2, "componentType": 5125, "count": mesh.triangles().len() * 3, "type": "SCALAR" },
        ]);
    }
    let mut json = serde_json::to_vec(&json).expect("a JSON value serialises");
    json.resize(json.len().next_multiple_of(4), b' ');
    bin.resize(bin.len().next_multiple_of(4), 0);

    let chunk = |kind: &[u8; 4], data: &[u8], out: &mut Vec<u8>| {
        out.extend_from_slice(&(data.len() as u32).to_le_bytes());
        out.extend_from_slice(kind);
        out.extend_from_slice(data);
    };
    let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    chunk(b"JSON", &json, &mut out);
    if !bin.is_empty() {
        chunk(b"BIN\0", &bin, &mut out);
    }
    out
}
