//! The real `rse-gen` binary, run in temporary folders: exit codes, stdout, stderr, files.

use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use sha2::{Digest, Sha256};

mod atlas;
mod batch;
mod check;
mod contact_sheet;
mod difficulty;
mod help;
mod messages;
mod regression;

/// Every target, as `--target` takes them.
fn all_targets() -> String {
    rse_world::Targets::all().to_string()
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn rse_gen(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rse-gen"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("rse-gen runs")
}

fn stdout(output: &Output) -> String {
    assert!(
        output.status.success(),
        "exit {:?}: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout.clone()).unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

fn write_scheme(dir: &Path, text: &str) -> String {
    let path = dir.join("scheme.csv");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn heightmap_matches_the_golden_table() {
    let golden = std::fs::read_to_string(repo().join("tests/golden/heightmaps.csv")).unwrap();
    let mut rows = 0;
    for line in golden.lines().skip(1) {
        let [scheme, seed, index, hash] = line.split(',').collect::<Vec<_>>()[..] else {
            panic!("bad golden line {line}")
        };
        let path = format!("schemes/{scheme}");
        let out = stdout(&rse_gen(&[
            "heightmap",
            &path,
            "--seed",
            seed,
            "--index",
            index,
        ]));
        let hex = Sha256::digest(out.as_bytes())
            .iter()
            .fold(String::new(), |hex, b| hex + &format!("{b:02x}"));
        assert_eq!(hex, hash, "{line}");
        rows += 1;
    }
    assert!(rows >= 36);
}

#[test]
fn heightmap_is_one_line_per_y_and_one_column_per_x() {
    let out = stdout(&rse_gen(&["heightmap", "schemes/wall.csv"]));
    let lines: Vec<_> = out.lines().collect();
    assert_eq!(lines.len(), 24);
    assert!(lines.iter().all(|l| l.split(',').count() == 30));
    // The wall runs from (3,3) to (26,20): its first cell is the top, 4 steps.
    assert_eq!(lines[3].split(',').nth(3), Some("4"));
}

#[test]
fn seed_defaults_to_the_schemes_and_flags_override() {
    let dir = tempfile::tempdir().unwrap();
    let with_seed = write_scheme(
        dir.path(),
        "# size: 8x8\n# seed: 77\ntype,height\nrandom,5\n",
    );
    let a = stdout(&rse_gen(&["heightmap", &with_seed]));
    let b = stdout(&rse_gen(&["heightmap", &with_seed, "--seed", "77"]));
    let c = stdout(&rse_gen(&["heightmap", &with_seed, "--seed", "78"]));
    let d = stdout(&rse_gen(&["heightmap", &with_seed, "--index", "1"]));
    assert_eq!(a, b);
    assert_ne!(a, c);
    assert_ne!(a, d);
}

#[test]
fn global_flags_override_the_scheme() {
    let out = stdout(&rse_gen(&[
        "heightmap",
        "schemes/random.csv",
        "--size",
        "7x3",
    ]));
    assert_eq!(out.lines().count(), 3);
    assert_eq!(out.lines().next().unwrap().split(',').count(), 7);
    // Flags may come before the subcommand too.
    let out = stdout(&rse_gen(&[
        "--pallets",
        "2x3",
        "--pallet-size",
        "3",
        "heightmap",
        "schemes/random.csv",
    ]));
    assert_eq!(out.lines().count(), 13);
    assert_eq!(out.lines().next().unwrap(), "1,1,1,1,1,1,1,1,1");
    let out = stdout(&rse_gen(&[
        "heightmap",
        "schemes/paper_pallets.csv",
        "--pallet-boundary",
        "false",
    ]));
    assert_eq!(out.lines().count(), 9);
    let out = stdout(&rse_gen(&[
        "heightmap",
        "schemes/paper_pallets.csv",
        "--pallets",
        "off",
    ]));
    assert_eq!(out.lines().count(), 10);
    // `--pallets` reads every word a scheme file's `pallets` takes.
    for off in ["none", "No", "false"] {
        let same = stdout(&rse_gen(&[
            "heightmap",
            "schemes/paper_pallets.csv",
            "--pallets",
            off,
        ]));
        assert_eq!(same, out, "--pallets {off}");
    }
}

#[test]
fn step_height_flag_changes_the_quantisation() {
    let coarse = stdout(&rse_gen(&["heightmap", "schemes/peak.csv"]));
    let fine = stdout(&rse_gen(&[
        "heightmap",
        "schemes/peak.csv",
        "--step-height",
        "0.05",
    ]));
    let row = |text: &str| text.lines().nth(7).unwrap().to_owned();
    // H = 5 steps at 45°: 0.1 m per cell is one step of 0.1 m, or two of 0.05 m.
    assert_eq!(row(&coarse), "0,0,0,1,2,3,4,5,4,3,2,1,0,0,0");
    assert_eq!(row(&fine), "0,0,0,0,0,1,3,5,3,1,0,0,0,0,0");
}

/// Width, height and RGB bytes of a PNG file.
fn read_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    (info.width, info.height, pixels)
}

#[test]
fn preview_draws_one_block_per_cell_north_up() {
    let dir = tempfile::tempdir().unwrap();
    let scheme = write_scheme(
        dir.path(),
        "# size: 4x3\ntype,height,angle,x1,y1\npeak,2,90,0,2\n",
    );
    let png_path = dir.path().join("p.png");
    let out = rse_gen(&[
        "preview",
        &scheme,
        "-o",
        png_path.to_str().unwrap(),
        "--cell-pixels",
        "10",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out.stdout.is_empty());
    let (width, height, pixels) = read_png(&png_path);
    // The map's 40×30, then its legend: three heights, a line each.
    assert_eq!(width, 40);
    assert!(height >= 30 + 3 * 11, "{height}");
    let at = |px: usize, py: usize| {
        let i = (py * 40 + px) * 3;
        [pixels[i], pixels[i + 1], pixels[i + 2]]
    };
    // The peak is cell (0, 2): top-left in a north-up picture, red; the rest blue.
    assert_eq!(at(3, 3), [255, 0, 0]);
    assert_eq!(at(35, 25), [0, 0, 255]);
    // Block edges are darker.
    assert_eq!(at(9, 3), [192, 0, 0]);
}

#[test]
fn preview_marks_pallet_frames() {
    let dir = tempfile::tempdir().unwrap();
    let png_path = dir.path().join("p.png");
    let p = png_path.to_str().unwrap();
    let out = rse_gen(&[
        "preview",
        "schemes/paper_pallets.csv",
        "-o",
        p,
        "--cell-pixels",
        "2",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let (width, height, pixels) = read_png(&png_path);
    // The map's 18×26, then its legend.
    assert_eq!(width, 18);
    assert!(height > 26, "{height}");
    assert_eq!(
        pixels[..3],
        [150, 111, 71],
        "frame colour at the top-left corner"
    );
}

#[test]
fn a_bad_scheme_names_file_line_and_column_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scheme = write_scheme(
        dir.path(),
        "# size: 10x10\ntype,height,angle,x1,y1\nrandom,2,,,\npeak,3,45,12,4\n",
    );
    let png_path = dir.path().join("p.png");
    for args in [
        vec!["heightmap", scheme.as_str()],
        vec!["preview", scheme.as_str(), "-o", png_path.to_str().unwrap()],
    ] {
        let out = rse_gen(&args);
        assert_eq!(out.status.code(), Some(2));
        assert!(out.stdout.is_empty());
        let err = stderr(&out);
        assert!(
            err.contains(&format!("{scheme}:4:4: x1: 12 is outside the grid")),
            "{err}"
        );
    }
    assert!(!png_path.exists());
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "only the scheme is there"
    );
}

#[test]
fn an_override_that_breaks_the_scheme_says_so() {
    let out = rse_gen(&["heightmap", "schemes/wall.csv", "--size", "10x10"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("command line"), "{err}");
    assert!(err.contains("schemes/wall.csv:6:6: x2"), "{err}");
}

#[test]
fn usage_and_io_errors_exit_2() {
    for args in [
        vec!["heightmap"],
        vec!["heightmap", "no-such.csv"],
        vec!["heightmap", "schemes/random.csv", "--size", "0x4"],
        vec!["heightmap", "schemes/random.csv", "--step-height", "-1"],
        vec!["heightmap", "schemes/random.csv", "--pallet-size", "3"],
        vec!["preview", "schemes/random.csv", "-o", "/no/such/dir/p.png"],
        vec!["frobnicate"],
    ] {
        let out = rse_gen(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).is_empty());
    }
    // The system's reason once (it was printed twice).
    let err = stderr(&rse_gen(&["heightmap", "no-such.csv"]));
    assert_eq!(
        err.trim_end(),
        "rse-gen: cannot read no-such.csv: No such file or directory (os error 2)"
    );
    // Far too large for memory: refused before anything is allocated or
    // written (a 19.6 TB preview once aborted with a backtrace).
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("p.png");
    let out = rse_gen(&[
        "preview",
        "schemes/random.csv",
        "--size",
        "10000x10000",
        "--cell-pixels",
        "256",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("use fewer --cell-pixels"),
        "{}",
        stderr(&out)
    );
    assert!(!png.exists());
    let batch = dir.path().join("huge");
    let out = rse_gen(&[
        "batch",
        "schemes/random.csv",
        "--size",
        "10000x10000",
        "-o",
        batch.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("MiB are available"),
        "{}",
        stderr(&out)
    );
    assert!(!batch.exists());
}

#[test]
fn a_closed_pipe_is_not_an_error() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rse-gen"))
        .args(["heightmap", "schemes/random.csv", "--size", "2000x2000"])
        .current_dir(repo())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap(); // then drop: closes the pipe
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(out.stderr.is_empty(), "{}", stderr(&out));
}

#[test]
fn mesh_writes_obj_with_its_mtl_stl_and_glb() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    for name in ["t.obj", "t.stl", "t.glb"] {
        let out = rse_gen(&["mesh", "schemes/peak.csv", "-o", &path(name)]);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        assert!(out.stdout.is_empty());
    }
    let obj = std::fs::read_to_string(path("t.obj")).unwrap();
    assert!(obj.contains("mtllib t.mtl\n"));
    assert_eq!(obj.lines().filter(|l| l.starts_with("vn ")).count(), 6);
    let faces = obj.lines().filter(|l| l.starts_with("f ")).count();
    assert!(
        obj.lines()
            .filter(|l| l.starts_with("f "))
            .all(|l| l.split(' ').skip(1).all(|c| c.contains("//")))
    );
    assert!(
        std::fs::read_to_string(path("t.mtl"))
            .unwrap()
            .contains("newmtl rse_terrain")
    );
    let stl = std::fs::read(path("t.stl")).unwrap();
    assert_eq!(
        u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize,
        faces
    );
    assert_eq!(stl.len(), 84 + 50 * faces);
    let glb = std::fs::read(path("t.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    assert_eq!(
        u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize,
        glb.len()
    );
}

#[test]
fn mesh_of_an_unknown_format_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("t.ply");
    let out = rse_gen(&["mesh", "schemes/peak.csv", "-o", target.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("name the file .obj, .stl or .glb"),
        "{}",
        stderr(&out)
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn mesh_is_deterministic_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let mut seen = Vec::new();
    for run in 0..2 {
        let folder = dir.path().join(format!("run{run}"));
        std::fs::create_dir(&folder).unwrap();
        let mut files = Vec::new();
        for name in ["t.obj", "t.mtl", "t.stl", "t.glb"] {
            let p = folder.join(name);
            if name == "t.mtl" {
                files.push(std::fs::read(p).unwrap_or_default());
                continue;
            }
            let out = rse_gen(&[
                "mesh",
                "schemes/six_obstacles.csv",
                "-o",
                p.to_str().unwrap(),
                "--index",
                "3",
            ]);
            assert!(out.status.success());
            files.push(std::fs::read(p).unwrap());
        }
        seen.push(files);
    }
    assert_eq!(seen[0], seen[1]);
}
