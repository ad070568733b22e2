//! Every fault kind, each found in a world damaged on purpose. Wherever a
//! file is changed, its hash in `rse.json` is rewritten to match ("forged"),
//! so only the deeper checks can tell.

mod common;

use std::path::{Path, PathBuf};

use common::*;
use rse_core::Scheme;
use rse_verify::{CheckOptions, FaultKind, check_paths, check_world};
use rse_world::{Templates, sha256_hex};

#[test]
fn an_untouched_world_is_good_and_fully_rebuilt() {
    let dir = tempfile::tempdir().unwrap();
    let report = check(&good_world(dir.path()));
    assert!(report.ok, "{:#?}", report.faults);
    assert!(report.hashed_only.is_empty());
    assert_eq!((report.seed, report.index), (Some(3), Some(1)));
}

#[test]
fn unreadable_a_file_name_that_is_not_utf8() {
    use std::os::unix::ffi::OsStrExt as _;
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let name = std::ffi::OsStr::from_bytes(b"bad\xffname");
    std::fs::write(world.join(name), "x").unwrap();
    let report = check(&world);
    assert_fault(
        &report,
        Some("bad\u{fffd}name"),
        |k| matches!(k, FaultKind::Unreadable { reason } if reason.contains("UTF-8")),
    );
}

/// A FIFO `dir/fifo`, outside the world: reading it would block for
/// ever, so a check that returns proves it was not read.
fn make_fifo(dir: &Path) -> PathBuf {
    let fifo = dir.join("fifo");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    fifo
}

#[test]
fn not_a_file_a_link_out_of_the_world_is_not_followed() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let fifo = make_fifo(dir.path());
    std::fs::remove_file(world.join("heightmap.csv")).unwrap();
    std::os::unix::fs::symlink(&fifo, world.join("heightmap.csv")).unwrap();
    let report = check(&world);
    assert_fault(&report, Some("heightmap.csv"), |k| {
        *k == FaultKind::NotAFile
    });
    assert_fault(&report, Some("heightmap.csv"), |k| *k == FaultKind::Missing);
}

#[test]
fn outside_world_a_manifest_path_that_climbs_out_is_not_read() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    make_fifo(dir.path());
    for path in ["../fifo", "/etc/passwd", "a/../../fifo"] {
        edit_manifest(&world, |m| {
            m.files.insert(path.to_owned(), "0".repeat(64));
        });
    }
    let report = check(&world);
    for path in ["../fifo", "/etc/passwd", "a/../../fifo"] {
        assert_fault(
            &report,
            Some("rse.json"),
            |k| matches!(k, FaultKind::OutsideWorld { path: p } if p == path),
        );
    }
}

#[test]
fn outside_world_a_reference_that_climbs_out() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let path = world.join("webots/rse.wbt");
    let text = std::fs::read_to_string(&path).unwrap();
    let edited = text.replace("../meshes/terrain.obj", "../../../etc/passwd");
    assert_ne!(text, edited);
    std::fs::write(&path, edited).unwrap();
    hashed_only(&world);
    forge(&world);
    let report = check(&world);
    assert_fault(&report, Some("webots/rse.wbt"), |k| {
        matches!(k, FaultKind::OutsideWorld { .. })
    });
}

#[test]
fn too_large_a_manifest_past_its_cap_is_not_read() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    // Sparse: no disk is used, and reading it would take a while.
    let file = std::fs::OpenOptions::new()
        .write(true)
        .open(world.join("rse.json"))
        .unwrap();
    file.set_len(rse_verify::limits::MAX_MANIFEST_BYTES + 1)
        .unwrap();
    let report = check(&world);
    assert_fault(
        &report,
        Some("rse.json"),
        |k| matches!(k, FaultKind::TooLarge { bytes, .. } if *bytes == rse_verify::limits::MAX_MANIFEST_BYTES + 1),
    );
}

#[test]
fn bad_manifest_truncated_json() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let path = world.join("rse.json");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, &text[..text.len() / 2]).unwrap();
    let report = check(&world);
    assert_fault(&report, Some("rse.json"), |k| {
        matches!(k, FaultKind::BadManifest { .. })
    });
    // An empty one and garbage too.
    for bytes in [&b""[..], b"\x00\x01garbage"] {
        std::fs::write(&path, bytes).unwrap();
        let report = check(&world);
        assert!(!report.ok);
        assert_eq!(report.faults[0].file.as_deref(), Some("rse.json"));
    }
}

#[test]
fn bad_manifest_forged_template_claims() {
    // Found by the fuzzer: a built-in world whose templates digest was
    // changed passed, its template files checked by hash alone.
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    edit_manifest(&world, |m| m.templates_sha256.replace_range(0..1, "-"));
    assert_fault(
        &check(&world),
        Some("rse.json"),
        |k| matches!(k, FaultKind::BadManifest { reason } if reason.contains("templates_sha256")),
    );
    // A template set that does not exist: refused as the manifest is read.
    let path = world.join("rse.json");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, text.replace("\"builtin\"", "\"mine\"")).unwrap();
    assert_fault(
        &check(&world),
        Some("rse.json"),
        // Named by what it may be, never quoted: the text may be anyone's.
        |k| matches!(k, FaultKind::BadManifest { reason } if reason.contains("expected `builtin` or `custom`") && !reason.contains("mine")),
    );
}

#[test]
fn bad_scheme_in_the_manifest() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    edit_manifest(&world, |m| m.scheme = m.scheme.replace("wall,", "tower,"));
    let report = check(&world);
    assert_fault(
        &report,
        Some("rse.json"),
        |k| matches!(k, FaultKind::BadScheme { reason } if reason.contains("tower")),
    );
}

#[test]
fn missing_a_deleted_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    std::fs::remove_file(world.join("gazebo/rse_terrain/meshes/terrain.obj")).unwrap();
    let report = check(&world);
    assert_fault(
        &report,
        Some("gazebo/rse_terrain/meshes/terrain.obj"),
        |k| *k == FaultKind::Missing,
    );
    assert_fault(
        &report,
        Some("gazebo/rse_terrain/model.sdf"),
        |k| matches!(k, FaultKind::MissingReference { reference } if reference.contains("terrain.obj")),
    );
}

/// A Gazebo classic world resolves `model://` in its own folder (Gazebo 11
/// is run with `GAZEBO_MODEL_PATH` on `gazebo-classic/`): its mesh deleted
/// is missing there even while `gazebo/` still has its copy; an SDF version
/// put back to 1.9 (what Gazebo 11 cannot read) differs from the rebuild.
#[test]
fn a_tampered_gazebo_classic_world_is_caught() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    assert!(
        world
            .join("gazebo/rse_terrain/meshes/terrain.obj")
            .is_file()
    );
    std::fs::remove_file(world.join("gazebo-classic/rse_terrain/meshes/terrain.obj")).unwrap();
    let sdf = world.join("gazebo-classic/rse_terrain/model.sdf");
    let text = std::fs::read_to_string(&sdf).unwrap();
    std::fs::write(
        &sdf,
        text.replace("<sdf version=\"1.7\">", "<sdf version=\"1.9\">"),
    )
    .unwrap();
    forge(&world);
    let report = check(&world);
    assert_fault(
        &report,
        Some("gazebo-classic/rse_terrain/meshes/terrain.obj"),
        |k| *k == FaultKind::Missing,
    );
    assert_fault(&report, Some("gazebo-classic/rse_terrain/model.sdf"), |k| {
        matches!(k, FaultKind::Differs { line: Some(2), .. })
    });
    assert!(
        !report
            .faults
            .iter()
            .any(|f| f.file.as_deref().is_some_and(|p| p.starts_with("gazebo/"))),
        "{:#?}",
        report.faults
    );
}

/// A reference from a Gazebo classic model to the mesh resolves in
/// `gazebo-classic/`, never in `gazebo/`: with `gazebo/`'s copy of the
/// mesh still there, the classic one deleted and the deletion forged into
/// the manifest is caught by the reference check.
#[test]
fn missing_reference_a_classic_model_looks_in_its_own_folder() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    std::fs::remove_file(world.join("gazebo-classic/rse_terrain/meshes/terrain.obj")).unwrap();
    edit_manifest(&world, |m| {
        m.files
            .remove("gazebo-classic/rse_terrain/meshes/terrain.obj");
    });
    let report = check(&world);
    assert_fault(
        &report,
        Some("gazebo-classic/rse_terrain/model.sdf"),
        |k| matches!(k, FaultKind::MissingReference { reference } if reference.contains("terrain.obj")),
    );
}

#[test]
fn unexpected_a_file_added_and_listed() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    std::fs::write(world.join("webots/extra.txt"), "x").unwrap();
    edit_manifest(&world, |m| {
        m.files
            .insert("webots/extra.txt".to_owned(), sha256_hex(b"x"));
    });
    let report = check(&world);
    assert_fault(&report, Some("webots/extra.txt"), |k| {
        *k == FaultKind::Unexpected
    });
}

#[test]
fn differs_text_and_binary_named_by_line_and_byte() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let sdf = world.join("gazebo/rse.world");
    let text = std::fs::read_to_string(&sdf).unwrap();
    let line = text.lines().position(|l| l.contains("<gravity>")).unwrap() + 1;
    std::fs::write(&sdf, text.replace("<gravity>0 0 -9.8", "<gravity>0 0 -1.6")).unwrap();
    let png = world.join("preview.png");
    let mut bytes = std::fs::read(&png).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 1;
    std::fs::write(&png, bytes).unwrap();
    forge(&world);
    let report = check(&world);
    assert_fault(
        &report,
        Some("gazebo/rse.world"),
        |k| matches!(k, FaultKind::Differs { line: Some(l), .. } if *l == line),
    );
    assert_fault(
        &report,
        Some("preview.png"),
        |k| matches!(k, FaultKind::Differs { line: None, byte } if *byte == middle),
    );
    assert_fault(&report, Some("rse.json"), |k| {
        matches!(k, FaultKind::Differs { .. })
    });
}

#[test]
fn hash_mismatch_of_a_file_from_user_templates() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("templates");
    copy_tree(&repo().join("templates/gazebo"), &templates.join("gazebo"));
    std::fs::write(templates.join("gazebo/notes.txt"), "our lab's notes\n").unwrap();
    let custom = Templates::with_overrides(&templates).unwrap();
    let world = write_world(dir.path(), "world_0001", SCHEME, &custom);
    let report = check(&world);
    assert!(report.ok, "{:#?}", report.faults);
    assert!(
        report.hashed_only.contains(&"gazebo/notes.txt".to_owned()),
        "{:?}",
        report.hashed_only
    );
    // Terrain files are still rebuilt: a forged heightmap is still found.
    std::fs::write(world.join("gazebo/notes.txt"), "changed\n").unwrap();
    let report = check(&world);
    assert_fault(&report, Some("gazebo/notes.txt"), |k| {
        *k == FaultKind::HashMismatch
    });
}

#[test]
fn too_large_a_file_from_user_templates_past_its_cap() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("templates");
    copy_tree(&repo().join("templates/gazebo"), &templates.join("gazebo"));
    std::fs::write(templates.join("gazebo/notes.txt"), "x").unwrap();
    let custom = Templates::with_overrides(&templates).unwrap();
    let world = write_world(dir.path(), "world_0001", SCHEME, &custom);
    let file = std::fs::OpenOptions::new()
        .write(true)
        .open(world.join("gazebo/notes.txt"))
        .unwrap();
    let cap = rse_verify::limits::file_cap(12 * 10);
    file.set_len(cap + 1).unwrap();
    let report = check(&world);
    assert_fault(&report, Some("gazebo/notes.txt"), |k| {
        *k == FaultKind::TooLarge {
            bytes: cap + 1,
            cap,
        }
    });
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&entry.path(), &to.join(entry.file_name()));
        } else {
            std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
        }
    }
}

/// Replaces line `y` (0-based) of the heightmap, adding 1 to column `x`.
fn raise_cell(world: &Path, x: usize, y: usize) {
    let path = world.join("heightmap.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let mut cells: Vec<u32> = lines[y].split(',').map(|c| c.parse().unwrap()).collect();
    cells[x] += 1;
    lines[y] = cells
        .iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(",");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
}

/// Another seed in `rse.json` (forged hashes and all) asks for another
/// world: the rebuild differs from the files, cell by cell.
#[test]
fn height_differs_after_a_changed_seed_in_the_manifest() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    edit_manifest(&world, |m| m.seed += 1);
    let report = check(&world);
    assert_fault(&report, Some("heightmap.csv"), |k| {
        matches!(k, FaultKind::HeightDiffers { .. })
    });
    assert_eq!(
        report.seed,
        Some(4),
        "the manifest's seed is the one rebuilt"
    );
}

#[test]
fn height_differs_names_the_cell() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    raise_cell(&world, 4, 2);
    forge(&world);
    let report = check(&world);
    assert_fault(
        &report,
        Some("heightmap.csv"),
        |k| matches!(k, FaultKind::HeightDiffers { x: 4, y: 2, found, expected } if *found == expected + 1),
    );
}

#[test]
fn bad_heightmap_garbage_and_wrong_size() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    for text in ["1,2,x\n", "1,2\n3,4\n", ""] {
        std::fs::write(world.join("heightmap.csv"), text).unwrap();
        forge(&world);
        let report = check(&world);
        assert_fault(&report, Some("heightmap.csv"), |k| {
            matches!(k, FaultKind::BadHeightmap { .. })
        });
    }
}

#[test]
fn not_text_a_world_file_that_is_not_utf8() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    std::fs::write(world.join("urdf/rse.urdf"), b"<robot>\xff\xfe</robot>").unwrap();
    hashed_only(&world);
    forge(&world);
    let report = check(&world);
    assert_fault(&report, Some("urdf/rse.urdf"), |k| *k == FaultKind::NotText);
}

#[test]
fn bad_xml_broken_entity_bomb_and_deep() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let mjcf = world.join("mujoco/rse.xml");
    let text = std::fs::read_to_string(&mjcf).unwrap();
    // Deeper than the limit and still shorter than the file it replaces
    // (a longer one is refused unread, below).
    let deep = "<a>".repeat(300) + &"</a>".repeat(300);
    let bomb = "<?xml version=\"1.0\"?>\n<!DOCTYPE m [<!ENTITY a \"aaaaaaaaaa\">\
        <!ENTITY b \"&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;\"><!ENTITY c \"&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;\">]>\n\
        <mujoco file=\"&c;\"/>\n";
    let huge = format!("<mujoco model=\"{}\">", "m".repeat(1 << 20));
    for (bad, reason) in [
        (text.replace("</worldbody>", ""), "not well-formed"),
        (bomb.to_owned(), "DTD"),
        (deep, "nest deeper"),
    ] {
        assert!(bad.len() <= text.len());
        std::fs::write(&mjcf, &bad).unwrap();
        hashed_only(&world);
        forge(&world);
        let report = check(&world);
        assert_fault(
            &report,
            Some("mujoco/rse.xml"),
            |k| matches!(k, FaultKind::BadXml { reason: r, .. } if r.contains(reason)),
        );
    }
    // Rebuilt (ours), a file is read no longer than ours.
    std::fs::write(&mjcf, &huge).unwrap();
    edit_manifest(&world, |m| m.templates = rse_world::TemplateSet::Builtin);
    forge(&world);
    assert_fault(
        &check(&world),
        Some("mujoco/rse.xml"),
        |k| matches!(k, FaultKind::TooLarge { cap, .. } if *cap == text.len() as u64),
    );
}

#[test]
fn missing_and_absolute_references() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let urdf = world.join("urdf/rse.urdf");
    let text = std::fs::read_to_string(&urdf).unwrap();
    let edited = text.replacen("../meshes/terrain.obj", "/abs/terrain.obj", 1);
    let edited = edited.replacen("../meshes/terrain.obj", "../meshes/none.obj", 1);
    std::fs::write(&urdf, edited).unwrap();
    hashed_only(&world);
    forge(&world);
    let report = check(&world);
    assert_fault(
        &report,
        Some("urdf/rse.urdf"),
        |k| matches!(k, FaultKind::AbsoluteReference { reference } if reference == "/abs/terrain.obj"),
    );
    assert_fault(
        &report,
        Some("urdf/rse.urdf"),
        |k| matches!(k, FaultKind::MissingReference { reference } if reference == "../meshes/none.obj"),
    );
}

/// Replaces `meshes/terrain.obj` (world 1 of seed 3 of `scheme`) by
/// `text` and forges the hashes: `check` finds it differs and examines it
/// no further (no parse, no mesh check, no physics). Returns what examining
/// it would have found: the OBJ reader's and mesh checks' own faults.
fn replace_obj(world: &Path, scheme: &str, text: &str) -> Vec<FaultKind> {
    std::fs::write(world.join("meshes/terrain.obj"), text).unwrap();
    forge(world);
    let report = check_world(
        world,
        &CheckOptions {
            physics: true,
            ..CheckOptions::default()
        },
    );
    let of_obj: Vec<&FaultKind> = report
        .faults
        .iter()
        .filter(|f| f.file.as_deref() == Some("meshes/terrain.obj"))
        .map(|f| &f.kind)
        .collect();
    assert!(
        matches!(
            of_obj[..],
            [FaultKind::Differs { .. } | FaultKind::TooLarge { .. }]
        ),
        "a failed file is not examined further: {of_obj:#?}"
    );
    let terrain = rse_core::generate(&Scheme::from_csv(scheme, None).unwrap(), 3, 1);
    match rse_verify::read_obj(text.as_bytes()) {
        Ok(mesh) => rse_verify::mesh_faults_against(&mesh, &terrain),
        Err(kind) => vec![kind],
    }
}

#[test]
fn bad_obj_non_finite_bad_indices_garbage_and_non_triangles() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let good = std::fs::read_to_string(world.join("meshes/terrain.obj")).unwrap();
    let first_v = good
        .lines()
        .find(|l| l.starts_with("v "))
        .unwrap()
        .to_owned();
    let first_f = good
        .lines()
        .find(|l| l.starts_with("f "))
        .unwrap()
        .to_owned();
    // Each no longer than the good file (a longer one is refused unread):
    // its comment line makes room.
    let good = good.split_once('\n').unwrap().1.to_owned();
    let cases = [
        good.replacen(&first_v, "v inf 0 0", 1),
        good.replacen(&first_v, "v NaN 0 0", 1),
        good.replacen(&first_v, "v 1e308 0 0", 1),
        good.replacen(&first_f, "f 1 2 99999", 1),
        "f 0 1 2\n".to_owned(),
        "f -5 -6 -7\n".to_owned(),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n".to_owned(),
        "\u{0}\u{1}garbage".to_owned(),
    ];
    for case in &cases {
        let found = replace_obj(&world, SCHEME, case);
        assert!(
            found.iter().any(|k| matches!(k, FaultKind::BadObj { .. })),
            "{found:#?}"
        );
    }
}

#[test]
fn bad_mesh_a_hole() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let good = std::fs::read_to_string(world.join("meshes/terrain.obj")).unwrap();
    let first_f = good.lines().find(|l| l.starts_with("f ")).unwrap();
    let found = replace_obj(
        &world,
        SCHEME,
        &good.replacen(&format!("{first_f}\n"), "", 1),
    );
    assert!(
        found
            .iter()
            .any(|k| matches!(k, FaultKind::BadMesh { first, .. } if first.contains("edge"))),
        "{found:#?}"
    );
}

/// The OBJ of another terrain, written into the world.
fn obj_of(scheme: &str) -> String {
    let scheme = Scheme::from_csv(scheme, None).unwrap();
    let terrain = rse_core::generate(&scheme, 3, 1);
    rse_core::export::obj(&terrain.mesh(), Some("terrain.mtl"))
}

const PEAK_A: &str = "# size: 10x10\n# base: 0.05\ntype,height,angle,x1,y1\npeak,3,90,2,5\n";

#[test]
fn volume_bounds_and_tops_of_a_sound_mesh_of_another_terrain() {
    let dir = tempfile::tempdir().unwrap();
    // The mesh of a terrain with one block fewer (a longer mesh would be
    // refused unread): less volume.
    let one_more = format!("{PEAK_A}peak,1,90,8,8\n");
    let fuller = write_world(dir.path(), "world_0000", &one_more, &Templates::builtin());
    let found = replace_obj(&fuller, &one_more, &obj_of(PEAK_A));
    assert!(
        found.iter().any(
            |k| matches!(k, FaultKind::VolumeDiffers { measured, expected } if measured < expected)
        ),
        "{found:#?}"
    );
    let world = write_world(dir.path(), "world_0001", PEAK_A, &Templates::builtin());
    // Taller: other bounds.
    let taller = obj_of(&PEAK_A.replace("peak,3,", "peak,5,"));
    let found = replace_obj(&world, PEAK_A, &taller);
    assert!(
        found
            .iter()
            .any(|k| matches!(k, FaultKind::BoundsDiffer { .. })),
        "{found:#?}"
    );
    // The peak elsewhere: same volume, same bounds, tops misplaced.
    let moved = obj_of(&PEAK_A.replace(",2,5", ",7,5"));
    let found = replace_obj(&world, PEAK_A, &moved);
    assert!(
        found
            .iter()
            .any(|k| matches!(k, FaultKind::TopMisplaced { .. })),
        "{found:#?}"
    );
    assert!(
        !found.iter().any(|k| matches!(
            k,
            FaultKind::VolumeDiffers { .. } | FaultKind::BoundsDiffer { .. }
        )),
        "{found:#?}"
    );
}

/// The physics smoke test finds a mesh without tops: bodies sink. `check`
/// runs it on meshes that match their rebuild only (a forged one is not
/// examined further, physics least of all), so here it is driven directly
/// on the holed mesh, as `check` would have.
#[cfg(feature = "physics")]
#[test]
fn physics_bodies_fall_through_a_mesh_without_tops() {
    let dir = tempfile::tempdir().unwrap();
    let world = good_world(dir.path());
    let good = std::fs::read_to_string(world.join("meshes/terrain.obj")).unwrap();
    // Drop every upward face (normal 5 is +z).
    let holed: String = good
        .split_inclusive('\n')
        .filter(|l| !(l.starts_with("f ") && l.contains("//5 ")))
        .collect();
    replace_obj(&world, SCHEME, &holed);
    let mesh = rse_verify::read_obj(holed.as_bytes()).unwrap();
    let terrain = rse_core::generate(&Scheme::from_csv(SCHEME, None).unwrap(), 3, 1);
    let model = rse_physics::TerrainModel::Mesh {
        vertices: mesh.vertices,
        triangles: mesh.triangles,
    };
    let reports = rse_physics::smoke_tests(
        &[(&model, Some("meshes/terrain.obj"))],
        &terrain,
        rse_physics::SmokeTest::default(),
    );
    let said: Vec<String> = reports[0].errors.iter().map(ToString::to_string).collect();
    assert!(said.iter().any(|e| e.contains("sank")), "{said:?}");
}

#[test]
fn leftover_and_duplicate_worlds_of_a_batch() {
    let dir = tempfile::tempdir().unwrap();
    let batch = dir.path().join("batch");
    write_world(&batch, "world_0001", SCHEME, &Templates::builtin());
    write_world(&batch, "world_00001", SCHEME, &Templates::builtin());
    std::fs::create_dir_all(batch.join(".world_0002.tmp-999/meshes")).unwrap();
    let report = check_paths(
        std::slice::from_ref(&batch),
        &CheckOptions::default(),
        &|| {},
    )
    .unwrap();
    assert!(!report.ok());
    assert_eq!(report.checked, 2, "a leftover is not a world");
    let kinds: Vec<&FaultKind> = report.batch_faults.iter().map(|f| &f.kind).collect();
    assert!(kinds.contains(&&FaultKind::Leftover), "{kinds:?}");
    assert!(
        kinds
            .iter()
            .any(|k| matches!(k, FaultKind::Duplicate { of } if of.ends_with("world_0001"))),
        "{kinds:?}"
    );
    assert!(
        report.verdict().contains("2 batch faults"),
        "{}",
        report.verdict()
    );
}

#[test]
fn faults_serialise_with_their_kind_and_fields() {
    let fault = rse_verify::Fault::of(
        "heightmap.csv",
        FaultKind::HeightDiffers {
            x: 1,
            y: 2,
            found: 3,
            expected: 4,
        },
    );
    let json = serde_json::to_value(&fault).unwrap();
    assert_eq!(json["kind"], "height_differs");
    assert_eq!(json["file"], "heightmap.csv");
    assert_eq!(json["x"], 1);
    assert_eq!(json["expected"], 4);
    assert_eq!(
        json["message"],
        "cell (1, 2) is 3, but the world regenerated from rse.json has 4"
    );
}
