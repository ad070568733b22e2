//! The sixth hardening round (hostile worlds VI): each hole built here as
//! the red team built it, and closed by its cause.

mod common;

use common::*;
use rse_verify::{Budget, CheckOptions, FaultKind, check_paths, check_world};

/// Hole 1: a fresh world with every collision box removed from
/// `mujoco/rse.xml`, its hashes forged and `"version": "0.1.1"` claimed
/// (templates still built-in) passed as "1 good (1 only by hash)": another
/// version's built-in templates turned the rendered files into hash-only
/// ones. This build renders only its own built-in templates; a world that
/// claims another version's is refused, naming both versions.
#[test]
fn a_world_claiming_another_versions_built_in_templates_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let xml = world.join("mujoco/rse.xml");
    let text = std::fs::read_to_string(&xml).unwrap();
    let stripped: String = text
        .split_inclusive('\n')
        .filter(|line| !line.contains("type=\"box\""))
        .collect();
    assert!(stripped.len() < text.len(), "the world has boxes to remove");
    std::fs::write(&xml, stripped).unwrap();
    forge(&world);
    edit_manifest(&world, |m| m.version = "0.1.1".to_owned());

    let report = check(&world);
    assert!(report.hashed_only.is_empty(), "{report:#?}");
    assert_fault(&report, Some("rse.json"), |k| {
        matches!(k, FaultKind::BadManifest { reason }
            if reason.contains("rse 0.1.1") && reason.contains(&format!("rse {}", rse_core::VERSION)))
    });

    // The same forgery under this build's own version is rebuilt and
    // found: the file differs from what the recipe writes.
    edit_manifest(&world, |m| m.version = rse_core::VERSION.to_owned());
    assert_fault(&check(&world), Some("mujoco/rse.xml"), |k| {
        matches!(k, FaultKind::Differs { .. })
    });
}

/// Hole 2: with 128 threads one fresh world failed `check` as over a
/// budget of the memory available divided by the threads. A world's
/// budget is the whole memory, however many threads the pool has and
/// however many worlds are checked: fewer are checked at once where they
/// would not fit together.
#[test]
fn worlds_on_many_threads_each_have_all_the_memory() {
    let dir = tempfile::tempdir().unwrap();
    let worlds: Vec<_> = (0..6)
        .map(|i| good_world(&dir.path().join(format!("w{i}"))))
        .collect();
    let bytes = check(&worlds[0]).estimate.expect("priced").bytes;
    // A budget 4 times this world's memory: a 32nd of that shared 128
    // ways, two thirds of it shared 6 ways.
    let all = rse_verify::limits::rebuild_bytes() as f64;
    let options = CheckOptions {
        budget: Budget::new(4.0 * bytes as f64 / all).unwrap(),
        ..CheckOptions::default()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(128)
        .build()
        .unwrap();
    for paths in [&worlds[..1], &worlds[..]] {
        let report = pool
            .install(|| check_paths(paths, &options, &|| {}))
            .unwrap();
        assert_eq!(report.checked, paths.len());
        for world in &report.worlds {
            assert!(world.ok, "{:#?}", world.faults);
        }
    }
}

/// Hole 4: `--physics` was priced per cell (8 µs, 300 bytes and a random
/// field's contacts for each), so a fresh flat 2000×2000 world of 1 cm
/// blocks (a 12-triangle mesh, one box; 0.8 s to write) was refused at
/// "7171 MiB, 112 s". The smoke test is priced from the models' triangles
/// and boxes once they are counted: that world passes, priced within a
/// few seconds.
#[test]
fn a_flat_world_of_fine_blocks_passes_the_physics_check_priced_by_its_models() {
    let dir = tempfile::tempdir().unwrap();
    let world = write_world(
        dir.path(),
        "flat",
        "# size: 2000x2000\n# block_size: 0.01\n# base: 0.01\ntype,height\nrandom,0\n",
        &rse_world::Templates::builtin(),
    );
    let physics = CheckOptions {
        physics: true,
        ..CheckOptions::default()
    };
    let report = check_world(&world, &physics);
    assert!(report.faults.is_empty(), "{:?}", report.faults);
    let estimate = report.estimate.expect("priced");
    assert!(estimate.seconds < 10.0, "{estimate:?}");
    assert!(estimate.bytes < 1 << 30, "{estimate:?}");
}
