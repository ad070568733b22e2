//! The golden tables: SHA-256 of the heightmap CSV of chosen worlds of every
//! sample scheme, and of the OBJ, STL and GLB of each sample's first world.
//! A change here is a change of the output format: bump the version and note
//! it in CHANGELOG.md, then re-bless with
//! `RSE_BLESS=1 cargo test -p rse-core --test lib golden`.
//! The heightmap table is checked through the CLI and from Python too.

use std::fmt::Write as _;

use rse_core::export::{glb, obj, stl};
use rse_core::{Scheme, generate};
use sha2::{Digest, Sha256};

use crate::util::repo;
use crate::util::sample_paths;

/// The worlds of each sample that the table pins.
const WORLDS: [(u64, u64); 3] = [(0, 0), (0, 1), (12_345, 7)];

fn hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .fold(String::new(), |mut s, b| {
            write!(s, "{b:02x}").unwrap();
            s
        })
}

fn heightmap_table() -> String {
    let mut out = String::from("scheme,seed,index,sha256\n");
    for path in sample_paths() {
        let scheme = Scheme::load(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy();
        for (seed, index) in WORLDS {
            let csv = generate(&scheme, seed, index).heightmap().to_csv();
            writeln!(out, "{name},{seed},{index},{}", hex(csv.as_bytes())).unwrap();
        }
    }
    out
}

fn mesh_table() -> String {
    let mut out = String::from("scheme,format,sha256\n");
    for path in sample_paths() {
        let scheme = Scheme::load(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy();
        let mesh = generate(&scheme, 0, 0).mesh();
        let files: [(&str, Vec<u8>); 3] = [
            ("obj", obj(&mesh, Some("terrain.mtl")).into_bytes()),
            ("stl", stl(&mesh)),
            ("glb", glb(&mesh)),
        ];
        for (format, bytes) in files {
            writeln!(out, "{name},{format},{}", hex(&bytes)).unwrap();
        }
    }
    out
}

/// Compares `now` with the golden file `name`, or rewrites it when blessing.
fn check_golden(name: &str, now: &str) {
    let path = repo().join("tests/golden").join(name);
    if std::env::var_os("RSE_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, now).unwrap();
        return;
    }
    let golden = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{} must exist: {e}", path.display()));
    let changed: Vec<_> = now
        .lines()
        .zip(golden.lines())
        .filter(|(a, b)| a != b)
        .map(|(a, _)| a.to_owned())
        .collect();
    assert!(
        changed.is_empty() && now.lines().count() == golden.lines().count(),
        "output changed for:\n{}\n(a breaking change: see the module doc)",
        changed.join("\n")
    );
}

#[test]
fn heightmaps_match_the_golden_table() {
    check_golden("heightmaps.csv", &heightmap_table());
}

#[test]
fn meshes_match_the_golden_table() {
    check_golden("meshes.csv", &mesh_table());
}
