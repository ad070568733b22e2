//! Helpers shared by the tests.

use std::path::PathBuf;

use rse_core::{Heightmap, Scheme, generate};

/// The repository's root folder.
pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The sample schemes in `schemes/`, sorted.
pub fn sample_paths() -> Vec<std::path::PathBuf> {
    let mut paths: Vec<_> = std::fs::read_dir(repo().join("schemes"))
        .expect("schemes/ exists")
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "csv"))
        .collect();
    paths.sort();
    paths
}

/// A scheme from CSV text, panicking with the error if it is refused.
pub fn scheme(text: &str) -> Scheme {
    Scheme::from_csv(text, None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The heightmap of world (0, 0) of `text`.
pub fn heights(text: &str) -> Heightmap {
    generate(&scheme(text), 0, 0).heightmap().clone()
}

/// Rows of a heightmap from the top (`y = ny−1`) down, as a picture reads.
pub fn picture(map: &Heightmap) -> Vec<String> {
    (0..map.ny())
        .rev()
        .map(|y| map.row(y).iter().map(u16::to_string).collect::<String>())
        .collect()
}
