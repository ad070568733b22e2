//! `rse-gen atlas`: every tile is `rse-gen heightmap` of its world, the
//! folder checks good and is the same on any `--jobs`, and bad arguments
//! exit 2 naming the argument with nothing written.

use std::path::Path;

use super::{rse_gen, stderr, stdout};

fn cells(csv: &str) -> Vec<Vec<String>> {
    csv.lines()
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

fn atlas(out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "atlas",
        "schemes/random.csv",
        "schemes/gaussian.csv",
        "schemes/flat_peak_and_pit.csv",
        "--size",
        "20x16",
        "--rows",
        "3",
        "--cols",
        "4",
        "--border",
        "1",
        "--seed",
        "9",
        "--difficulty",
        "0.25..1",
        "--flat-patches",
        "4",
        "--patch-radius",
        "0.2",
        "--max-step",
        "1",
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    rse_gen(&args)
}

#[test]
fn every_tile_is_the_heightmap_of_its_world() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("atlas");
    stdout(&atlas(&out, &["--target", "obj,mujoco"]));
    let map = cells(&std::fs::read_to_string(out.join("heightmap.csv")).unwrap());
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("atlas.json")).unwrap()).unwrap();
    let tiles = json["tiles"].as_array().unwrap();
    assert_eq!(tiles.len(), 12);
    assert_eq!(map.len(), 4 * 17 + 1);
    assert_eq!(map[0].len(), 3 * 21 + 1);
    for tile in tiles {
        let scheme = format!("schemes/{}", tile["scheme"].as_str().unwrap());
        let index = tile["index"].to_string();
        let difficulty = tile["difficulty"].to_string();
        let (r, c) = (tile["row"].as_u64().unwrap(), tile["col"].as_u64().unwrap());
        assert_eq!(index, (r * 4 + c).to_string());
        let want = cells(&stdout(&rse_gen(&[
            "heightmap",
            &scheme,
            "--size",
            "20x16",
            "--seed",
            "9",
            "--index",
            &index,
            "--difficulty",
            &difficulty,
        ])));
        let [x0, y0, x1, y1] = [0, 1, 2, 3].map(|i| tile["cells"][i].as_u64().unwrap() as usize);
        assert_eq!((x1 - x0, y1 - y0), (20, 16));
        for (dy, row) in want.iter().enumerate() {
            assert_eq!(&map[y0 + dy][x0..x1], row.as_slice(), "tile ({r}, {c})");
        }
    }
    // Borders: the first line, the first column.
    assert!(map[0].iter().all(|h| h == "0"));
    assert!(map.iter().all(|row| row[0] == "0"));
}

#[test]
fn the_atlas_checks_good_and_is_the_same_on_any_jobs() {
    let dir = tempfile::tempdir().unwrap();
    let one = dir.path().join("a1").join("atlas");
    let two = dir.path().join("a2").join("atlas");
    let all = &rse_world::Targets::all().to_string();
    stdout(&atlas(&one, &["--target", all, "--jobs", "1"]));
    stdout(&atlas(&two, &["--target", all, "--jobs", "2"]));
    for file in [
        "rse.json",
        "atlas.json",
        "heightmap.csv",
        "meshes/terrain.obj",
    ] {
        assert_eq!(
            std::fs::read(one.join(file)).unwrap(),
            std::fs::read(two.join(file)).unwrap(),
            "{file}"
        );
    }
    stdout(&rse_gen(&["check", one.to_str().unwrap()]));
    // What a run killed before its rename leaves is removed by the next.
    let leftover = one.parent().unwrap().join(".atlas.tmp-4242");
    std::fs::create_dir(&leftover).unwrap();
    std::fs::write(leftover.join("rse.json"), "{").unwrap();
    // check reports it, given the atlas or the folder it is in.
    for path in [one.as_path(), one.parent().unwrap()] {
        let check = rse_gen(&["check", path.to_str().unwrap()]);
        assert_eq!(check.status.code(), Some(1), "{}", stderr(&check));
        let said = format!(
            "{}{}",
            String::from_utf8_lossy(&check.stdout),
            stderr(&check)
        );
        assert!(said.contains(".atlas.tmp-4242"), "{said}");
    }
    // A rerun leaves it alone; another layout is refused without --force.
    let again = atlas(&one, &["--target", all]);
    assert!(stderr(&again).contains("unchanged"), "{}", stderr(&again));
    assert!(!leftover.exists());
    let other = atlas(&one, &["--target", all, "--border", "0"]);
    assert_eq!(other.status.code(), Some(2), "{}", stderr(&other));
    // A forged tile list is caught even with its hash rewritten.
    let path = one.join("atlas.json");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replacen("\"row\": 0", "\"row\": 7", 1);
    std::fs::write(&path, &text).unwrap();
    let manifest = std::fs::read_to_string(one.join("rse.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&manifest).unwrap();
    let old = json["files"]["atlas.json"].as_str().unwrap();
    let new = rse_world::sha256_hex(text.as_bytes());
    std::fs::write(one.join("rse.json"), manifest.replace(old, &new)).unwrap();
    let check = rse_gen(&["check", one.to_str().unwrap()]);
    assert_eq!(check.status.code(), Some(1));
    assert!(
        stdout_of(&check).contains("atlas.json"),
        "{}",
        stdout_of(&check)
    );
}

fn stdout_of(output: &std::process::Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned() + &stderr(output)
}

#[test]
fn bad_arguments_exit_2_naming_them_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let steps = dir.path().join("steps.csv");
    std::fs::write(
        &steps,
        "# size: 50x50\n# step_height: 0.05\ntype,height\nrandom,2\n",
    )
    .unwrap();
    let out = dir.path().join("atlas");
    let (six, wall) = ("schemes/six_obstacles.csv", "schemes/wall.csv");
    let cases: [(&[&str], &[&str], &str); 6] = [
        (&[wall], &["--rows", "0", "--cols", "2"], "--rows"),
        (&[wall], &["--rows", "2", "--cols", "0"], "--cols"),
        (
            &[wall],
            &["--rows", "2", "--cols", "2", "--difficulty", "2"],
            "--difficulty",
        ),
        (
            &[wall],
            &["--rows", "2", "--cols", "2", "--difficulty", "1..0.5"],
            "runs backwards",
        ),
        (
            &[six, steps.to_str().unwrap()],
            &["--rows", "2", "--cols", "2"],
            "step_height",
        ),
        (&[six, wall], &["--rows", "1", "--cols", "2"], "size"),
    ];
    for (schemes, flags, needle) in cases {
        let mut args = vec!["atlas"];
        args.extend_from_slice(schemes);
        args.extend_from_slice(flags);
        args.extend_from_slice(&["-o", out.to_str().unwrap()]);
        let output = rse_gen(&args);
        assert_eq!(
            output.status.code(),
            Some(2),
            "{args:?}: {}",
            stderr(&output)
        );
        assert!(
            stderr(&output).contains(needle),
            "{args:?}: {}",
            stderr(&output)
        );
        assert!(!out.exists(), "{args:?} wrote something");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}
