//! `--difficulty` on heightmap, preview, mesh and batch: the contract of
//! docs/schemes.md through the binary, and bad values refused.

use super::{rse_gen, stderr, stdout};

fn cells(csv: &str) -> Vec<Vec<u32>> {
    csv.lines()
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

#[test]
fn heightmap_scales_every_non_frame_cell_and_keeps_frames() {
    let scheme = "schemes/paper_pallets.csv";
    let full = stdout(&rse_gen(&["heightmap", scheme, "--index", "2"]));
    let same = stdout(&rse_gen(&[
        "heightmap",
        scheme,
        "--index",
        "2",
        "--difficulty",
        "1",
    ]));
    assert_eq!(full, same);
    let half = stdout(&rse_gen(&[
        "heightmap",
        scheme,
        "--index",
        "2",
        "--difficulty",
        "0.5",
    ]));
    let zero = stdout(&rse_gen(&[
        "heightmap",
        scheme,
        "--index",
        "2",
        "--difficulty",
        "0",
    ]));
    let (full, half, zero) = (cells(&full), cells(&half), cells(&zero));
    let mut frames = 0;
    for (y, row) in full.iter().enumerate() {
        for (x, &h) in row.iter().enumerate() {
            // paper_pallets: 3-cell pallets, a frame every 4th line.
            if x % 4 == 0 || y % 4 == 0 {
                assert_eq!((half[y][x], zero[y][x]), (1, 1), "frame ({x}, {y})");
                frames += 1;
            } else {
                // floor(0.5·h + u), one u per world: h/2 rounded down or up.
                assert!([h / 2, h.div_ceil(2)].contains(&half[y][x]), "({x}, {y})");
                assert_eq!(zero[y][x], 0);
            }
        }
    }
    assert!(frames > 0);
}

#[test]
fn bad_difficulties_exit_2_naming_the_flag_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.obj");
    for bad in ["2", "-0.1", "NaN", "hard", "inf"] {
        let output = rse_gen(&[
            "mesh",
            "schemes/wall.csv",
            "-o",
            out.to_str().unwrap(),
            "--difficulty",
            bad,
        ]);
        assert_eq!(output.status.code(), Some(2), "{bad}");
        let err = stderr(&output);
        assert!(err.contains("--difficulty"), "{bad}: {err}");
        assert!(err.contains("from 0 to 1"), "{bad}: {err}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "{bad}");
    }
}

#[test]
fn a_batch_at_a_difficulty_records_it_and_checks_good() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let scheme = "schemes/six_obstacles.csv";
    stdout(&rse_gen(&[
        "batch",
        scheme,
        "-o",
        out,
        "--amount",
        "2",
        "--seed",
        "5",
        "--difficulty",
        "0.3",
        "--target",
        "obj,mujoco",
    ]));
    let world = std::path::Path::new(out).join("world_0001");
    let manifest = std::fs::read_to_string(world.join("rse.json")).unwrap();
    assert!(manifest.contains("\"difficulty\": 0.3,"), "{manifest}");
    let want = stdout(&rse_gen(&[
        "heightmap",
        scheme,
        "--seed",
        "5",
        "--index",
        "1",
        "--difficulty",
        "0.3",
    ]));
    assert_eq!(
        std::fs::read_to_string(world.join("heightmap.csv")).unwrap(),
        want
    );
    stdout(&rse_gen(&["check", out]));
    // Another difficulty is another world: a rerun does not pass it off as this one.
    let rerun = rse_gen(&[
        "batch",
        scheme,
        "-o",
        out,
        "--amount",
        "2",
        "--seed",
        "5",
        "--target",
        "obj,mujoco",
    ]);
    assert_eq!(rerun.status.code(), Some(2), "{}", stderr(&rerun));
}

#[test]
fn check_curriculum_passes_every_sample_scheme_and_fails_a_flat_one() {
    for entry in std::fs::read_dir(super::repo().join("schemes")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "csv") {
            let out = rse_gen(&["check-curriculum", path.to_str().unwrap(), "--draws", "20"]);
            assert!(out.status.success(), "{}: {}", path.display(), stdout(&out));
            let table = stdout(&out);
            assert_eq!(
                table.lines().filter(|l| l.starts_with("    ")).count(),
                10,
                "{table}"
            );
            assert!(table.contains("ok: no dead level"), "{table}");
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let flat = dir.path().join("flat.csv");
    std::fs::write(&flat, "# size: 5x5\ntype,height\n").unwrap();
    let out = rse_gen(&["check-curriculum", flat.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["ok"], false);
    assert_eq!(report["per_level"].as_array().unwrap().len(), 10);
    assert!(
        report["problems"][0]
            .as_str()
            .unwrap()
            .contains("flat at difficulty 1")
    );
}

#[test]
fn check_curriculum_checks_every_scheme_of_a_mix_and_fails_if_any_fails() {
    let mix = [
        "schemes/mix_stairs.csv",
        "schemes/mix_walls.csv",
        "schemes/mix_rough.csv",
    ];
    let mut args = vec!["check-curriculum", "--draws", "20"];
    args.extend(mix);
    let table = stdout(&rse_gen(&args));
    for scheme in mix {
        assert!(table.contains(&format!("{scheme}: 10 levels")), "{table}");
    }
    assert_eq!(table.matches("ok: no dead level").count(), 3, "{table}");
    let dir = tempfile::tempdir().unwrap();
    let flat = dir.path().join("flat.csv");
    std::fs::write(&flat, "# size: 5x5\ntype,height\n").unwrap();
    let out = rse_gen(&[
        "check-curriculum",
        "schemes/mix_rough.csv",
        flat.to_str().unwrap(),
        "--json",
        "--draws",
        "20",
    ]);
    assert_eq!(out.status.code(), Some(1), "one scheme of the mix fails");
    let reports: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let reports = reports.as_array().expect("several schemes: a list");
    assert_eq!(
        (reports[0]["ok"].as_bool(), reports[1]["ok"].as_bool()),
        (Some(true), Some(false))
    );
    assert_eq!(reports[1]["scheme"], flat.to_str().unwrap());
}

#[test]
fn check_curriculum_refuses_bad_counts_and_names_the_scheme_line() {
    let out = rse_gen(&["check-curriculum", "schemes/random.csv", "--levels", "1"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("levels 1: expected 2 to"),
        "{}",
        stderr(&out)
    );
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.csv");
    std::fs::write(&bad, "type,height\npeak,x\n").unwrap();
    let out = rse_gen(&["check-curriculum", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("bad.csv:2:2: height"),
        "{}",
        stderr(&out)
    );
}

/// Hostile worlds VI, hole 4: with four schemes and `--budget 0.035` the
/// budget held each scheme apart and the run took four times it. It holds
/// the whole run now, priced before a world is made.
#[test]
fn check_curriculums_budget_holds_every_scheme_of_the_run_together() {
    let dir = tempfile::tempdir().unwrap();
    let text = "# size: 60x60\ntype,height\nrandom,3\n";
    let paths: Vec<String> = (0..4)
        .map(|i| {
            let path = dir.path().join(format!("s{i}.csv"));
            std::fs::write(&path, text).unwrap();
            path.to_str().unwrap().to_owned()
        })
        .collect();
    let scheme = rse_core::Scheme::from_csv(text, None).unwrap();
    let options = rse_core::CurriculumOptions {
        levels: 2,
        draws: 2,
        seed: 0,
    };
    // One scheme fits the budget with a third to spare; four do not.
    let factor = 1.5 * options.visits(&scheme) as f64 / rse_core::CURRICULUM_VISITS as f64;
    let budget = format!("{factor:e}");
    let args = |schemes: &[String]| {
        let mut all = vec![
            "check-curriculum",
            "--levels",
            "2",
            "--draws",
            "2",
            "--budget",
            budget.as_str(),
        ];
        all.extend(schemes.iter().map(String::as_str));
        rse_gen(&all)
    };
    let one = args(&paths[..1]);
    assert_eq!(one.status.code(), Some(0), "{}", stderr(&one));
    let four = args(&paths);
    assert_eq!(four.status.code(), Some(2), "{}", stderr(&four));
    assert!(
        stderr(&four).contains("the 4 schemes together")
            && stderr(&four).contains("over the budget"),
        "{}",
        stderr(&four)
    );
    assert!(four.stdout.is_empty(), "nothing checked before the refusal");
}
