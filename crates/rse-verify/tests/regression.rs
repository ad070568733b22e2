//! Regressions: hostile worlds found by the hardening rounds, a world folder handed over by
//! someone else, each attack built here. `check` must answer with a fault
//! naming the file, read nothing outside the world, print nothing of a
//! file that is not ours, neither hang nor panic, and rebuild nothing its
//! budget does not cover.

mod common;

use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;

use common::*;
use rse_core::{AtlasOptions, PatchOptions, Scheme};
use rse_verify::{CheckOptions, FaultKind, NotAWorld, WorldReport, check_paths, check_world};
use rse_world::{
    MeshMode, NamedScheme, Targets, Templates, WorldOptions, build_atlas_world, build_world,
};

/// Every fault's message and the JSON of the report, for what they must
/// not say.
fn everything_said(report: &WorldReport) -> String {
    serde_json::to_string(report).unwrap()
}

fn over_budget(report: &WorldReport) -> bool {
    report.faults.iter().any(|f| {
        f.file.as_deref() == Some("rse.json") && matches!(f.kind, FaultKind::OverBudget { .. })
    })
}

/// Item 1: a few KB of `rse.json` naming a 10000×10000 scheme would make
/// the rebuild allocate gigabytes: refused with its cost, before building.
#[test]
fn a_huge_recorded_scheme_is_refused_by_the_budget_not_rebuilt() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    edit_manifest(&world, |m| {
        m.scheme = "# size: 10000x10000\ntype,height\nrandom,2\n".to_owned();
    });
    let report = check(&world);
    assert!(over_budget(&report), "{:#?}", report.faults);
    let said = everything_said(&report);
    assert!(said.contains("100000000 cells"), "{said}");
    // A larger budget lets the memory through, so it is the flag that
    // decides; the work of 10⁸ cells is still over 100 times as much.
    let generous = CheckOptions {
        budget: rse_verify::Budget::new(1e-6).unwrap(),
        ..CheckOptions::default()
    };
    let small = good_world(&dir.path().join("small"));
    assert!(
        over_budget(&check_world(&small, &generous)),
        "a tiny budget refuses even a small world"
    );
}

/// Gaussian rows are priced by the tables they build (65,535 odds, every
/// one an erfc for a wide sigma): 4000 such rows in a forged `rse.json`
/// were budgeted like 4000 cells (0.1 s) and ran 11 s. Rows alike share a
/// table (and are priced once); rows each of its own height are priced
/// each. The estimate is the work (bench/budget.py measures it within 2×),
/// so a budget a twentieth of the default refuses the 4000, unbuilt.
#[test]
fn gaussian_tables_are_priced_by_what_they_build() {
    let rows = |distinct: bool| -> String {
        let mut text = String::new();
        for i in 0..4000 {
            let height = if distinct { 65_535 - i } else { 65_535 };
            writeln!(text, "gaussian,{height},10000").unwrap();
        }
        text
    };
    let scheme =
        |rows: String| format!("# size: 2x2\n# step_height: 0.001\ntype,height,sigma\n{rows}");
    let visits = |text: &str| Scheme::from_csv(text, None).unwrap().generation_visits();
    let (distinct, alike) = (scheme(rows(true)), scheme(rows(false)));
    assert!(
        visits(&distinct) >= 4000 * 61_535 * 8,
        "priced {} visits",
        visits(&distinct)
    );
    assert!(
        visits(&alike) < 65_535 * 9 + 4000 * 5,
        "one table shared: {} visits",
        visits(&alike)
    );
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    edit_manifest(&world, |m| m.scheme = distinct);
    // Some 2·10⁹ visits (about 10 s): a budget of 10⁹ visits refuses them.
    let tight = CheckOptions {
        budget: rse_verify::Budget::new(0.05).unwrap(),
        ..CheckOptions::default()
    };
    let report = check_world(&world, &tight);
    assert!(over_budget(&report), "{:#?}", report.faults);
}

/// The physics smoke test is priced with the rebuild (bench/budget.py
/// measures it within 2×): asking for it raises the estimate by a second
/// or so of drops and the colliders' size, and a budget that the rebuild
/// alone fits but the test does not refuses the world before either runs.
#[cfg(feature = "physics")]
#[test]
fn the_physics_smoke_test_is_priced_in_the_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let plain = check(&world);
    let physics = CheckOptions {
        physics: true,
        ..CheckOptions::default()
    };
    let dropped = check_world(&world, &physics);
    assert!(plain.ok && dropped.ok, "{:#?}", dropped.faults);
    let (without, with) = (plain.estimate.unwrap(), dropped.estimate.unwrap());
    assert!(with.seconds > without.seconds + 0.5, "{without:?} {with:?}");
    // A budget between the two: the rebuild fits, rebuild and drops do not.
    let between = (without.seconds + 0.1) / 100.0;
    let tight = CheckOptions {
        physics: true,
        budget: rse_verify::Budget::new(between).unwrap(),
        ..CheckOptions::default()
    };
    let refused = check_world(&world, &tight);
    assert!(
        over_budget(&refused) && refused.physics.is_empty(),
        "{:#?}",
        refused.faults
    );
}

/// Item 1: 100,000 peaks that reach the whole of a 1000×1000 map cost
/// 10¹¹ cell visits (some ten minutes): refused by the work budget.
#[test]
fn a_hundred_thousand_map_wide_peaks_are_refused_by_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let mut scheme = "# size: 1000x1000\ntype,height,angle,x1,y1\n".to_owned();
    for i in 0..100_000 {
        writeln!(scheme, "peak,60,0.5,{},{}", i % 1000, (i * 7) % 1000).unwrap();
    }
    edit_manifest(&world, |m| m.scheme = scheme);
    let report = check(&world);
    assert!(over_budget(&report), "{:#?}", report.faults);
}

/// Writes an atlas world of `tile`×`tile` flat tiles into `dir/atlas`.
fn atlas_world(dir: &Path, tile: u32, patches: u32) -> std::path::PathBuf {
    let scheme = Scheme::from_csv(
        &format!("# size: {tile}x{tile}\ntype,height\nrandom,0\n"),
        None,
    )
    .unwrap();
    let schemes = [NamedScheme {
        name: "flat.csv".to_owned(),
        scheme,
    }];
    let options = AtlasOptions {
        patches: PatchOptions {
            count: patches,
            radius: 0.1,
            max_step: 0,
        },
        ..AtlasOptions::default()
    };
    let world_options = WorldOptions {
        targets: Targets::parse("obj").unwrap(),
        ..WorldOptions::default()
    };
    let (world, _) = build_atlas_world(
        &schemes,
        &options,
        "atlas".to_owned(),
        &world_options,
        &Templates::builtin(),
    )
    .unwrap();
    let root = dir.join("atlas");
    write_files(&root, &world);
    root
}

/// Item 1: an atlas record asking a million flat patches of a 200×200 tile
/// is within the budget and rebuilt — in `candidates × log n`, not the
/// minutes of a quadratic farthest-point sampling — and found to differ.
#[test]
fn a_million_flat_patches_are_sampled_fast_and_the_forgery_found() {
    let dir = tempfile::tempdir().unwrap();
    let atlas = atlas_world(dir.path(), 200, 4);
    edit_manifest(&atlas, |m| {
        m.atlas.as_mut().unwrap().flat_patches.count = 1_000_000;
    });
    let report = check(&atlas);
    assert!(!over_budget(&report), "{:#?}", report.faults);
    assert_fault(&report, Some("atlas.json"), |k| {
        matches!(k, FaultKind::Differs { .. })
    });
}

/// Item 2: rows and columns whose product wraps a machine word passed the
/// size limit and panicked (`capacity overflow`, exit 101): now a fault.
#[test]
fn atlas_rows_and_columns_that_would_wrap_are_a_fault_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let atlas = atlas_world(dir.path(), 8, 0);
    for (rows, cols, border) in [
        (u32::MAX, u32::MAX, 0),
        (1 << 31, 2, u32::MAX),
        (65_536, 65_536, 0),
    ] {
        edit_manifest(&atlas, |m| {
            let record = m.atlas.as_mut().unwrap();
            (record.rows, record.cols, record.border) = (rows, cols, border);
        });
        let report = check(&atlas);
        assert!(!report.ok);
        assert_eq!(
            report.faults[0].file.as_deref(),
            Some("rse.json"),
            "{:#?}",
            report.faults
        );
    }
}

/// Item 3: a FIFO or a link where a world file was is refused, never
/// opened for reading (a FIFO hung `open()`), never followed.
#[test]
fn a_fifo_or_a_link_in_place_of_a_world_file_is_a_fault() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    std::fs::remove_file(world.join("heightmap.csv")).unwrap();
    let made = std::process::Command::new("mkfifo")
        .arg(world.join("heightmap.csv"))
        .status()
        .unwrap();
    assert!(made.success());
    std::fs::remove_file(world.join("meshes/terrain.obj")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", world.join("meshes/terrain.obj")).unwrap();
    std::fs::remove_dir_all(world.join("usd")).unwrap();
    std::os::unix::fs::symlink("/etc", world.join("usd")).unwrap();
    let report = check(&world);
    for file in ["heightmap.csv", "meshes/terrain.obj", "usd"] {
        assert_fault(&report, Some(file), |k| matches!(k, FaultKind::NotAFile));
    }
}

/// Item 4: a world file that is a hard link to a secret elsewhere is a
/// fault, and nothing of the secret is said.
#[test]
fn a_hard_linked_world_file_is_a_fault_and_its_content_unsaid() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let secret = dir.path().join("secret.txt");
    std::fs::write(&secret, "TOPSECRET hunter2\n").unwrap();
    std::fs::remove_file(world.join("heightmap.csv")).unwrap();
    std::fs::hard_link(&secret, world.join("heightmap.csv")).unwrap();
    let report = check(&world);
    assert_fault(&report, Some("heightmap.csv"), |k| {
        matches!(k, FaultKind::HardLinked { links: 2 })
    });
    assert!(!everything_said(&report).contains("TOPSECRET"));
}

/// Item 4: a file that is not ours in format is never quoted, wherever it
/// is: the heightmap, a mesh, a world file, the manifest.
#[test]
fn text_that_does_not_parse_as_ours_is_never_quoted() {
    let secret = "TOPSECRET";
    let cases: [(&str, String); 5] = [
        ("heightmap.csv", format!("{secret},1,2\n")),
        ("meshes/terrain.obj", format!("{secret} 1 2 3\n")),
        ("gazebo/rse.world", format!("<sdf><{secret}></sdf>\n")),
        (
            "mujoco/rse.xml",
            format!("<mujoco><a b=\"{secret}></mujoco>\n"),
        ),
        (
            "rse.json",
            format!("{{\"generator\": \"rse\", \"templates\": \"{secret}\"}}\n"),
        ),
    ];
    for (file, text) in cases {
        let dir = tempfile::tempdir().unwrap();
        let world = good_world(dir.path());
        std::fs::write(world.join(file), text).unwrap();
        if file != "rse.json" {
            forge(&world);
        }
        let report = check(&world);
        assert!(!report.ok, "{file}");
        let said = everything_said(&report);
        assert!(!said.contains(secret), "{file}: {said}");
    }
}

/// Item 5: a batch folder is checked whole: a world that lost its
/// `rse.json`, a junk folder and a symlinked world are faults, named.
#[test]
fn every_sub_folder_of_a_batch_must_be_a_world() {
    let dir = tempfile::tempdir().unwrap();
    let batch = dir.path().join("batch");
    write_world(&batch, "world_0000", SCHEME, &Templates::builtin());
    let lost = write_world(&batch, "world_0001", SCHEME, &Templates::builtin());
    std::fs::remove_file(lost.join("rse.json")).unwrap();
    std::fs::create_dir_all(batch.join("junk")).unwrap();
    std::fs::write(batch.join("junk/notes.txt"), "hello").unwrap();
    let elsewhere = write_world(dir.path(), "world_0002", SCHEME, &Templates::builtin());
    std::os::unix::fs::symlink(&elsewhere, batch.join("world_0002")).unwrap();
    // Plain files beside the worlds (a saved report) and hidden ones (the
    // batch's lock) are not worlds and are let be.
    std::fs::write(batch.join("report.json"), "{}").unwrap();
    std::fs::write(batch.join(".rse-0123456789abcdef.lock"), "").unwrap();
    let report = check_paths(
        std::slice::from_ref(&batch),
        &CheckOptions::default(),
        &|| {},
    )
    .unwrap();
    assert!(!report.ok());
    assert_eq!(report.checked, 1);
    let named = |name: &str, reason: NotAWorld| {
        report.batch_faults.iter().any(|f| {
            f.file.as_deref() == Some(&*batch.join(name).display().to_string())
                && f.kind == FaultKind::NotAWorld { reason }
        })
    };
    assert!(
        named("world_0001", NotAWorld::NoManifest),
        "{:#?}",
        report.batch_faults
    );
    assert!(
        named("junk", NotAWorld::NoManifest),
        "{:#?}",
        report.batch_faults
    );
    assert!(
        named("world_0002", NotAWorld::Link),
        "{:#?}",
        report.batch_faults
    );
    assert_eq!(report.batch_faults.len(), 3, "{:#?}", report.batch_faults);
}

/// Item 5: shards written with different seeds into one folder are a
/// batch of mixed recipes.
#[test]
fn worlds_of_different_seeds_in_one_batch_are_a_fault() {
    let dir = tempfile::tempdir().unwrap();
    let batch = dir.path().join("batch");
    let scheme = Scheme::from_csv(SCHEME, None).unwrap();
    let options = WorldOptions::default();
    for (seed, index) in [(3, 0), (3, 1), (4, 2)] {
        let name = format!("world_{index:04}");
        let world = build_world(
            &scheme,
            seed,
            index,
            name.clone(),
            &options,
            &Templates::builtin(),
        )
        .unwrap();
        write_files(&batch.join(&name), &world);
    }
    let report = check_paths(
        std::slice::from_ref(&batch),
        &CheckOptions::default(),
        &|| {},
    )
    .unwrap();
    assert_eq!(report.failed, 0, "each world is sound on its own");
    let mixed: Vec<_> = report
        .batch_faults
        .iter()
        .filter(|f| matches!(&f.kind, FaultKind::MixedRecipes { difference, .. } if difference.contains("seed 3 there, 4 now")))
        .collect();
    assert_eq!(mixed.len(), 1, "{:#?}", report.batch_faults);
    assert!(mixed[0].file.as_deref().unwrap().ends_with("world_0002"));
}

/// Item 6: a built-in world flipped to `"templates": "custom"` with the
/// gravity reversed and the hashes rewritten passes by hash alone; the
/// summary counts it, `strict` fails it, and with the templates it was
/// really made with (ours, as a folder) the reversal is found.
#[test]
fn custom_templates_cannot_downgrade_a_check() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let sdf = world.join("gazebo/rse.world");
    let text = std::fs::read_to_string(&sdf).unwrap();
    std::fs::write(
        &sdf,
        text.replace(
            "<gravity>0 0 -9.81</gravity>",
            "<gravity>0 0 9.81</gravity>",
        ),
    )
    .unwrap();
    edit_manifest(&world, |m| m.templates = rse_world::TemplateSet::Custom);
    forge(&world);

    let lenient = check_paths(
        std::slice::from_ref(&world),
        &CheckOptions::default(),
        &|| {},
    )
    .unwrap();
    assert!(lenient.ok(), "hash-only: {:#?}", lenient.worlds[0].faults);
    assert_eq!(lenient.worlds_hashed_only, 1);
    assert!(
        lenient.verdict().contains("1 good (1 only by hash)"),
        "{}",
        lenient.verdict()
    );

    let strict = CheckOptions {
        strict: true,
        ..CheckOptions::default()
    };
    assert_fault(&check_world(&world, &strict), None, |k| {
        matches!(k, FaultKind::HashOnly { .. })
    });

    // Ours exported as a folder: the digest of the set is the recorded
    // one only if the world was really made with it.
    let folder = dir.path().join("templates");
    Templates::export_builtin(&folder).unwrap();
    let ours = CheckOptions {
        templates: Some(Arc::new(Templates::with_overrides(&folder).unwrap())),
        ..CheckOptions::default()
    };
    let report = check_world(&world, &ours);
    assert!(!report.ok || !report.hashed_only.is_empty(), "{report:#?}");
}

/// Item 6: a world made with a user's templates is compared byte for byte
/// when `check` is given them: an edit its hashes were forged for is found.
#[test]
fn given_the_templates_a_custom_world_is_rebuilt_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("mine");
    std::fs::create_dir_all(folder.join("gazebo")).unwrap();
    let ours = std::fs::read_to_string(repo().join("templates/gazebo/rse.world.j2")).unwrap();
    std::fs::write(
        folder.join("gazebo/rse.world.j2"),
        format!("<!-- mine -->\n{ours}"),
    )
    .unwrap();
    let templates = Templates::with_overrides(&folder).unwrap();
    let world = write_world(dir.path(), "world_0001", SCHEME, &templates);
    let given = CheckOptions {
        templates: Some(Arc::new(templates)),
        ..CheckOptions::default()
    };
    let report = check_world(&world, &given);
    assert!(report.ok && report.hashed_only.is_empty(), "{report:#?}");
    let sdf = world.join("gazebo/rse.world");
    let text = std::fs::read_to_string(&sdf).unwrap();
    std::fs::write(&sdf, text.replace("-9.81", "9.81")).unwrap();
    forge(&world);
    assert!(check(&world).ok, "by hash alone the forgery passes");
    assert_fault(
        &check_world(&world, &given),
        Some("gazebo/rse.world"),
        |k| matches!(k, FaultKind::Differs { .. }),
    );
}

/// Found by the seeded fuzzing of `make test` (fuzz/regressions/obj/crash-aa9dfafc…):
/// a relative index past what is defined, 0, or a positive one whose
/// offset overflows made tobj compute an offset that overflows (a panic
/// where overflow is checked); each is refused, naming its line.
#[test]
fn an_index_tobj_cannot_resolve_is_refused_by_line() {
    let cases: [(&[u8], &str); 3] = [
        (
            b"v 0 0 0\nvn 0 0 1\nf 1//-12 1//1 1//1\n",
            "line 3: a statement names normal -12, but 1 are defined",
        ),
        (b"v 0 0 0\nf 0 1 1\n", "line 2: a statement names vertex 0"),
        (
            b"v 0 0 0\nf 9223372036854775807 1 1\n",
            "line 2: a statement names vertex 9223372036854775807",
        ),
    ];
    for (obj, said) in cases {
        assert!(
            matches!(rse_verify::read_obj(obj), Err(FaultKind::BadObj { ref reason }) if reason.starts_with(said)),
            "{said}: {:?}",
            rse_verify::read_obj(obj).map(|m| m.triangles.len())
        );
    }
}

/// Item 7: an OBJ of repeated `o a` / `f 1 2 3` lines cost gigabytes to
/// parse: one longer than ours is not read past our size, one as long is
/// refused after 1024 objects.
#[test]
fn a_mesh_bomb_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let obj = world.join("meshes/terrain.obj");
    let size = std::fs::metadata(&obj).unwrap().len() as usize;
    let bomb = "o a\nf 1 2 3\n".repeat(size / 12 + 1);
    std::fs::write(&obj, &bomb[..size]).unwrap();
    forge(&world);
    // As long as ours but not ours: a difference, never parsed (parsing a
    // same-size hostile OBJ once cost 15–36 s); the reader itself refuses
    // the bomb after 1024 objects.
    let report = check(&world);
    assert_fault(&report, Some("meshes/terrain.obj"), |k| {
        matches!(k, FaultKind::Differs { .. })
    });
    assert!(
        matches!(rse_verify::read_obj(&bomb.as_bytes()[..size]), Err(FaultKind::BadObj { reason }) if reason.contains("more than 1024 objects"))
    );
    std::fs::write(&obj, "o a\nf 1 2 3\n".repeat(1 << 20)).unwrap();
    forge(&world);
    let report = check(&world);
    assert_fault(
        &report,
        Some("meshes/terrain.obj"),
        |k| matches!(k, FaultKind::TooLarge { cap, .. } if *cap == size as u64),
    );
}

/// A sound world of every target, its terrain as blocks, checks good under
/// `strict` (the others damage the single-mesh `good_world`, which
/// `faults.rs` checks whole).
#[test]
fn a_sound_world_passes_strict() {
    let dir = tempfile::tempdir().unwrap();
    let scheme = Scheme::from_csv(SCHEME, None).unwrap();
    let options = WorldOptions {
        targets: Targets::all(),
        mesh: MeshMode::Blocks,
        ..WorldOptions::default()
    };
    let world = build_world(
        &scheme,
        1,
        0,
        "w".to_owned(),
        &options,
        &Templates::builtin(),
    )
    .unwrap();
    write_files(&dir.path().join("w"), &world);
    let strict = CheckOptions {
        strict: true,
        ..CheckOptions::default()
    };
    let report = check_world(&dir.path().join("w"), &strict);
    assert!(report.ok, "{:#?}", report.faults);
}
