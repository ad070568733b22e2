//! Error messages as a newcomer reads them: each names
//! what is wrong in the user's terms and what to do, exits 2, and leaks no
//! internal name (temporary files, empty values).

use super::{rse_gen, stderr, write_scheme};

/// A temporary folder whose name has no `.tmp` in it, so that one in a
/// message is ours.
fn folder() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("rse-messages-")
        .tempdir()
        .unwrap()
}

/// Runs rse-gen, expecting exit 2 and one `rse-gen: ` line; returns it.
fn refused(args: &[&str]) -> String {
    let out = rse_gen(args);
    let text = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {text}");
    assert!(
        text.starts_with("rse-gen: ") && text.lines().count() == 1,
        "{text}"
    );
    assert!(!text.contains(".tmp") && !text.contains("``"), "{text}");
    text
}

#[test]
fn an_output_path_that_is_a_file_is_named_as_one() {
    let dir = folder();
    let file = dir.path().join("worlds");
    std::fs::write(&file, "not a folder").unwrap();
    let text = refused(&["batch", "schemes/wall.csv", "-o", file.to_str().unwrap()]);
    assert!(
        text.contains("worlds is a file: worlds go into a folder"),
        "{text}"
    );
    let mesh = file.join("t.obj");
    let text = refused(&["mesh", "schemes/wall.csv", "-o", mesh.to_str().unwrap()]);
    assert!(
        text.contains("cannot write ") && text.contains("worlds/t.mtl"),
        "{text}"
    );
}

#[test]
fn no_worlds_is_an_error_and_no_obstacles_a_note() {
    let dir = folder();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let text = refused(&["batch", "schemes/wall.csv", "-o", out, "--amount", "0"]);
    assert!(
        text.contains("amount is 0: a batch needs at least one world"),
        "{text}"
    );
    let zero = write_scheme(dir.path(), "# amount: 0\ntype,height\nrandom,1\n");
    let text = refused(&["batch", &zero, "-o", out]);
    assert!(
        text.ends_with("scheme.csv:1: amount: invalid value `0`: needs at least one world\n"),
        "{text}"
    );

    let empty = write_scheme(dir.path(), "");
    let made = rse_gen(&["batch", &empty, "-o", out]);
    let text = stderr(&made);
    assert!(made.status.success(), "{text}");
    assert!(
        text.starts_with("rse-gen: note: ")
            && text.contains("scheme.csv has no obstacles: every world is flat"),
        "{text}"
    );
    assert!(
        text.contains("rse-gen: 1 world in "),
        "one world, not '1 worlds': {text}"
    );
    // Said once per command: preview once read the scheme twice.
    let png = dir.path().join("flat.png");
    let made = rse_gen(&["preview", &empty, "-o", png.to_str().unwrap()]);
    let text = stderr(&made);
    assert!(made.status.success(), "{text}");
    assert_eq!(text.matches("has no obstacles").count(), 1, "{text}");
}

#[test]
fn pallet_settings_without_pallets_and_empty_values_read_plainly() {
    let dir = folder();
    let scheme = write_scheme(dir.path(), "# pallet_size: 3\ntype,height\nrandom,2\n");
    let text = refused(&["heightmap", &scheme]);
    assert!(
        text.ends_with(
            "scheme.csv:1: pallet_size: is set but pallets are off; add e.g. `# pallets: 2x3`\n"
        ),
        "{text}"
    );
    let scheme = write_scheme(dir.path(), "# step_height:\ntype,height\nrandom,2\n");
    let text = refused(&["heightmap", &scheme]);
    assert!(
        text.ends_with("scheme.csv:1: step_height: no value: expected a length in metres\n"),
        "{text}"
    );
}

#[test]
fn a_different_world_says_which_setting_differs() {
    let dir = folder();
    let out = dir.path().join("w");
    let out = out.to_str().unwrap();
    let base = ["batch", "schemes/wall.csv", "-o", out, "--amount", "1"];
    assert!(
        rse_gen(&[&base[..], &["--target", "gazebo"]].concat())
            .status
            .success()
    );
    let cases = [
        (
            vec!["--target", "gazebo,mujoco"],
            "targets gazebo there, gazebo,mujoco now",
        ),
        (
            vec!["--target", "gazebo", "--seed", "3"],
            "seed 0 there, 3 now",
        ),
        (
            vec!["--target", "gazebo", "--mesh", "blocks"],
            "mesh auto there, blocks now",
        ),
        (
            vec!["--target", "gazebo", "--difficulty", "0.5"],
            "difficulty 1 there, 0.5 now",
        ),
        (
            vec!["--target", "gazebo", "--step-height", "0.05"],
            "it was made from another scheme or other global settings",
        ),
    ];
    for (extra, why) in cases {
        let text = refused(&[&base[..], &extra[..]].concat());
        assert!(
            text.contains(&format!(
                "w/world_0000 holds a different world: {why}; rerun with --force to replace it"
            )),
            "{extra:?}: {text}"
        );
    }
    let csv = std::path::Path::new(out).join("world_0000/heightmap.csv");
    std::fs::write(&csv, "edited\n").unwrap();
    let text = refused(&[&base[..], &["--target", "gazebo"]].concat());
    assert!(
        text.contains(
            "heightmap.csv differs, though it was made with the same settings (changed since?)"
        ),
        "{text}"
    );
}
