//! The golden table: SHA-256 of the heightmap CSV of chosen worlds of every
//! sample scheme. A change here is a change of the output format: bump the
//! version and note it in CHANGELOG.md, then re-bless with
//! `RSE_BLESS=1 cargo test -p rse-core --test lib golden`.
//! The same table is checked through the CLI and from Python.

use std::fmt::Write as _;

use rse_core::{Scheme, generate};
use sha2::{Digest, Sha256};

use crate::samples::sample_paths;
use crate::util::repo;

/// The worlds of each sample that the table pins.
const WORLDS: [(u64, u64); 3] = [(0, 0), (0, 1), (12_345, 7)];

fn table() -> String {
    let mut out = String::from("scheme,seed,index,sha256\n");
    for path in sample_paths() {
        let scheme = Scheme::load(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy();
        for (seed, index) in WORLDS {
            let csv = generate(&scheme, seed, index).heightmap().to_csv();
            let hash = Sha256::digest(csv.as_bytes());
            write!(out, "{name},{seed},{index},").unwrap();
            hash.iter().for_each(|b| write!(out, "{b:02x}").unwrap());
            out.push('\n');
        }
    }
    out
}

#[test]
fn heightmaps_match_the_golden_table() {
    let path = repo().join("tests/golden/heightmaps.csv");
    let now = table();
    if std::env::var_os("RSE_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &now).unwrap();
        return;
    }
    let golden = std::fs::read_to_string(&path).expect("tests/golden/heightmaps.csv exists");
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
