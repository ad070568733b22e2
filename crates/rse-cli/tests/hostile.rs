//! Hostile input to `batch` and the scheme reader: planted
//! links and FIFOs in a folder a rerun compares, a lock planted as a link,
//! a file size limit, schemes that look right and are not.

use std::path::Path;
use std::process::Command;

use super::{rse_gen, stderr, stdout, write_scheme};

fn batch(out: &Path, extra: &[&str]) -> std::process::Output {
    let out = out.to_str().unwrap();
    let mut args = vec![
        "batch",
        "schemes/six_obstacles.csv",
        "-o",
        out,
        "--amount",
        "2",
    ];
    args.extend_from_slice(extra);
    rse_gen(&args)
}

/// Item 3: a rerun compares the worlds already there by descriptor: a
/// `heightmap.csv` planted as a link to `/dev/zero` (2 GB read before
/// ENOMEM) or as a FIFO (the batch hung) stops the run with the path.
#[test]
fn a_rerun_stops_at_a_planted_link_or_fifo_with_its_path() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    stdout(&batch(&out, &[]));
    // A rerun (with or without --force) must stop naming `what`, exit 2.
    let stops_at = |extra: &[&str], what: &str| {
        let done = batch(&out, extra);
        let said = stderr(&done);
        assert_eq!(done.status.code(), Some(2), "{said}");
        assert!(
            said.contains(&format!("{what} is a link or special file")),
            "{said}"
        );
    };
    let planted = out.join("world_0001/heightmap.csv");
    std::fs::remove_file(&planted).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &planted).unwrap();
    stops_at(&[], "world_0001/heightmap.csv");

    std::fs::remove_file(&planted).unwrap();
    let fifo = Command::new("mkfifo").arg(&planted).status().unwrap();
    assert!(fifo.success());
    stops_at(&["--force"], "world_0001/heightmap.csv");

    // A world folder that is a link is not followed either.
    std::fs::remove_file(&planted).unwrap();
    let moved = dir.path().join("elsewhere");
    std::fs::rename(out.join("world_0001"), &moved).unwrap();
    std::os::unix::fs::symlink(&moved, out.join("world_0001")).unwrap();
    stops_at(&[], "world_0001");
}

/// Item 8: the lock lives in the output folder, hidden, and nothing is
/// made in the shared temporary folder; a lock planted as a link is
/// refused, its target never created.
#[test]
fn the_lock_lives_with_the_output_and_a_planted_link_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let temp = dir.path().join("tmp");
    std::fs::create_dir(&temp).unwrap();
    let out = dir.path().join("out");
    let run = |out: &Path| {
        Command::new(env!("CARGO_BIN_EXE_rse-gen"))
            .args(["batch", "schemes/wall.csv", "--amount", "1", "-o"])
            .arg(out)
            .current_dir(super::repo())
            .env("TMPDIR", &temp)
            .output()
            .unwrap()
    };
    stdout(&run(&out));
    assert_eq!(
        std::fs::read_dir(&temp).unwrap().count(),
        0,
        "nothing in the temporary folder"
    );
    // A finished run leaves the worlds only: its lock file is removed.
    let names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(names, ["world_0000"]);

    // The lock of shard 0 of 1, by the name the batch gives it, planted as
    // a link to a file that does not exist yet.
    let hash = rse_world::sha256_hex(b"shard-0-of-1");
    let lock = out.join(format!(".rse-{}.lock", &hash[..16]));
    let target = dir.path().join("created-through-the-link");
    std::os::unix::fs::symlink(&target, &lock).unwrap();
    let done = run(&out);
    assert_eq!(done.status.code(), Some(2), "{}", stderr(&done));
    assert!(
        stderr(&done).contains("is a link or special file"),
        "{}",
        stderr(&done)
    );
    assert!(!target.exists(), "the link's target was created");
}

/// Item 11: under `ulimit -f` the write fails with EFBIG and the batch
/// stops with the path, exit 2, as on a full disk (it died of SIGXFSZ
/// without a word).
#[test]
fn a_file_size_limit_stops_the_batch_with_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let done = Command::new("sh")
        .arg("-c")
        .arg("ulimit -f 8; exec \"$0\" batch schemes/six_obstacles.csv --target obj -o \"$1\"")
        .arg(env!("CARGO_BIN_EXE_rse-gen"))
        .arg(&out)
        .current_dir(super::repo())
        .output()
        .unwrap();
    assert_eq!(
        done.status.code(),
        Some(2),
        "{:?} {}",
        done.status,
        stderr(&done)
    );
    let said = stderr(&done);
    assert!(
        said.contains("cannot write") && said.contains("too large"),
        "{said}"
    );
}

/// The stderr of `rse-gen heightmap` on the scheme `text`, which must be
/// refused with exit 2.
fn refused(dir: &Path, text: &str) -> String {
    let scheme = write_scheme(dir, text);
    let done = rse_gen(&["heightmap", &scheme]);
    assert_eq!(done.status.code(), Some(2), "{text:.200}");
    stderr(&done)
}

/// Item 9 (each case in rse-core's tests too): a comment spelling a
/// global's name with a slip is an error with a "did you mean", on its
/// line; free text stays a note. Lengths the mesh cannot hold apart are
/// refused, `-0` is told as what it is, and a huge field is quoted short.
#[test]
fn schemes_that_look_right_are_refused_plainly() {
    let dir = tempfile::tempdir().unwrap();
    for (line, near) in [
        ("# step-height: 0.05", "step_height"),
        ("# Seeds: 3", "seed"),
    ] {
        let said = refused(
            dir.path(),
            &format!("{line}\n# size: 5x5\ntype,height\nrandom,2\n"),
        );
        assert!(
            said.contains(&format!(
                "scheme.csv:1: {}: ",
                &line[2..line.find(':').unwrap()]
            )),
            "{said}"
        );
        assert!(said.contains(&format!("did you mean `{near}`")), "{said}");
    }
    let free = write_scheme(
        dir.path(),
        "# A stepfield for the Husky: run 2\n# size: 5x5\ntype,height\nrandom,2\n",
    );
    stdout(&rse_gen(&["heightmap", &free]));

    for (global, value) in [
        ("step_height", "1e-7"),
        ("base", "1e-320"),
        ("block_size", "1e-320"),
    ] {
        let said = refused(
            dir.path(),
            &format!("# size: 5x5\n# {global}: {value}\ntype,height\nrandom,2\n"),
        );
        assert!(said.contains(global) && said.contains("0.001 m"), "{said}");
    }
    let said = refused(dir.path(), "# size: 5x5\ntype,height\nrandom,-0\n");
    assert!(
        said.contains("`-0` is not a whole number") && !said.contains("above the largest"),
        "{said}"
    );
    let said = refused(
        dir.path(),
        &format!(
            "# size: 5x5\ntype,height\nrandom,{}\n",
            "x".repeat(10 << 20)
        ),
    );
    assert!(said.len() < 1000, "{} bytes of stderr", said.len());
}
