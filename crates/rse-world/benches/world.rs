//! Where one world's time goes: a world of `schemes/nist_hill.csv` built
//! and placed stage by stage (terrain, preview, mesh, mesh files, each
//! target's templates, the manifest's hashes, writing the folder), beside
//! copying the same folder as `cp -r` would. Prints a table; run with
//! `cargo bench -p rse-world --bench world` (`TMPDIR=/dev/shm` to write to
//! memory). `bench/batch.sh` measures whole batches.

use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};

use rse_core::export::{obj, usda};
use rse_core::{Difficulty, Scheme, generate_at, preview};
use rse_world::{
    MeshMode, MujocoCollider, Target, Targets, Templates, WorldFiles, WorldOptions, build_world,
    place_world, sha256_hex,
};

/// The median of `run`'s times, over at least 15 runs and about `budget`.
fn median_time(mut run: impl FnMut(), budget: Duration) -> Duration {
    let mut times = Vec::new();
    let start = Instant::now();
    while times.len() < 15 || (start.elapsed() < budget && times.len() < 2000) {
        let t = Instant::now();
        run();
        times.push(t.elapsed());
    }
    times.sort();
    times[times.len() / 2]
}

fn options(targets: &str) -> WorldOptions {
    WorldOptions {
        difficulty: Difficulty::FULL,
        difficulty_rule: None,
        targets: Targets::parse(targets).expect("bench target lists are valid"),
        mesh: MeshMode::Auto,
        mujoco_collider: MujocoCollider::Boxes,
    }
}

/// Copies `from` into `to` file by file, as `cp -r` does.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir(to).expect("copy folder");
    for entry in std::fs::read_dir(from).expect("read folder") {
        let entry = entry.expect("read entry");
        let target = to.join(entry.file_name());
        if entry.file_type().expect("file type").is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).expect("copy file");
        }
    }
}

/// World `index` of `scheme` with `targets`, as a batch builds it.
fn build(scheme: &Scheme, templates: &Templates, targets: &str, index: u64) -> WorldFiles {
    build_world(
        scheme,
        0,
        index,
        format!("world_{index}"),
        &options(targets),
        templates,
    )
    .expect("world builds")
}

/// The parts of one world built alone: terrain, preview, meshes, box set.
fn parts(scheme: &Scheme, budget: Duration) -> Vec<(String, Duration)> {
    let terrain = generate_at(scheme, 0, 0, Difficulty::FULL);
    let mesh = terrain.mesh();
    let mut index = 0;
    vec![
        (
            "terrain (generate)".into(),
            median_time(
                || {
                    index += 1;
                    drop(black_box(generate_at(scheme, 0, index, Difficulty::FULL)));
                },
                budget,
            ),
        ),
        (
            "preview.png".into(),
            median_time(
                || drop(black_box(preview::png(&terrain, None).unwrap())),
                budget,
            ),
        ),
        (
            "heightmap.csv".into(),
            median_time(|| drop(black_box(terrain.heightmap().to_csv())), budget),
        ),
        (
            "mesh".into(),
            median_time(|| drop(black_box(terrain.mesh())), budget),
        ),
        (
            "terrain.obj".into(),
            median_time(|| drop(black_box(obj(&mesh, Some("terrain.mtl")))), budget),
        ),
        (
            "terrain.usda".into(),
            median_time(
                || drop(black_box(usda(&mesh, &rse_core::Globals::default()))),
                budget,
            ),
        ),
        (
            "box set".into(),
            median_time(|| drop(black_box(terrain.boxes())), budget),
        ),
        (
            "mjcf() (MuJoCo template, blocks)".into(),
            median_time(
                || drop(black_box(rse_world::mjcf(&terrain).unwrap())),
                budget,
            ),
        ),
    ]
}

/// Each target's share: a world with it and the OBJ, less one with the OBJ
/// alone (new worlds each run, as in a batch: nothing cached between).
fn targets(scheme: &Scheme, templates: &Templates, budget: Duration) -> Vec<(String, Duration)> {
    let mut index = 0;
    let mut time = |targets: &str| {
        median_time(
            || {
                index += 1;
                drop(black_box(build(scheme, templates, targets, index)));
            },
            budget,
        )
    };
    let obj_only = time("obj");
    [
        Target::Gazebo,
        Target::Webots,
        Target::Mujoco,
        Target::Urdf,
        Target::Usd,
    ]
    .into_iter()
    .map(|target| {
        let with = time(&format!("obj,{target}"));
        (
            format!("{target} (world with it less without)"),
            with.saturating_sub(obj_only),
        )
    })
    .collect()
}

/// Placing `world` (temporary folder, rename), and copying it file by file.
fn place_and_copy(world: &WorldFiles, budget: Duration) -> (Duration, Duration) {
    let root = tempfile::tempdir().expect("temporary folder");
    let mut round = 0;
    let place = median_time(
        || {
            round += 1;
            let out = root.path().join(format!("placed_{round}"));
            std::fs::create_dir(&out).unwrap();
            black_box(place_world(&out, world, false).unwrap());
        },
        budget,
    );
    let source = root.path().join("placed_1").join(&world.name);
    let copy = median_time(
        || {
            round += 1;
            copy_tree(&source, &root.path().join(format!("copy_{round}")));
        },
        budget,
    );
    (place, copy)
}

fn main() {
    let scheme_path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../schemes/nist_hill.csv");
    let scheme = Scheme::load(scheme_path).expect("sample loads");
    let templates = Templates::builtin();
    let all = &Targets::all().to_string();
    let budget = Duration::from_secs(2);

    let mut rows = parts(&scheme, budget);
    rows.extend(targets(&scheme, &templates, budget));
    let world = build(&scheme, &templates, all, 0);
    rows.push((
        "rse.json's hashes (every file)".into(),
        median_time(
            || {
                for bytes in world.files.values() {
                    black_box(sha256_hex(bytes));
                }
            },
            budget,
        ),
    ));
    let mut index = 0;
    let whole = median_time(
        || {
            index += 1;
            drop(black_box(build(&scheme, &templates, all, index)));
        },
        budget,
    );
    let (place, copy) = place_and_copy(&world, budget);

    println!(
        "one world of nist_hill.csv, targets {all}: {} files, {:.1} KB",
        world.files.len(),
        world.bytes() as f64 / 1e3
    );
    println!("{:<44} {:>9}", "stage", "ms");
    let ms = |time: Duration| time.as_secs_f64() * 1e3;
    for (name, time) in &rows {
        println!("{name:<44} {:>9.3}", ms(*time));
    }
    println!("{:<44} {:>9.3}", "built in memory, all targets", ms(whole));
    println!("{:<44} {:>9.3}", "placed (temp folder, rename)", ms(place));
    println!(
        "{:<44} {:>9.3}",
        "world, built and placed",
        ms(whole + place)
    );
    println!(
        "{:<44} {:>9.3}",
        "copy of the placed folder (cp -r)",
        ms(copy)
    );
    println!(
        "world / copy: {:.2} on one core",
        (whole + place).as_secs_f64() / copy.as_secs_f64()
    );
}
