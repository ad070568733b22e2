//! A world's terrain against its manifest: the heightmap regenerated from
//! `rse.json`, and every OBJ re-read from disk against SPEC §6 and the
//! heightmap (volume, bounding box, top heights).

use std::path::Path;

use rse_core::mesh::check::{bounding_box, faults as mesh_faults, volume};
use rse_core::{Heightmap, Scheme, Terrain, generate};
use rse_world::Manifest;

/// The world `rse.json` describes, regenerated; faults if `heightmap.csv`
/// is not its heightmap.
pub fn regenerate(world: &Path, manifest: &Manifest, faults: &mut Vec<String>) -> Option<Terrain> {
    let scheme = match Scheme::from_csv(&manifest.scheme, Some("rse.json scheme")) {
        Ok(scheme) => scheme,
        Err(e) => {
            faults.push(format!("rse.json: its scheme does not load: {e}"));
            return None;
        }
    };
    let terrain = generate(&scheme, manifest.seed, manifest.index);
    if terrain.grid() != manifest.grid {
        faults.push("rse.json: its grid is not the scheme's".to_owned());
    }
    let what = format!(
        "the world regenerated from rse.json (seed {}, index {})",
        manifest.seed, manifest.index
    );
    match std::fs::read_to_string(world.join("heightmap.csv")) {
        Err(e) => faults.push(format!("heightmap.csv: cannot be read: {e}")),
        Ok(text) => match Heightmap::from_csv(&text) {
            Err(e) => faults.push(format!("heightmap.csv: {e}")),
            Ok(map) if (map.nx(), map.ny()) != (terrain.grid().nx, terrain.grid().ny) => faults
                .push(format!(
                    "heightmap.csv: {}x{} cells, but {what} has {}x{}",
                    map.nx(),
                    map.ny(),
                    terrain.grid().nx,
                    terrain.grid().ny
                )),
            Ok(map) => {
                let differs = map
                    .cells()
                    .iter()
                    .zip(terrain.heightmap().cells())
                    .position(|(a, b)| a != b);
                if let Some(i) = differs {
                    let (x, y) = (i as u32 % map.nx(), i as u32 / map.nx());
                    faults.push(format!(
                        "heightmap.csv: cell ({x}, {y}) is {}, but in {what} it is {}",
                        map.get(x, y),
                        terrain.heightmap().get(x, y)
                    ));
                } else if text != terrain.heightmap().to_csv() {
                    faults.push(
                        "heightmap.csv: same heights, but not in the canonical format".to_owned(),
                    );
                }
            }
        },
    }
    Some(terrain)
}

/// A mesh read from an OBJ file.
pub struct ObjMesh {
    pub vertices: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// Reads an OBJ file's positions and triangles (normals and materials are
/// the readers' business).
pub fn read_obj(path: &Path) -> Result<ObjMesh, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ..tobj::LoadOptions::default()
    };
    let (models, _) = tobj::load_obj_buf(&mut std::io::BufReader::new(file), &options, |_| {
        Ok((Vec::new(), std::collections::HashMap::default()))
    })
    .map_err(|e| e.to_string())?;
    let mut mesh = ObjMesh {
        vertices: Vec::new(),
        triangles: Vec::new(),
    };
    for model in models {
        let m = model.mesh;
        if m.face_arities.iter().any(|&n| n != 3) {
            return Err("has faces that are not triangles".to_owned());
        }
        let first = mesh.vertices.len() as u32;
        mesh.vertices
            .extend(m.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        mesh.triangles.extend(
            m.indices
                .chunks_exact(3)
                .map(|t| [first + t[0], first + t[1], first + t[2]]),
        );
    }
    Ok(mesh)
}

/// Faults of the OBJ at `path` (in the world), read as `mesh`, as the mesh
/// of `terrain`.
pub fn check_obj(
    path: &str,
    mesh: &Result<ObjMesh, String>,
    terrain: &Terrain,
    faults: &mut Vec<String>,
) {
    let mesh = match mesh {
        Ok(mesh) => mesh,
        Err(e) => {
            faults.push(format!("{path}: cannot be read as OBJ: {e}"));
            return;
        }
    };
    let broken = mesh_faults(&mesh.vertices, &mesh.triangles);
    if let Some(first) = broken.first() {
        faults.push(format!(
            "{path}: not a closed, oriented, exact mesh: {} faults, first: {first}",
            broken.len()
        ));
        return;
    }
    let map = terrain.heightmap();
    let (s, step, base) = (terrain.block_size(), terrain.step_height(), terrain.base());
    let top = |x: u32, y: u32| base + f64::from(map.get(x, y)) * step;
    let solid: Vec<(u32, u32)> = (0..map.ny())
        .flat_map(|y| (0..map.nx()).map(move |x| (x, y)))
        .filter(|&(x, y)| top(x, y) > 0.0)
        .collect();
    let expected: f64 = solid.iter().map(|&(x, y)| s * s * top(x, y)).sum();
    let measured = volume(&mesh.vertices, &mesh.triangles);
    // f32 coordinates: about 7 significant digits.
    if (measured - expected).abs() > 1e-5 * expected.max(1e-3) {
        faults.push(format!(
            "{path}: encloses {measured:.6} m³, but the heightmap's solid is {expected:.6} m³"
        ));
    }
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-5 * b.abs().max(1.0);
    let want = solid
        .iter()
        .fold(None, |acc: Option<([f64; 3], [f64; 3])>, &(x, y)| {
            let lo = [f64::from(x) * s, f64::from(y) * s, 0.0];
            let hi = [f64::from(x + 1) * s, f64::from(y + 1) * s, top(x, y)];
            Some(match acc {
                None => (lo, hi),
                Some((a, b)) => (
                    std::array::from_fn(|i| a[i].min(lo[i])),
                    std::array::from_fn(|i| b[i].max(hi[i])),
                ),
            })
        });
    match (bounding_box(&mesh.vertices), want) {
        (None, None) => {}
        (Some((lo, hi)), Some((a, b)))
            if (0..3).all(|i| close(lo[i], a[i]) && close(hi[i], b[i])) => {}
        (got, want) => faults.push(format!(
            "{path}: bounding box {got:?}, but the heightmap's solid spans {want:?}"
        )),
    }
    // Every upward face lies on the top of the cells under it.
    for t in &mesh.triangles {
        let [p, q, r] = t.map(|i| mesh.vertices[i as usize].map(f64::from));
        let nz = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
        if nz <= 0.0 || !(close(p[2], q[2]) && close(q[2], r[2])) || p[2] == 0.0 {
            continue;
        }
        let (cx, cy) = ((p[0] + q[0] + r[0]) / 3.0, (p[1] + q[1] + r[1]) / 3.0);
        let (x, y) = ((cx / s).floor() as u32, (cy / s).floor() as u32);
        if x >= map.nx() || y >= map.ny() || !close(p[2], top(x, y)) {
            faults.push(format!(
                "{path}: a top face at z = {:.4} m lies over cell ({x}, {y}), whose top is at {:.4} m",
                p[2],
                if x < map.nx() && y < map.ny() { top(x, y) } else { 0.0 }
            ));
            return;
        }
    }
}
