//! Hostile input, third round: what a batch folder, a template folder and
//! the names in them can do to `check` and a batch rerun, each attack built
//! here. The two must agree on every world, and neither may crash.

use std::path::Path;

use super::{rse_gen, stderr, stdout};

fn batch(out: &Path, extra: &[&str]) -> std::process::Output {
    let out = out.to_str().unwrap();
    let mut args = vec!["batch", "schemes/wall.csv", "-o", out, "--amount", "2"];
    args.extend_from_slice(extra);
    rse_gen(&args)
}

fn check(path: &Path) -> std::process::Output {
    rse_gen(&["check", path.to_str().unwrap()])
}

/// A fresh batch of two worlds in `dir/out`.
fn two_worlds(dir: &Path) -> std::path::PathBuf {
    let out = dir.join("out");
    stdout(&batch(&out, &[]));
    out
}

/// A chain of 6000 folders inside a world overflowed the stack of `check`
/// and of the rerun (exit 134). Both now stop at a depth and say so.
#[test]
fn a_folder_chain_thousands_deep_is_a_fault_not_a_crash() {
    let dir = tempfile::tempdir().unwrap();
    let out = two_worlds(dir.path());
    let mut deep = out.join("world_0001");
    let mut made = 0;
    while made < 6000 {
        deep = deep.join("d");
        if std::fs::create_dir(&deep).is_err() {
            break; // PATH_MAX reached: deep enough
        }
        made += 1;
    }
    assert!(made > 1000, "only {made} levels made");
    let checked = check(&out);
    assert_eq!(checked.status.code(), Some(1), "{}", stderr(&checked));
    let said = String::from_utf8_lossy(&checked.stdout);
    assert!(said.contains("folders deep: not listed"), "{said}");
    let rerun = batch(&out, &[]);
    assert_eq!(rerun.status.code(), Some(2), "{}", stderr(&rerun));
    assert!(
        stderr(&rerun).contains("folders deep: not listed"),
        "{}",
        stderr(&rerun)
    );
}

/// The rerun and `check` agree: an extra empty folder, and a world file
/// hard-linked to a file outside the world, fail both (the empty folder
/// passed both; the hard link passed the rerun).
#[test]
fn rerun_and_check_agree_on_empty_folders_and_hard_links() {
    let dir = tempfile::tempdir().unwrap();
    let out = two_worlds(dir.path());
    std::fs::create_dir(out.join("world_0000/extra")).unwrap();
    std::fs::hard_link(
        out.join("world_0001/heightmap.csv"),
        dir.path().join("outside.csv"),
    )
    .unwrap();
    let checked = check(&out);
    assert_eq!(checked.status.code(), Some(1));
    let said = String::from_utf8_lossy(&checked.stdout);
    assert!(said.contains("world_0000: extra"), "{said}");
    assert!(said.contains("world_0001: heightmap.csv"), "{said}");
    let rerun = batch(&out, &[]);
    assert_eq!(rerun.status.code(), Some(2));
    assert!(
        stderr(&rerun).contains("unexpected folder extra"),
        "{}",
        stderr(&rerun)
    );
    std::fs::remove_dir(out.join("world_0000/extra")).unwrap();
    let rerun = batch(&out, &[]);
    assert_eq!(rerun.status.code(), Some(2));
    assert!(
        stderr(&rerun).contains("heightmap.csv is hard-linked (2 links)"),
        "{}",
        stderr(&rerun)
    );
    // --force writes the world afresh: its own file again, and both pass.
    stdout(&batch(&out, &["--force"]));
    stdout(&check(&out));
}
