//! A world's terrain files against the terrain regenerated from its
//! manifest: the heightmap cell by cell, and every OBJ re-read against
//! docs/meshes.md and the heightmap (closed, exact, volume, bounding box, tops).

use rse_core::mesh::invariants::lattice_faults;
use rse_core::mesh::{LatticeVolume, MeshUnits};
use rse_core::{Heightmap, HeightmapCsvError, Terrain};

use crate::fault::FaultKind;
use crate::limits::MAX_OBJ_OBJECTS;

/// Why `heightmap.csv` (its `bytes`) is not `terrain`'s heightmap; `None`
/// when it is, or when it differs only in format (the byte comparison
/// reports that).
pub fn heightmap_fault(bytes: &[u8], terrain: &Terrain) -> Option<FaultKind> {
    let bad = |reason: String| Some(FaultKind::BadHeightmap { reason });
    let Ok(text) = std::str::from_utf8(bytes) else {
        return Some(FaultKind::NotText);
    };
    let map = match Heightmap::from_csv(text) {
        Ok(map) => map,
        // Where, not what: a value that is no height may be anyone's text.
        Err(HeightmapCsvError::NotAHeight { line, column, .. }) => {
            return bad(format!(
                "line {line}, column {column} is not a height in steps"
            ));
        }
        Err(e) => return bad(e.to_string()),
    };
    let want = terrain.heightmap();
    if (map.nx(), map.ny()) != (want.nx(), want.ny()) {
        return bad(format!(
            "{}x{} cells, but the world regenerated from rse.json has {}x{}",
            map.nx(),
            map.ny(),
            want.nx(),
            want.ny()
        ));
    }
    let i = map
        .cells()
        .iter()
        .zip(want.cells())
        .position(|(a, b)| a != b)?;
    let (x, y) = (i as u32 % map.nx(), i as u32 / map.nx());
    Some(FaultKind::HeightDiffers {
        x,
        y,
        found: map.get(x, y),
        expected: want.get(x, y),
    })
}

/// A mesh read from an OBJ file.
#[derive(Debug, Clone)]
pub struct ObjMesh {
    /// Vertex positions, every coordinate finite.
    pub vertices: Vec<[f32; 3]>,
    /// Triangles, every index a vertex of `vertices`.
    pub triangles: Vec<[u32; 3]>,
}

/// Whether every index of a face, line or point statement (`line`) is
/// one tobj can resolve without overflow: never 0, a relative one (from
/// -1 back) within the elements defined before it (`defined`: vertices,
/// texture coordinates, normals), a positive one whose offset (three
/// floats an element) fits. tobj turns any other into a number whose
/// offset overflows (a panic where overflow is checked: hostile input
/// must not abort); a positive index past the file, or one that is not a
/// number, is tobj's to refuse.
fn references_defined(line: &[u8], defined: &[usize; 3]) -> Result<(), String> {
    let words = line
        .split(u8::is_ascii_whitespace)
        .filter(|w| !w.is_empty());
    for word in words.skip(1) {
        for (kind, part) in word.split(|&b| b == b'/').enumerate().take(3) {
            let Some(index) = std::str::from_utf8(part)
                .ok()
                .and_then(|t| t.parse::<i64>().ok())
            else {
                continue;
            };
            let n = defined[kind] as i64;
            let offset_fits = usize::try_from(index - 1)
                .ok()
                .and_then(|i| i.checked_mul(3)?.checked_add(2))
                .is_some();
            if index == 0 || index < -n || (index > 0 && !offset_fits) {
                let name = ["vertex", "texture coordinate", "normal"][kind];
                return Err(format!(
                    "a statement names {name} {index}, but {n} are defined before it"
                ));
            }
        }
    }
    Ok(())
}

/// Reads an OBJ file's positions and triangles (normals and materials are
/// the readers' business). Refuses what a simulator could not use: faces
/// that are not triangles, indices that name no vertex, coordinates that
/// are not finite numbers.
pub fn read_obj(bytes: &[u8]) -> Result<ObjMesh, FaultKind> {
    let bad = |reason: String| FaultKind::BadObj { reason };
    // tobj skips lines it does not know: garbage would read as an empty
    // mesh. Every line must be one of the statements of a polygon OBJ.
    // tobj also makes a model of every `o`/`g` line, each with its own
    // buffers: a file of nothing else costs tens of times its size, so
    // there may be few (ours have one).
    let mut objects = 0usize;
    // Vertices, texture coordinates and normals defined so far.
    let mut defined = [0usize; 3];
    for (i, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let keyword = line
            .split(u8::is_ascii_whitespace)
            .find(|w| !w.is_empty())
            .unwrap_or_default();
        let known = [
            &b"v"[..],
            b"vn",
            b"vt",
            b"f",
            b"o",
            b"g",
            b"s",
            b"usemtl",
            b"mtllib",
            b"l",
            b"p",
        ]
        .contains(&keyword);
        if keyword == b"o" || keyword == b"g" {
            objects += 1;
            if objects > MAX_OBJ_OBJECTS {
                return Err(bad(format!(
                    "line {}: more than {MAX_OBJ_OBJECTS} objects and groups (ours have one)",
                    i + 1
                )));
            }
        }
        match keyword {
            b"v" => defined[0] += 1,
            b"vt" => defined[1] += 1,
            b"vn" => defined[2] += 1,
            b"f" | b"l" | b"p" => {
                references_defined(line, &defined)
                    .map_err(|r| bad(format!("line {}: {r}", i + 1)))?;
            }
            _ => {}
        }
        if !(keyword.is_empty() || keyword.starts_with(b"#") || known) {
            // Not quoted: a line that is no OBJ may be anyone's text.
            return Err(bad(format!("line {} is not an OBJ statement", i + 1)));
        }
    }
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ..tobj::LoadOptions::default()
    };
    let (models, _) = tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, |_| {
        Ok((Vec::new(), std::collections::HashMap::default()))
    })
    .map_err(|e| bad(e.to_string()))?;
    let mut mesh = ObjMesh {
        vertices: Vec::new(),
        triangles: Vec::new(),
    };
    for model in models {
        let m = model.mesh;
        if m.face_arities.iter().any(|&n| n != 3) {
            return Err(bad("has faces that are not triangles".to_owned()));
        }
        let first = mesh.vertices.len() as u32;
        let count = (m.positions.len() / 3) as u32;
        if let Some(i) = m.positions.iter().position(|c| !c.is_finite()) {
            return Err(bad(format!(
                "vertex {} has a coordinate that is not a finite number",
                mesh.vertices.len() + i / 3 + 1
            )));
        }
        mesh.vertices
            .extend(m.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        for t in m.indices.chunks_exact(3) {
            if t.iter().any(|&i| i >= count) {
                return Err(bad(format!(
                    "a face names vertex {}, but there are {count}",
                    t.iter().max().map_or(0, |&i| u64::from(i) + 1)
                )));
            }
            mesh.triangles
                .push([first + t[0], first + t[1], first + t[2]]);
        }
    }
    Ok(mesh)
}

/// Faults of `mesh` as the mesh of `terrain`: docs/meshes.md first; then, for a
/// sound mesh, volume, bounding box and top heights. Every vertex of the
/// terrain's mesh is a lattice point rounded to `f32`: mapped back, each
/// of these is decided exactly, in whole numbers (a true corner a few
/// microns off a long, thin wall triangle's edge is a corner, not a
/// T-junction as an `f32` tolerance took it to be; a volume summed from
/// `f32` vertices drifted past its tolerance on a 1×1,000,000 strip).
pub fn mesh_faults_against(mesh: &ObjMesh, terrain: &Terrain) -> Vec<FaultKind> {
    let units = terrain.mesh_units();
    let mut levels = Vec::with_capacity(mesh.vertices.len());
    for (i, &v) in mesh.vertices.iter().enumerate() {
        let Some(level) = units.snap_level(v) else {
            return vec![FaultKind::BadMesh {
                faults: 1,
                first: format!(
                    "vertex {} at ({}, {}, {}) is not a corner of the terrain's cells",
                    i + 1,
                    v[0],
                    v[1],
                    v[2]
                ),
            }];
        };
        levels.push(level);
    }
    let points: Vec<[i128; 3]> = levels.iter().map(|&p| units.lattice_point(p)).collect();
    let positions: Vec<[f64; 3]> = points.iter().map(|&p| units.position(p)).collect();
    let broken = lattice_faults(&points, &positions, &mesh.triangles);
    if let Some(first) = broken.first() {
        return vec![FaultKind::BadMesh {
            faults: broken.len(),
            first: first.to_string(),
        }];
    }
    let mut faults = Vec::new();
    let map = terrain.heightmap();
    let top = |x: u32, y: u32| units.top_level(map.get(x, y));
    let solid: Vec<(u32, u32)> = (0..map.ny())
        .flat_map(|y| (0..map.nx()).map(move |x| (x, y)))
        .filter(|&(x, y)| top(x, y) > 0)
        .collect();
    let expected = terrain.lattice_volume();
    let measured = LatticeVolume::of(&levels, &mesh.triangles);
    if !measured.same_as(expected, units) {
        faults.push(FaultKind::VolumeDiffers {
            measured: measured.cubic_metres(units),
            expected: expected.cubic_metres(units),
        });
    }
    if let Some(fault) = bounds_fault(&levels, &solid, &top, terrain.ramps(), units) {
        faults.push(fault);
        return faults; // tops beyond the grid would be looked up off the map
    }
    // Every upward face lies on the top of the cells under it: a level
    // above the ground, seen counter-clockwise from above, over the cell
    // of its centroid (corners are whole cells: the centroid's cell is
    // their sum divided by 3, rounded down).
    for t in &mesh.triangles {
        let [p, q, r] = t.map(|i| levels[i as usize].map(i64::from));
        let up = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
        if up <= 0 || p[2] != q[2] || q[2] != r[2] || p[2] == 0 {
            continue;
        }
        let (x, y) = (
            ((p[0] + q[0] + r[0]) / 3) as u32,
            ((p[1] + q[1] + r[1]) / 3) as u32,
        );
        // Within the bounding box just checked: on the map.
        let (x, y) = (x.min(map.nx() - 1), y.min(map.ny() - 1));
        if p[2] != i64::from(top(x, y)) {
            faults.push(FaultKind::TopMisplaced {
                x,
                y,
                z: units.z(p[2] as u32),
                top: units.z(top(x, y)),
            });
            break;
        }
    }
    faults
}

/// The fault of a mesh (`levels`, one per vertex) whose bounding box is not
/// that of the `solid` cells (their tops by `top`) and the wedges of
/// `ramps`, decided in lattice units; `None` when they agree.
fn bounds_fault(
    levels: &[[u32; 3]],
    solid: &[(u32, u32)],
    top: &dyn Fn(u32, u32) -> u32,
    ramps: &[rse_core::Ramp],
    units: MeshUnits,
) -> Option<FaultKind> {
    let grow = |acc: Option<[[u32; 3]; 2]>, lo: [u32; 3], hi: [u32; 3]| {
        Some(match acc {
            None => [lo, hi],
            Some([a, b]) => [
                std::array::from_fn(|i| a[i].min(lo[i])),
                std::array::from_fn(|i| b[i].max(hi[i])),
            ],
        })
    };
    let cells = solid.iter().fold(None, |acc, &(x, y)| {
        grow(acc, [x, y, 0], [x + 1, y + 1, top(x, y)])
    });
    let want = ramps.iter().filter(|r| r.rise > 0).fold(cells, |acc, r| {
        let [x0, y0, x1, y1] = r.cells;
        // A rise fits a cell's height (validated as one).
        let top = units.top_level(r.rise as u16);
        grow(acc, [x0, y0, 0], [x1 + 1, y1 + 1, top])
    });
    let got = levels.iter().fold(None, |acc, &p| grow(acc, p, p));
    if got == want {
        return None;
    }
    let metres = |b: Option<[[u32; 3]; 2]>| {
        b.map(|corners| {
            corners.map(|[x, y, level]| {
                [
                    f64::from(x) * units.block_size,
                    f64::from(y) * units.block_size,
                    units.z(level),
                ]
            })
        })
    };
    Some(FaultKind::BoundsDiffer {
        measured: metres(got),
        expected: metres(want),
    })
}
