//! Every sample in `schemes/` loads, generates, previews and round-trips.

use rse_core::{Scheme, generate, preview};

use crate::util::{repo, sample_paths};

#[test]
fn every_sample_loads_generates_and_round_trips() {
    let paths = sample_paths();
    assert!(
        paths.len() >= 12,
        "expected the 12 samples, found {}",
        paths.len()
    );
    for path in paths {
        let scheme = Scheme::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(!scheme.obstacles().is_empty(), "{}", path.display());
        let terrain = generate(&scheme, 0, 0);
        assert!(terrain.heightmap().max() > 0, "{} is flat", path.display());
        let png = preview::encode_png(&preview::render(&terrain, 2)).unwrap();
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            scheme.to_csv(),
            text,
            "{} is not in canonical form",
            path.display()
        );
    }
}

#[test]
fn there_is_a_sample_of_every_obstacle_type() {
    let mut kinds = std::collections::BTreeSet::new();
    for path in sample_paths() {
        for o in Scheme::load(&path).unwrap().obstacles() {
            kinds.insert(o.kind().name());
        }
    }
    assert_eq!(kinds.len(), rse_core::ObstacleKind::ALL.len(), "{kinds:?}");
}

#[test]
fn the_paper_pallet_sample_is_9_by_13() {
    let scheme = Scheme::load(repo().join("schemes/paper_pallets.csv")).unwrap();
    let grid = scheme.grid();
    assert_eq!((grid.nx, grid.ny), (9, 13));
}
