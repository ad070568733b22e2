//! Worlds below full difficulty are rebuilt by the rounding rule they were
//! written with: today's (`"difficulty_rule": "drawn"` in `rse.json`) and
//! the half-up rule of worlds written before the rule was recorded.

mod common;

use std::path::Path;

use common::*;
use rse_core::{Difficulty, DifficultyRule, Scheme, generate_by};
use rse_world::{MeshMode, Targets, Templates, WorldConfig, WorldOptions, build_world};

const D: f64 = 0.5;

fn options(d: f64, rule: Option<DifficultyRule>) -> WorldOptions {
    WorldOptions {
        targets: Targets::parse("obj,mujoco").unwrap(),
        mesh: MeshMode::Single,
        difficulty: Difficulty::new(d).unwrap(),
        difficulty_rule: rule,
        ..WorldOptions::default()
    }
}

fn write(dir: &Path, name: &str, options: &WorldOptions) -> std::path::PathBuf {
    let scheme = Scheme::from_csv(SCHEME, None).unwrap();
    let world = build_world(
        &scheme,
        3,
        1,
        name.to_owned(),
        options,
        &Templates::builtin(),
    )
    .unwrap();
    let root = dir.join(name);
    write_files(&root, &world);
    root
}

#[test]
fn a_new_world_records_the_drawn_rule_and_passes() {
    let resolved = WorldConfig {
        difficulty: Some(Difficulty::new(D).unwrap()),
        ..WorldConfig::default()
    }
    .resolve()
    .unwrap();
    assert_eq!(resolved.difficulty_rule, Some(DifficultyRule::Drawn));
    let full = WorldConfig::default().resolve().unwrap();
    assert_eq!(full.difficulty_rule, None, "full worlds keep their bytes");

    let dir = tempfile::tempdir().unwrap();
    let world = write(dir.path(), "world_0001", &resolved);
    let manifest = std::fs::read_to_string(world.join("rse.json")).unwrap();
    assert!(
        manifest.contains("\"difficulty_rule\": \"drawn\""),
        "{manifest}"
    );
    let report = check(&world);
    assert!(report.ok, "{:#?}", report.faults);
}

#[test]
fn a_world_written_before_the_rule_is_rebuilt_half_up_and_passes() {
    let dir = tempfile::tempdir().unwrap();
    let world = write(dir.path(), "world_0001", &options(D, None));
    let manifest = std::fs::read_to_string(world.join("rse.json")).unwrap();
    assert!(!manifest.contains("difficulty_rule"), "{manifest}");
    assert!(manifest.contains("\"difficulty\": 0.5"), "{manifest}");
    let report = check(&world);
    assert!(report.ok, "{:#?}", report.faults);
}

#[test]
fn a_drawn_world_stripped_of_its_rule_is_caught() {
    // A difficulty at which the two rules differ on this world, for the
    // test to mean anything.
    let scheme = Scheme::from_csv(SCHEME, None).unwrap();
    let differs = |d: f64| {
        let d = Difficulty::new(d).unwrap();
        let drawn = generate_by(&scheme, 3, 1, d, DifficultyRule::Drawn);
        drawn != generate_by(&scheme, 3, 1, d, DifficultyRule::Nearest)
    };
    let d = [0.5, 0.3, 0.7, 0.4, 0.6, 0.2]
        .into_iter()
        .find(|&d| differs(d))
        .expect("the rules differ at some difficulty");

    let dir = tempfile::tempdir().unwrap();
    let world = write(
        dir.path(),
        "world_0001",
        &options(d, Some(DifficultyRule::Drawn)),
    );
    let path = world.join("rse.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let stripped = text.replace("  \"difficulty_rule\": \"drawn\",\n", "");
    assert_ne!(stripped, text);
    std::fs::write(&path, stripped).unwrap();
    forge(&world);
    let report = check(&world);
    assert!(!report.ok, "a world rebuilt by the wrong rule passed");
}
