//! `rse-gen batch`: identical trees whatever the jobs and shards, resuming
//! after SIGKILL, never overwriting a different world, template errors.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::Duration;

use super::{all_targets, repo, rse_gen, stderr, stdout};

/// Every file under `dir` by relative path, hidden leftovers included.
fn tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    rse_world::list_files(dir)
        .unwrap()
        .into_iter()
        .map(|path| {
            let bytes = std::fs::read(dir.join(&path)).unwrap();
            (path, bytes)
        })
        .collect()
}

fn batch(out: &Path, extra: &[&str]) -> Output {
    let out = out.to_str().unwrap();
    let mut args = vec!["batch", "schemes/six_obstacles.csv", "-o", out];
    args.extend_from_slice(extra);
    rse_gen(&args)
}

fn assert_same_tree(a: &Path, b: &Path) {
    let (ta, tb) = (tree(a), tree(b));
    assert_eq!(
        ta.keys().collect::<Vec<_>>(),
        tb.keys().collect::<Vec<_>>(),
        "same files"
    );
    for (path, bytes) in &ta {
        assert!(tb[path] == *bytes, "{path} differs");
    }
}

#[test]
fn jobs_and_shards_give_identical_trees() {
    let dir = tempfile::tempdir().unwrap();
    let [one, two, shards] = ["one", "two", "shards"].map(|n| dir.path().join(n));
    let common = ["--amount", "9", "--target", &all_targets()];
    stdout(&batch(&one, &[&common[..], &["--jobs", "1"]].concat()));
    stdout(&batch(&two, &[&common[..], &["--jobs", "2"]].concat()));
    for k in 0..4 {
        let shard = format!("{k}/4");
        stdout(&batch(
            &shards,
            &[&common[..], &["--shard", &shard]].concat(),
        ));
    }
    assert_eq!(
        tree(&one)
            .keys()
            .filter(|p| p.ends_with("rse.json"))
            .count(),
        9
    );
    assert_same_tree(&one, &two);
    assert_same_tree(&one, &shards);
}

/// `rse-gen batch ... --shard auto` with these Slurm array variables only.
fn batch_in_slurm_array(out: &Path, vars: &[(&str, &str)]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rse-gen"));
    for name in [
        "SLURM_ARRAY_TASK_ID",
        "SLURM_ARRAY_TASK_MIN",
        "SLURM_ARRAY_TASK_COUNT",
        "SLURM_ARRAY_TASK_STEP",
    ] {
        command.env_remove(name);
    }
    command
        .args([
            "batch",
            "schemes/six_obstacles.csv",
            "-o",
            out.to_str().unwrap(),
            "--amount",
            "10",
        ])
        .args(["--shard", "auto"])
        .envs(vars.iter().copied())
        .current_dir(repo())
        .output()
        .expect("rse-gen runs")
}

#[test]
fn shard_auto_is_the_slurm_array_tasks_shard_and_a_usage_error_outside_one() {
    let dir = tempfile::tempdir().unwrap();
    let (auto, explicit) = (dir.path().join("auto"), dir.path().join("explicit"));
    // Task 12 of an array 10-16:2 (ids 10, 12, 14, 16): shard 1 of 4.
    let vars = [
        ("SLURM_ARRAY_TASK_ID", "12"),
        ("SLURM_ARRAY_TASK_MIN", "10"),
        ("SLURM_ARRAY_TASK_COUNT", "4"),
        ("SLURM_ARRAY_TASK_STEP", "2"),
    ];
    stdout(&batch_in_slurm_array(&auto, &vars));
    stdout(&batch(&explicit, &["--amount", "10", "--shard", "1/4"]));
    assert_same_tree(&auto, &explicit);

    let outside = batch_in_slurm_array(&dir.path().join("outside"), &[]);
    assert_eq!(outside.status.code(), Some(2), "{}", stderr(&outside));
    assert!(
        stderr(&outside).contains("SLURM_ARRAY_TASK_ID is not set"),
        "{}",
        stderr(&outside)
    );
    let bad = batch_in_slurm_array(
        &dir.path().join("bad"),
        &[
            ("SLURM_ARRAY_TASK_ID", "x"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ],
    );
    assert_eq!(bad.status.code(), Some(2), "{}", stderr(&bad));
    assert!(
        stderr(&bad).contains("SLURM_ARRAY_TASK_ID=\"x\""),
        "{}",
        stderr(&bad)
    );
    assert!(
        !dir.path().join("outside").exists() && !dir.path().join("bad").exists(),
        "nothing written"
    );
}

#[test]
fn a_shard_writes_exactly_its_worlds() {
    let dir = tempfile::tempdir().unwrap();
    stdout(&batch(dir.path(), &["--amount", "10", "--shard", "1/4"]));
    let mut names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["world_0001", "world_0005", "world_0009"]);
}

#[test]
fn a_batch_killed_at_any_moment_resumes_to_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let (clean, killed) = (dir.path().join("clean"), dir.path().join("killed"));
    let common = ["--amount", "24", "--target", &all_targets(), "--jobs", "2"];
    let started = std::time::Instant::now();
    stdout(&batch(&clean, &common));
    let whole = started.elapsed();
    // Kill at spread-out moments, as fractions of an uninterrupted run (a
    // fixed schedule in milliseconds finished the batch before the last
    // kill on a fast machine): before anything, among the first worlds,
    // midway; each run resumes what the last one left, and together they
    // run about half a batch's time.
    for fraction in [0.0, 0.01, 0.03, 0.06, 0.1, 0.15, 0.2] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rse-gen"))
            .args(["batch", "schemes/six_obstacles.csv", "-o"])
            .arg(&killed)
            .args(common)
            .current_dir(repo())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(whole.mul_f64(fraction));
        child.kill().unwrap(); // SIGKILL
        child.wait().unwrap();
    }
    // Finished worlds only: a kill can leave a temporary folder that
    // already holds its rse.json (`.world_0007.tmp-PID/`), which the rerun
    // removes and writes again, not counting it as already there.
    let worlds = |dir: &Path| {
        tree(dir)
            .keys()
            .filter(|p| p.ends_with("/rse.json") && !p.starts_with('.'))
            .count()
    };
    let interrupted = worlds(&killed);
    assert!(
        interrupted < 24,
        "the kills came too late to interrupt anything"
    );
    let last = batch(&killed, &common);
    stdout(&last);
    assert!(
        stderr(&last).contains(&format!("{interrupted} already there")),
        "{}",
        stderr(&last)
    );
    assert_same_tree(&clean, &killed);
}

/// Ctrl-C (SIGINT) once exited silently: now the worlds being written are
/// finished, the run says what it kept and that a rerun resumes, and exits
/// 130; the rerun ends identical to an uninterrupted run.
#[test]
fn ctrl_c_says_what_was_kept_and_a_rerun_finishes() {
    let dir = tempfile::tempdir().unwrap();
    let (clean, stopped) = (dir.path().join("clean"), dir.path().join("stopped"));
    let common = ["--amount", "400", "--target", "obj", "--jobs", "2"];
    stdout(&batch(&clean, &common));
    let child = Command::new(env!("CARGO_BIN_EXE_rse-gen"))
        .args(["batch", "schemes/six_obstacles.csv", "-o"])
        .arg(&stopped)
        .args(common)
        .current_dir(repo())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Once the first world is there, the run is under way.
    while !stopped.join("world_0000").exists() {
        std::thread::sleep(Duration::from_millis(1));
    }
    let pid = child.id().to_string();
    assert!(
        Command::new("kill")
            .args(["-INT", &pid])
            .status()
            .unwrap()
            .success()
    );
    let done = child.wait_with_output().unwrap();
    let message = String::from_utf8_lossy(&done.stderr).into_owned();
    assert_eq!(done.status.code(), Some(130), "{message}");
    assert!(message.contains("rse-gen: interrupted:"), "{message}");
    assert!(message.contains("Rerun the same command"), "{message}");
    assert!(message.contains("not started"), "{message}");
    assert!(stdout(&batch(&stopped, &common)).is_empty());
    assert_same_tree(&clean, &stopped);
}

#[test]
fn a_rerun_skips_whole_worlds_and_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let first = batch(dir.path(), &["--amount", "3"]);
    // On a pipe: no progress bar, no data on stdout, one summary line.
    assert_eq!(stdout(&first), "");
    let message = stderr(&first);
    assert!(
        message.lines().count() == 1 && message.starts_with("rse-gen: 3 worlds in "),
        "{message}"
    );
    let before = tree(dir.path());
    let again = batch(dir.path(), &["--amount", "3"]);
    stdout(&again);
    assert!(
        stderr(&again).contains("0 written, 3 already there"),
        "{}",
        stderr(&again)
    );
    assert_eq!(before, tree(dir.path()));
}

/// A grown batch keeps its worlds: names depend on the index alone (from
/// 10,000 to 10,001 worlds the width once changed and every world was
/// written again beside the old ones).
#[test]
fn a_grown_batch_keeps_its_worlds_and_adds_the_new_ones() {
    let dir = tempfile::tempdir().unwrap();
    assert!(batch(dir.path(), &["--amount", "3"]).status.success());
    let grown = batch(dir.path(), &["--amount", "5"]);
    assert!(
        stderr(&grown).contains("2 written, 3 already there"),
        "{}",
        stderr(&grown)
    );
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(names.len(), 5, "{names:?}");
    assert!(
        names.iter().all(|n| n.len() == "world_0000".len()),
        "{names:?}"
    );
}

#[test]
fn a_different_world_is_replaced_only_with_force() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, out) = (dir.path().join("ref"), dir.path().join("out"));
    stdout(&batch(&reference, &["--amount", "3"]));
    stdout(&batch(&out, &["--amount", "3"]));
    let damaged = out.join("world_0001/heightmap.csv");
    std::fs::write(&damaged, "0\n").unwrap();

    let refused = batch(&out, &["--amount", "3"]);
    assert_eq!(refused.status.code(), Some(2));
    let message = stderr(&refused);
    assert!(
        message.contains("world_0001")
            && message.contains("heightmap.csv differs")
            && message.contains("--force"),
        "{message}"
    );
    assert_eq!(std::fs::read_to_string(&damaged).unwrap(), "0\n");

    // Another seed is another batch: refused too.
    let other_seed = batch(&out, &["--amount", "3", "--seed", "5"]);
    assert_eq!(other_seed.status.code(), Some(2), "{}", stderr(&other_seed));

    let forced = batch(&out, &["--amount", "3", "--force"]);
    assert!(
        stderr(&forced).contains("1 replaced"),
        "{}",
        stderr(&forced)
    );
    assert_same_tree(&reference, &out);
}

/// A plain file named like a world, replaced under `--force`: no leftover
/// stays (it stayed as a file `.world_0000.old-PID`, which every later run
/// failed to remove as a folder while `check` said good); a leftover that
/// is a file is removed by the next run and reported by `check`; a world
/// named twice on `check`'s line is one world, never its own duplicate.
#[test]
fn force_over_a_plain_file_leaves_nothing_behind_and_a_world_named_twice_is_one() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, out) = (dir.path().join("ref"), dir.path().join("out"));
    stdout(&batch(&reference, &["--amount", "2"]));
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("world_0000"), "a note, not a world\n").unwrap();
    let forced = batch(&out, &["--amount", "2", "--force"]);
    assert!(
        stderr(&forced).contains("1 replaced"),
        "{}",
        stderr(&forced)
    );
    assert_same_tree(&reference, &out);

    std::fs::write(
        out.join(".world_0001.old-99"),
        "moved aside, then cut short",
    )
    .unwrap();
    let check = |paths: &[&Path]| {
        let texts: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
        let mut args = vec!["check"];
        args.extend(texts.iter().map(String::as_str));
        rse_gen(&args)
    };
    let said = |o: &Output| {
        format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        )
    };
    let found = check(&[&out]);
    assert_eq!(found.status.code(), Some(1), "a leftover file is a fault");
    assert!(
        said(&found).contains(".world_0001.old-99"),
        "{}",
        said(&found)
    );
    let again = batch(&out, &["--amount", "2"]);
    assert!(again.status.success(), "{}", stderr(&again));
    assert_same_tree(&reference, &out);

    let twice = check(&[&out, &out.join("world_0001"), &out]);
    let said = stdout(&twice) + &stderr(&twice);
    assert!(twice.status.success(), "{said}");
    assert!(
        said.contains("checked 2 worlds: 2 good, 0 failed") && !said.contains("duplicate"),
        "{said}"
    );
}

#[test]
fn user_templates_overlay_ours_and_their_files_reach_every_world() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("templates");
    let gazebo = templates.join("gazebo");
    std::fs::create_dir_all(gazebo.join("robot")).unwrap();
    std::fs::write(
        gazebo.join("robot/model.sdf"),
        "<robot model, copied as is {{ x }}>",
    )
    .unwrap();
    std::fs::write(
        gazebo.join("rse.world.j2"),
        "world {{ world }} of {{ cells[0] }}x{{ cells[1] }} cells, {{ boxes|length }} boxes\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let template = templates.to_str().unwrap();
    stdout(&batch(&out, &["--amount", "2", "--template", template]));
    for world in ["world_0000", "world_0001"] {
        let robot =
            std::fs::read_to_string(out.join(world).join("gazebo/robot/model.sdf")).unwrap();
        assert_eq!(robot, "<robot model, copied as is {{ x }}>");
        let text = std::fs::read_to_string(out.join(world).join("gazebo/rse.world")).unwrap();
        assert!(
            text.starts_with(&format!("world {world} of 50x50 cells, ")),
            "{text}"
        );
        // Overlaid file by file: our model templates are kept.
        assert!(
            out.join(world)
                .join("gazebo/rse_terrain/model.sdf")
                .exists()
        );
    }
}

/// A folder holding one edited template is a whole template set: the
/// other files are ours, and `check` finds the worlds good.
#[test]
fn one_edited_template_overlays_ours_and_the_worlds_check_good() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("templates");
    std::fs::create_dir_all(templates.join("gazebo")).unwrap();
    let ours = std::fs::read_to_string(repo().join("templates/gazebo/rse.world.j2")).unwrap();
    let edited = ours.replace("</world>", "  <!-- our lab -->\n  </world>");
    assert_ne!(edited, ours);
    std::fs::write(templates.join("gazebo/rse.world.j2"), &edited).unwrap();
    let out = dir.path().join("out");
    stdout(&batch(
        &out,
        &["--amount", "2", "--template", templates.to_str().unwrap()],
    ));
    let world = out.join("world_0001");
    for file in ["rse_terrain/model.config", "rse_terrain/model.sdf"] {
        assert!(world.join("gazebo").join(file).is_file(), "{file}");
    }
    let text = std::fs::read_to_string(world.join("gazebo/rse.world")).unwrap();
    assert!(text.contains("<!-- our lab -->"), "{text}");
    let checked = rse_gen(&["check", out.to_str().unwrap()]);
    assert_eq!(checked.status.code(), Some(0), "{}", stderr(&checked));
}

/// `templates export` writes ours; used as `--template`, they give the same
/// world files as the built-in ones; a second export refuses to overwrite.
#[test]
fn exported_templates_are_ours() {
    let dir = tempfile::tempdir().unwrap();
    let exported = dir.path().join("exported");
    let listed = stdout(&rse_gen(&[
        "templates",
        "export",
        exported.to_str().unwrap(),
    ]));
    assert_eq!(listed.lines().count(), 10, "{listed}");
    for target in [
        "gazebo",
        "gazebo-classic",
        "mujoco",
        "urdf",
        "usd",
        "webots",
    ] {
        assert_same_tree(
            &exported.join(target),
            &repo().join("templates").join(target),
        );
    }
    let again = rse_gen(&["templates", "export", exported.to_str().unwrap()]);
    assert_eq!(again.status.code(), Some(2));
    assert!(
        stderr(&again).contains("exists already"),
        "{}",
        stderr(&again)
    );

    let [builtin, custom] = ["builtin", "custom"].map(|n| dir.path().join(n));
    let targets = ["--target", &all_targets()];
    stdout(&batch(&builtin, &targets));
    stdout(&batch(
        &custom,
        &[&targets[..], &["--template", exported.to_str().unwrap()]].concat(),
    ));
    let (a, b) = (tree(&builtin), tree(&custom));
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    for (path, bytes) in &a {
        if !path.ends_with("rse.json") {
            assert!(b[path] == *bytes, "{path} differs");
        }
    }
}

#[test]
fn a_template_folder_that_is_not_there_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let missing = dir.path().join("nonexistent");
    let failed = batch(&out, &["--template", missing.to_str().unwrap()]);
    assert_eq!(failed.status.code(), Some(2));
    let message = stderr(&failed);
    assert!(
        message.contains("nonexistent") && message.contains("does not exist"),
        "{message}"
    );
    assert!(!out.exists());
}

#[test]
fn a_template_error_names_file_and_line_and_writes_no_world() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("templates");
    std::fs::create_dir_all(templates.join("mujoco")).unwrap();
    std::fs::write(
        templates.join("mujoco/rse.xml.j2"),
        "<mujoco>\n  {{ world }}\n  {{ no_such_value }}\n</mujoco>\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let failed = batch(
        &out,
        &[
            "--target",
            "mujoco",
            "--template",
            templates.to_str().unwrap(),
        ],
    );
    assert_eq!(failed.status.code(), Some(2));
    let message = stderr(&failed);
    assert!(message.contains("mujoco/rse.xml.j2:3:"), "{message}");
    assert!(
        message.contains("undefined value 'no_such_value'"),
        "{message}"
    );
    assert!(!out.join("world_0000").exists());

    std::fs::write(templates.join("mujoco/rse.xml.j2"), "ok\n{% if %}\n").unwrap();
    let syntax = batch(
        &out,
        &[
            "--target",
            "mujoco",
            "--template",
            templates.to_str().unwrap(),
        ],
    );
    assert_eq!(syntax.status.code(), Some(2));
    assert!(
        stderr(&syntax).contains("rse.xml.j2:2:"),
        "{}",
        stderr(&syntax)
    );
}

#[test]
fn bad_batch_options_exit_2_with_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("a_file");
    std::fs::write(&file, "").unwrap();
    for (args, expected) in [
        (vec!["--shard", "4/4"], "bad shard"),
        (vec!["--target", "gazebo,isaac"], "unknown target"),
        (vec!["--mesh", "voxels"], "unknown mesh mode"),
        (vec!["--jobs", "0"], "--jobs"),
        (vec!["--oversample", "4"], "hfield collider only"),
        (vec!["--mujoco-collider", "mesh"], "--mujoco-collider"),
        (
            vec!["--mujoco-collider", "hfield", "--oversample", "0"],
            "--oversample",
        ),
        (vec!["--difficulty", "1.5"], "--difficulty"),
    ] {
        let out = dir.path().join("out");
        let failed = batch(&out, &args);
        assert_eq!(failed.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&failed).contains(expected),
            "{args:?}: {}",
            stderr(&failed)
        );
    }
    let into_file = batch(&file, &[]);
    assert_eq!(into_file.status.code(), Some(2));
    assert!(
        stderr(&into_file).contains("a_file"),
        "{}",
        stderr(&into_file)
    );
}

/// Hostile worlds VI, hole 5: under an address-space limit a batch of
/// 1000×1000 worlds aborted in an allocation (exit 134), leaving its lock
/// (here 500×500 worlds under 500 MB).
/// The room the limit leaves is memory available like any other: the
/// batch is refused before it starts, naming what to reduce, with nothing
/// left behind, and runs once the limit is lifted.
#[test]
fn a_batch_under_an_address_space_limit_is_refused_cleanly_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let scheme = dir.path().join("big.csv");
    std::fs::write(&scheme, "# size: 500x500\ntype,height\nrandom,2\n").unwrap();
    let out = dir.path().join("out");
    let args = [
        "batch",
        scheme.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--amount",
        "1",
        "--target",
        "mujoco",
    ];
    let limited = Command::new("prlimit")
        .arg("--as=500000000")
        .arg(env!("CARGO_BIN_EXE_rse-gen"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("prlimit runs");
    let said = stderr(&limited);
    assert!(
        matches!(limited.status.code(), Some(1 | 2)),
        "{:?}: {said}",
        limited.status
    );
    assert!(
        said.contains("250000 cells") && said.contains("MiB are available"),
        "{said}"
    );
    let left = if out.exists() {
        rse_world::list_files(&out).unwrap()
    } else {
        Vec::new()
    };
    assert!(left.is_empty(), "left behind: {left:?}");
    let done = rse_gen(&args);
    assert_eq!(done.status.code(), Some(0), "{}", stderr(&done));
}
