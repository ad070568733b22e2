//! Regressions: hostile input found by the hardening rounds, each attack
//! built here against the real binary. To `batch` and the scheme reader:
//! planted links and FIFOs in a folder a rerun compares, a lock planted as
//! a link, a file size limit, schemes that look right and are not. To
//! `check` and a batch rerun: what a batch folder, a template folder and the
//! names in them can do; the two must agree on every world, and neither may
//! crash.

use std::path::Path;
use std::process::Command;

use super::{all_targets, rse_gen, stderr, stdout, write_scheme};

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

/// `batch` of two `wall.csv` worlds into `out`.
fn wall_batch(out: &Path, extra: &[&str]) -> std::process::Output {
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
    stdout(&wall_batch(&out, &[]));
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
    let rerun = wall_batch(&out, &[]);
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
    let rerun = wall_batch(&out, &[]);
    assert_eq!(rerun.status.code(), Some(2));
    assert!(
        stderr(&rerun).contains("unexpected folder extra"),
        "{}",
        stderr(&rerun)
    );
    std::fs::remove_dir(out.join("world_0000/extra")).unwrap();
    let rerun = wall_batch(&out, &[]);
    assert_eq!(rerun.status.code(), Some(2));
    assert!(
        stderr(&rerun).contains("heightmap.csv is hard-linked (2 links)"),
        "{}",
        stderr(&rerun)
    );
    // --force writes the world afresh: its own file again, and both pass.
    stdout(&wall_batch(&out, &["--force"]));
    stdout(&check(&out));
}

/// A world moved into another index's folder passed `check` (its files
/// are its own) while the rerun refused it. A world's name is its folder's:
/// both refuse it now, however the folder is named on the command line.
#[test]
fn a_world_renamed_into_another_index_folder_fails_check_and_the_rerun() {
    let dir = tempfile::tempdir().unwrap();
    let out = two_worlds(dir.path());
    std::fs::remove_dir_all(out.join("world_0000")).unwrap();
    std::fs::rename(out.join("world_0001"), out.join("world_0000")).unwrap();
    let link = dir.path().join("link");
    std::os::unix::fs::symlink(out.join("world_0000"), &link).unwrap();
    let said = "the folder is named world_0000, but its rse.json is another world's (index 1)";
    for path in [out.clone(), out.join("world_0000/."), link] {
        let checked = check(&path);
        assert_eq!(checked.status.code(), Some(1), "{}", path.display());
        let printed = String::from_utf8_lossy(&checked.stdout);
        assert!(printed.contains(said), "{}: {printed}", path.display());
    }
    let rerun = wall_batch(&out, &[]);
    assert_eq!(rerun.status.code(), Some(2));
    assert!(
        stderr(&rerun).contains("holds a different world"),
        "{}",
        stderr(&rerun)
    );
}

/// A world name reaches SDF, MJCF, URDF and `model.config` (attributes and
/// XML comments): `a"--><b` from the command line is refused before
/// anything is written, and from a forged `rse.json` it is a fault that
/// does not repeat the name.
#[test]
fn a_world_name_that_is_markup_is_refused_from_the_command_line_and_rse_json() {
    let dir = tempfile::tempdir().unwrap();
    let named = dir.path().join("a\"--><b");
    let made = rse_gen(&[
        "atlas",
        "schemes/wall.csv",
        "--rows",
        "1",
        "--cols",
        "1",
        "-o",
        named.to_str().unwrap(),
    ]);
    assert_eq!(made.status.code(), Some(2), "{}", stderr(&made));
    assert!(
        stderr(&made).contains("cannot name a world"),
        "{}",
        stderr(&made)
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing written"
    );

    let out = two_worlds(dir.path());
    let manifest = out.join("world_0000/rse.json");
    let mut json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&manifest).unwrap()).unwrap();
    json["world"] = "a\"--><b".into();
    std::fs::write(&manifest, serde_json::to_vec(&json).unwrap()).unwrap();
    let checked = check(&out);
    assert_eq!(checked.status.code(), Some(1));
    let printed = String::from_utf8_lossy(&checked.stdout);
    assert!(
        printed.contains("its world name is not a world name rse writes"),
        "{printed}"
    );
    assert!(
        !printed.contains("--><b"),
        "the forged name is not repeated: {printed}"
    );
}

/// A file named with ESC and BEL reached the terminal raw in `check`'s
/// output (colours, a bell, a rewritten line): printed escaped now.
#[test]
fn control_characters_in_file_names_are_printed_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let out = two_worlds(dir.path());
    std::fs::write(out.join("world_0000/x\u{1b}[31mred\u{7}"), b"").unwrap();
    let checked = check(&out);
    assert_eq!(checked.status.code(), Some(1));
    assert!(!checked.stdout.iter().any(|&b| b == 0x1b || b == 0x07));
    let printed = String::from_utf8_lossy(&checked.stdout);
    assert!(
        printed.contains(r"x\u{1b}[31mred\u{7}: not a file of the world"),
        "{printed}"
    );
}

/// `batch` of a whole folder and `batch --shard 0/2` of the same folder at
/// once: one failed with "Directory not empty", and each removed the
/// other's temporary folders as leftovers. Overlapping runs now exclude
/// each other (the second says which shard is being written); disjoint
/// shards still run side by side, and the tree ends as one run's.
#[test]
fn overlapping_batches_exclude_each_other_and_disjoint_shards_do_not() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let one = dir.path().join("one");
    let args = |out: &Path, shard: &str| {
        let mut args: Vec<String> = [
            "batch",
            "schemes/six_obstacles.csv",
            "-o",
            out.to_str().unwrap(),
            "--amount",
            "24",
            "--target",
            &all_targets(),
        ]
        .map(String::from)
        .into();
        if !shard.is_empty() {
            args.extend(["--shard".to_owned(), shard.to_owned()]);
        }
        args
    };
    let spawn = |shard: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_rse-gen"))
            .args(args(&out, shard))
            .current_dir(super::repo())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap()
    };
    // Many tries at once, so some truly overlap in time.
    let runs: Vec<_> = ["", "0/2", "", "1/2", "0/2"]
        .into_iter()
        .map(|shard| (shard, spawn(shard)))
        .collect();
    let mut busy = 0;
    for (shard, run) in runs {
        let done = run.wait_with_output().unwrap();
        let said = String::from_utf8_lossy(&done.stderr);
        match done.status.code() {
            Some(0) => {}
            Some(2) if said.contains("another rse-gen batch is writing shard") => busy += 1,
            other => panic!("{shard}: {other:?} {said}"),
        }
        assert!(!said.contains("not empty"), "{shard}: {said}");
    }
    // Whatever ran or was refused, a rerun finishes the same tree as one run.
    stdout(&rse_gen(
        &args(&out, "")
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
    ));
    stdout(&rse_gen(
        &args(&one, "")
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
    ));
    let list = |d: &Path| rse_world::list_files(d).unwrap();
    assert_eq!(list(&out), list(&one));
    for path in list(&one) {
        assert!(
            std::fs::read(out.join(&path)).unwrap() == std::fs::read(one.join(&path)).unwrap(),
            "{path}"
        );
    }
    eprintln!("{busy} of 5 runs found an overlapping run writing");
}

/// A template folder handed to `batch` and `check --template`: a link in
/// it copied a secret into every world (and `check --template` said
/// good), a FIFO hung the batch. Both are refused, naming the entry, and
/// the batch writes nothing.
#[cfg(unix)]
#[test]
fn a_template_folder_with_a_link_or_fifo_is_refused_by_batch_and_check() {
    let dir = tempfile::tempdir().unwrap();
    let out = two_worlds(dir.path());
    let secret = dir.path().join("secret.txt");
    std::fs::write(&secret, "secret").unwrap();
    for (name, fifo) in [("key.txt", false), ("pipe", true)] {
        let templates = dir.path().join(format!("templates-{name}"));
        std::fs::create_dir_all(templates.join("urdf")).unwrap();
        let planted = templates.join("urdf").join(name);
        if fifo {
            assert!(
                std::process::Command::new("mkfifo")
                    .arg(&planted)
                    .status()
                    .unwrap()
                    .success()
            );
        } else {
            std::os::unix::fs::symlink(&secret, &planted).unwrap();
        }
        let fresh = dir.path().join(format!("fresh-{name}"));
        let run = wall_batch(&fresh, &["--template", templates.to_str().unwrap()]);
        assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
        assert!(stderr(&run).contains(name), "{}", stderr(&run));
        assert!(!fresh.exists(), "the failed batch left {}", fresh.display());
        let checked = rse_gen(&[
            "check",
            out.to_str().unwrap(),
            "--template",
            templates.to_str().unwrap(),
        ]);
        assert_eq!(checked.status.code(), Some(2), "{}", stderr(&checked));
        assert!(stderr(&checked).contains(name), "{}", stderr(&checked));
    }
}

/// A failed command removes every file and folder it made: a batch whose
/// template fails to render leaves no output folder (nor the folders made
/// for it), and a mesh whose OBJ cannot be written leaves no `.mtl`.
#[test]
fn failed_commands_leave_nothing_they_made() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("templates");
    std::fs::create_dir_all(templates.join("urdf")).unwrap();
    std::fs::write(templates.join("urdf/broken.txt.j2"), "{{ no_such_value }}").unwrap();
    let out = dir.path().join("new/deeper/out");
    let run = wall_batch(
        &out,
        &[
            "--template",
            templates.to_str().unwrap(),
            "--target",
            "urdf",
        ],
    );
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(stderr(&run).contains("no_such_value"), "{}", stderr(&run));
    assert!(
        !dir.path().join("new").exists(),
        "the failed batch left its folders"
    );
    // The OBJ's name is taken by a folder: its .mtl, written first, goes.
    std::fs::create_dir(dir.path().join("t.obj")).unwrap();
    std::fs::write(dir.path().join("t.obj/inside"), "x").unwrap();
    let obj = dir.path().join("t.obj");
    let run = rse_gen(&["mesh", "schemes/wall.csv", obj.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(
        !dir.path().join("t.mtl").exists(),
        "the failed mesh left its .mtl"
    );
}
