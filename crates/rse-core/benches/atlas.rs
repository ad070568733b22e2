//! An Isaac Lab-sized curriculum atlas: 10 rows × 20 cols of 80×80-cell
//! tiles (8 m at 0.1 m cells, Isaac Lab's rough-terrain layout, 1.28 M
//! cells) of `six_obstacles.csv`. Prints the time to build heights,
//! origins and flat patches, and to mesh the whole map, beside a closed box
//! on every cell (Isaac Lab's and `legged_gym`'s grids); run with
//! `cargo bench -p rse-core --bench atlas`.
//!
//! Targets: heights + origins + flat patches + single mesh < 1 s
//! on the 2-core machine; triangles ≤ 0.5× a box on every cell.

mod common;

use std::hint::black_box;
use std::time::Duration;

use rse_core::mesh::naive::box_per_cell;
use rse_core::{AtlasOptions, Difficulty, PatchOptions, Scheme, build_atlas};

/// The median of 5 to 50 runs within `budget`.
fn median_time(run: impl FnMut(), budget: Duration) -> Duration {
    common::median_time(run, budget, 5, 50)
}

fn main() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../schemes/six_obstacles.csv"
    );
    let scheme = Scheme::load(path).expect("the sample loads");
    let mut globals = *scheme.globals();
    globals.size = [80, 80];
    let scheme = scheme.with_globals(globals).expect("80x80 fits the sample");
    let options = AtlasOptions {
        rows: 10,
        cols: 20,
        seed: 0,
        border: 0,
        difficulty: (Difficulty::new(0.0).unwrap(), Difficulty::FULL),
        rule: rse_core::DifficultyRule::CURRENT,
        spawn_radius: 0.3,
        patches: PatchOptions {
            count: 10,
            radius: 0.3,
            max_step: 0,
        },
    };
    let schemes = [scheme];
    let atlas = build_atlas(&schemes, &options).expect("a valid layout");
    let cells = atlas.terrain().heightmap().cells().len();
    let without_patches = AtlasOptions {
        patches: PatchOptions::default(),
        ..options
    };
    let layout = median_time(
        || drop(black_box(build_atlas(&schemes, &without_patches).unwrap())),
        Duration::from_secs(3),
    );
    let with_patches = median_time(
        || drop(black_box(build_atlas(&schemes, &options).unwrap())),
        Duration::from_secs(3),
    );
    let mesh_time = median_time(
        || drop(black_box(atlas.terrain().mesh())),
        Duration::from_secs(3),
    );
    let naive_time = median_time(
        || drop(black_box(box_per_cell(atlas.terrain()))),
        Duration::from_secs(3),
    );
    let triangles = atlas.terrain().mesh().triangles().len();
    let every_cell = 12 * cells;
    let patches: usize = atlas.tiles().iter().map(|t| t.flat_patches.len()).sum();
    let total = with_patches + mesh_time;
    println!(
        "atlas 10x20 tiles of 80x80 cells, six_obstacles.csv, difficulty 0..1 ({cells} cells)"
    );
    println!("  heights + origins                {:>9.1} ms", ms(layout));
    println!(
        "  heights + origins + 10 patches   {:>9.1} ms ({patches} patches found)",
        ms(with_patches)
    );
    println!(
        "  single mesh                      {:>9.1} ms",
        ms(mesh_time)
    );
    println!(
        "  all of it                        {:>9.1} ms   (target < 1000 ms)",
        ms(total)
    );
    println!(
        "  mesh triangles                   {triangles:>9}   a box on every cell: {every_cell} ({:.3}x; target <= 0.5x), built in {:.1} ms",
        triangles as f64 / every_cell as f64,
        ms(naive_time)
    );
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
