//! Mesh size and build time, beside a naive mesh of one closed box per cell
//! built from the same heightmaps. Prints a table; run with
//! `cargo bench -p rse-core --bench mesh`.
//!
//! Targets: 50×50 `random` of height 4 ≤ 20,000 triangles
//! (aim 15,000; Isaac Lab's random grid: 30,060); wall and peak samples ≥ 5×
//! fewer than naive; flat 1000×1000 ≤ 12; meshing 1000×1000 random < 0.5 s.
//!
//! Two naive baselines: "every cell", a closed box on every cell as the RL
//! terrain generators build their grids (12 triangles a cell), and "solid
//! cells", boxes only where a cell has height (the smallest per-cell mesh).

mod common;

use std::hint::black_box;
use std::time::Duration;

use rse_core::mesh::naive::box_per_cell;
use rse_core::{Scheme, generate};

/// Triangles of the naive mesh: 12 per cell with solid (a closed box each).
fn naive_triangles(terrain: &rse_core::Terrain) -> usize {
    let base = terrain.base() > 0.0;
    12 * terrain
        .heightmap()
        .cells()
        .iter()
        .filter(|&&h| h > 0 || base)
        .count()
}

/// The median of 5 to 200 runs within `budget`.
fn median_time(run: impl FnMut(), budget: Duration) -> Duration {
    common::median_time(run, budget, 5, 200)
}

fn row(name: &str, terrain: &rse_core::Terrain) {
    let mesh = terrain.mesh();
    let cells = terrain.heightmap().cells().len();
    let naive = naive_triangles(terrain);
    let every_cell = 12 * cells;
    let ours = mesh.triangles().len();
    let build = median_time(|| drop(black_box(terrain.mesh())), Duration::from_secs(2));
    let naive_build = median_time(
        || drop(black_box(box_per_cell(terrain))),
        Duration::from_secs(2),
    );
    println!(
        "{name:<24} {cells:>8} {ours:>9} {:>6.2} {every_cell:>9} {:>8.1}x {naive:>9} {:>7.1}x {:>9.3} {:>9.3}",
        ours as f64 / cells as f64,
        every_cell as f64 / ours.max(1) as f64,
        naive as f64 / ours.max(1) as f64,
        build.as_secs_f64() * 1e3,
        naive_build.as_secs_f64() * 1e3,
    );
}

fn scheme(text: &str) -> Scheme {
    Scheme::from_csv(text, None).expect("bench schemes are valid")
}

fn main() {
    let samples = concat!(env!("CARGO_MANIFEST_DIR"), "/../../schemes/");
    println!(
        "{:<24} {:>8} {:>9} {:>6} {:>9} {:>9} {:>9} {:>8} {:>9} {:>9}",
        "heightmap",
        "cells",
        "triangles",
        "/cell",
        "naive all",
        "fewer",
        "naive sol",
        "fewer",
        "build ms",
        "naive ms"
    );
    let random50 = scheme("# size: 50x50\ntype,height\nrandom,4\n");
    for index in 0..3 {
        row(
            &format!("random 50x50 H4 (world {index})"),
            &generate(&random50, 0, index),
        );
    }
    for name in [
        "wall",
        "peak",
        "wall_long_pit",
        "nist_hill",
        "nist_diagonal_hill",
        "six_obstacles",
        "curriculum",
    ] {
        let s = Scheme::load(format!("{samples}{name}.csv")).expect("sample loads");
        row(name, &generate(&s, 0, 0));
    }
    row(
        "flat 1000x1000",
        &generate(
            &scheme("# size: 1000x1000\ntype,height,angle,x1,y1\npeak,2,0,0,0\n"),
            0,
            0,
        ),
    );
    row(
        "random 1000x1000 H4",
        &generate(&scheme("# size: 1000x1000\ntype,height\nrandom,4\n"), 0, 0),
    );
}
