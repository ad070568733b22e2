//! The sample schemes of the repository's `schemes/` folder, built into
//! the editor so its page can open them from any folder (a test holds the
//! list to the folder: a new sample is listed, or the test fails).

/// `(file name, CSV text)` of each sample, by name.
pub const SAMPLES: [(&str, &str); 17] = [
    (
        "curriculum.csv",
        include_str!("../../../schemes/curriculum.csv"),
    ),
    (
        "flat_peak_and_pit.csv",
        include_str!("../../../schemes/flat_peak_and_pit.csv"),
    ),
    (
        "gaussian.csv",
        include_str!("../../../schemes/gaussian.csv"),
    ),
    (
        "mix_flights.csv",
        include_str!("../../../schemes/mix_flights.csv"),
    ),
    (
        "mix_ramps.csv",
        include_str!("../../../schemes/mix_ramps.csv"),
    ),
    (
        "mix_rough.csv",
        include_str!("../../../schemes/mix_rough.csv"),
    ),
    (
        "mix_stairs.csv",
        include_str!("../../../schemes/mix_stairs.csv"),
    ),
    (
        "mix_walls.csv",
        include_str!("../../../schemes/mix_walls.csv"),
    ),
    (
        "nist_diagonal_hill.csv",
        include_str!("../../../schemes/nist_diagonal_hill.csv"),
    ),
    (
        "nist_flat.csv",
        include_str!("../../../schemes/nist_flat.csv"),
    ),
    (
        "nist_hill.csv",
        include_str!("../../../schemes/nist_hill.csv"),
    ),
    (
        "paper_pallets.csv",
        include_str!("../../../schemes/paper_pallets.csv"),
    ),
    ("peak.csv", include_str!("../../../schemes/peak.csv")),
    ("random.csv", include_str!("../../../schemes/random.csv")),
    (
        "six_obstacles.csv",
        include_str!("../../../schemes/six_obstacles.csv"),
    ),
    ("wall.csv", include_str!("../../../schemes/wall.csv")),
    (
        "wall_long_pit.csv",
        include_str!("../../../schemes/wall_long_pit.csv"),
    ),
];

/// The scheme a new document starts from (New, and `rse-gen edit` without
/// a file): one random field on a 20×20 grid.
pub const NEW_SCHEME: &str = "# size: 20x20\ntype,height\nrandom,1\n";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_sample_of_the_schemes_folder_is_listed_and_reads() {
        let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../schemes");
        let mut on_disk: Vec<String> = std::fs::read_dir(&folder)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|path| path.extension().is_some_and(|e| e == "csv"))
            .map(|path| path.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        on_disk.sort();
        let listed: Vec<&str> = SAMPLES.iter().map(|(name, _)| *name).collect();
        assert_eq!(listed, on_disk);
        for (name, csv) in SAMPLES {
            assert!(
                rse_core::Scheme::from_csv(csv, Some(name)).is_ok(),
                "{name}"
            );
        }
        assert!(rse_core::Scheme::from_csv(NEW_SCHEME, None).is_ok());
    }
}
