//! `rse-gen contact-sheet`: N envs' terrains in one PNG, one scheme or a
//! mix, labelled; bad input refused at the flag, nothing written.

use super::{read_png, rse_gen, stderr, write_scheme};

#[test]
fn one_scheme_draws_n_labelled_tiles_and_the_same_bytes_every_time() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sheet.png");
    let out = out.to_str().unwrap();
    let args = [
        "contact-sheet",
        "schemes/six_obstacles.csv",
        "--envs",
        "6",
        "--difficulty",
        "0.5",
        "-o",
        out,
    ];
    let done = rse_gen(&args);
    assert!(done.status.success(), "{}", stderr(&done));
    let (width, height, _) = read_png(std::path::Path::new(out));
    // 6 envs: 3 columns, 2 rows of 50 cells at 3 px (tiles of 150 px).
    assert_eq!(width, 6 + 3 * (150 + 6));
    assert!(height > 2 * 150, "{height}");
    let first = std::fs::read(out).unwrap();
    assert!(rse_gen(&args).status.success());
    assert_eq!(
        std::fs::read(out).unwrap(),
        first,
        "the same bytes every run"
    );
    // Harder terrains look harder: more red at difficulty 1 than at 0.
    let red = |rgb: &[u8]| rgb.chunks(3).filter(|p| p[0] > 200 && p[1] < 100).count();
    let at = |d: &str| {
        let path = dir.path().join(format!("d{d}.png"));
        let path = path.to_str().unwrap();
        assert!(
            rse_gen(&[
                "contact-sheet",
                "schemes/six_obstacles.csv",
                "--envs",
                "4",
                "--difficulty",
                d,
                "-o",
                path
            ])
            .status
            .success()
        );
        red(&read_png(std::path::Path::new(path)).2)
    };
    assert!(
        at("1") > 0 && at("0") == 0,
        "a flat field has no top to draw red"
    );
}

#[test]
fn a_mix_names_each_tiles_scheme_and_levels_rise_row_by_row() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("mix.png");
    let done = rse_gen(&[
        "contact-sheet",
        "schemes/mix_stairs.csv",
        "schemes/mix_walls.csv",
        "schemes/mix_rough.csv",
        "--proportions",
        "2,1,1",
        "--envs",
        "20",
        "--levels",
        "5",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(done.status.success(), "{}", stderr(&done));
    let (width, _, _) = read_png(&out);
    // 20 envs: 5 columns of 80 cells at 2 px.
    assert_eq!(width, 6 + 5 * (160 + 6));
}

#[test]
fn bad_flags_are_refused_naming_them_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let scheme = write_scheme(dir.path(), "# size: 10x10\ntype,height\nrandom,2\n");
    let out = dir.path().join("sheet.png");
    let out = out.to_str().unwrap();
    for (args, words) in [
        (
            vec!["--proportions", "1,1"],
            "--proportions: 2 given for 1 schemes",
        ),
        (
            vec!["--proportions", "-1"],
            "--proportions: scheme 1's proportion is -1",
        ),
        (
            vec!["--proportions", "0"],
            "--proportions: every proportion is 0",
        ),
        (vec!["--difficulty", "1.5"], "--difficulty"),
        (vec!["--levels", "1"], "--levels"),
        (vec!["--envs", "0"], "--envs"),
        (
            vec!["--levels", "3", "--difficulty", "0.5"],
            "cannot be used with",
        ),
    ] {
        let mut all = vec!["contact-sheet", scheme.as_str(), "-o", out];
        all.extend(args);
        let done = rse_gen(&all);
        assert_eq!(done.status.code(), Some(2), "{all:?}: {}", stderr(&done));
        assert!(stderr(&done).contains(words), "{all:?}: {}", stderr(&done));
        assert!(!std::path::Path::new(out).exists(), "{all:?} wrote a file");
    }
    let missing = rse_gen(&["contact-sheet", "no/such.csv", "-o", out]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(
        stderr(&missing).contains("no/such.csv"),
        "{}",
        stderr(&missing)
    );
}

/// Hostile worlds VI, hole 7: a sheet too wide for its columns names the
/// flag that sets them, and proportions whose sum overflows are shares,
/// not "every proportion is 0".
#[test]
fn a_sheet_too_large_names_its_columns_and_huge_proportions_mix() {
    let dir = tempfile::tempdir().unwrap();
    let scheme = write_scheme(dir.path(), "# size: 10x10\ntype,height\nrandom,2\n");
    let out = dir.path().join("sheet.png");
    let out = out.to_str().unwrap();
    let wide = rse_gen(&[
        "contact-sheet",
        scheme.as_str(),
        "-o",
        out,
        "--cols",
        "1000000000",
    ]);
    assert_ne!(wide.status.code(), Some(0));
    assert!(
        stderr(&wide).contains("1000000000 columns") && stderr(&wide).contains("use fewer --cols"),
        "{}",
        stderr(&wide)
    );
    assert!(!std::path::Path::new(out).exists());
    let other = dir.path().join("other.csv");
    std::fs::write(&other, "# size: 10x10\ntype,height\nrandom,3\n").unwrap();
    let huge = rse_gen(&[
        "contact-sheet",
        scheme.as_str(),
        other.to_str().unwrap(),
        "-o",
        out,
        "--envs",
        "4",
        "--proportions=1e308,1e308",
    ]);
    assert_eq!(huge.status.code(), Some(0), "{}", stderr(&huge));
}
