//! What the `check` tests share: small worlds written to disk, and ways
//! to damage them as a forger would.
#![allow(dead_code)] // each test file uses its own part

use std::path::{Path, PathBuf};

use rse_core::Scheme;
use rse_verify::{CheckOptions, FaultKind, WorldReport, check_world};
use rse_world::{
    Manifest, MeshMode, Targets, Templates, WorldFiles, WorldOptions, build_world, sha256_hex,
};

/// A small scheme with something of every height.
pub const SCHEME: &str = "# size: 12x10\n# base: 0.05\ntype,height,angle,x1,y1,x2,y2\n\
    random,2,,,,,\nwall,4,45,2,2,9,6\n";

pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Writes the files of `world` under `root`.
pub fn write_files(root: &Path, world: &WorldFiles) {
    for (path, bytes) in &world.files {
        let path = root.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, bytes).unwrap();
    }
}

/// Writes world `index` of `scheme` into `dir/name` and returns its path.
pub fn write_world(dir: &Path, name: &str, scheme: &str, templates: &Templates) -> PathBuf {
    let scheme = Scheme::from_csv(scheme, None).unwrap();
    let options = WorldOptions {
        targets: Targets::all(),
        mesh: MeshMode::Single,
        ..WorldOptions::default()
    };
    let world = build_world(&scheme, 3, 1, name.to_owned(), &options, templates).unwrap();
    let root = dir.join(name);
    write_files(&root, &world);
    root
}

pub fn good_world(dir: &Path) -> PathBuf {
    write_world(dir, "world_0001", SCHEME, &Templates::builtin())
}

/// Rewrites every hash in `rse.json` to match the files on disk, as a
/// careful forger would.
pub fn forge(world: &Path) {
    let path = world.join("rse.json");
    let mut manifest = Manifest::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap();
    for (file, digest) in &mut manifest.files {
        if let Ok(bytes) = std::fs::read(world.join(file)) {
            *digest = sha256_hex(&bytes);
        }
    }
    std::fs::write(&path, manifest.to_json()).unwrap();
}

/// Marks the world as made with templates `check` does not have: its
/// rendered files are then compared by hash alone, and examined (their
/// references, their XML) as files that pass.
pub fn hashed_only(world: &Path) {
    edit_manifest(world, |m| m.templates = rse_world::TemplateSet::Custom);
}

/// Edits `rse.json` as a value.
pub fn edit_manifest(world: &Path, edit: impl FnOnce(&mut Manifest)) {
    let path = world.join("rse.json");
    let mut manifest = Manifest::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap();
    edit(&mut manifest);
    std::fs::write(&path, manifest.to_json()).unwrap();
}

pub fn check(world: &Path) -> WorldReport {
    check_world(world, &CheckOptions::default())
}

/// The report must fail, with a fault of `file` matching `kind`.
pub fn assert_fault(report: &WorldReport, file: Option<&str>, kind: impl Fn(&FaultKind) -> bool) {
    assert!(!report.ok, "{report:#?}");
    assert!(
        report
            .faults
            .iter()
            .any(|f| f.file.as_deref() == file && kind(&f.kind)),
        "no such fault of {file:?} in {:#?}",
        report.faults
    );
}
