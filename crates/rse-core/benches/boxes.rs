//! The block model's cover beside the greedy search as first written (which
//! walks the area of every rectangle it tries), on the same heightmaps: the
//! same boxes, so only time differs. Prints a table; run with
//! `cargo bench -p rse-core --bench boxes`.
//!
//! Targets: cones `peak,R,45,R,R` on 2R×2R near-linear in their cells (the
//! area walk grew as R^3.5: 155 s at R = 500); ordinary fields, whose
//! small candidates made the walk cheap, within 1.5× of it.

mod common;

use std::hint::black_box;
use std::time::Duration;

use rse_core::mesh::naive::area_walk_boxes;
use rse_core::{Scheme, Terrain, generate};

/// The median of 3 to 100 runs within `budget`.
fn median_time(run: impl FnMut(), budget: Duration) -> Duration {
    common::median_time(run, budget, 3, 100)
}

fn row(name: &str, terrain: &Terrain, walk_too: bool) {
    let boxes = terrain.boxes();
    let cells = terrain.heightmap().cells().len();
    let ours = median_time(|| drop(black_box(terrain.boxes())), Duration::from_secs(3));
    let walk = walk_too.then(|| {
        assert_eq!(area_walk_boxes(terrain), boxes, "{name}: the covers differ");
        median_time(
            || drop(black_box(area_walk_boxes(terrain))),
            Duration::from_secs(3),
        )
    });
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let walls = terrain.heightmap().walls().count;
    println!(
        "{name:<28} {cells:>9} {walls:>9} {:>8} {:>10.1} {:>8.1} {:>8.1} {:>12} {:>8}",
        boxes.len(),
        ms(ours),
        ours.as_secs_f64() * 1e9 / cells as f64,
        ours.as_secs_f64() * 1e9 / walls.max(1) as f64,
        walk.map_or("-".into(), |w| format!("{:.1}", ms(w))),
        walk.map_or("-".into(), |w| format!(
            "{:.1}x",
            w.as_secs_f64() / ours.as_secs_f64()
        )),
    );
}

fn scheme(text: &str) -> Scheme {
    Scheme::from_csv(text, None).expect("bench schemes are valid")
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    println!(
        "{:<28} {:>9} {:>9} {:>8} {:>10} {:>8} {:>8} {:>12} {:>8}",
        "heightmap",
        "cells",
        "walls",
        "boxes",
        "cover ms",
        "ns/cell",
        "ns/wall",
        "area walk ms",
        "faster"
    );
    let samples = concat!(env!("CARGO_MANIFEST_DIR"), "/../../schemes/");
    for name in ["six_obstacles", "nist_hill", "wall_long_pit"] {
        let s = Scheme::load(format!("{samples}{name}.csv")).expect("sample loads");
        row(name, &generate(&s, 0, 0), true);
    }
    for (name, text) in [
        (
            "random,4 1000x1000",
            "# size: 1000x1000\ntype,height\nrandom,4\n",
        ),
        (
            "random,4 1000x1000 on a base",
            "# size: 1000x1000\n# base: 0.1\ntype,height\nrandom,4\n",
        ),
        // Flat fields: one box, or none; the indexes alone.
        ("flat 1000x1000", "# size: 1000x1000\ntype,height\n"),
        (
            "flat 1000x1000 on a base",
            "# size: 1000x1000\n# base: 0.01\ntype,height\n",
        ),
        (
            "random,1 1000x1000",
            "# size: 1000x1000\ntype,height\nrandom,1\n",
        ),
        (
            "random,1000 300x300",
            "# size: 300x300\ntype,height\nrandom,1000\n",
        ),
        (
            "strip 1x1000000 random,3",
            "# size: 1x1000000\ntype,height\nrandom,3\n",
        ),
    ] {
        row(name, &generate(&scheme(text), 0, 0), true);
    }
    let radii: &[u32] = if quick {
        &[100, 200]
    } else {
        &[100, 200, 300, 500, 1000]
    };
    for &r in radii {
        let text = format!(
            "# size: {0}x{0}\ntype,height,angle,x1,y1\npeak,{r},45,{r},{r}\n",
            2 * r
        );
        // The area walk past R = 200 takes minutes: shown up to there.
        row(
            &format!("cone R={r} on {0}x{0}", 2 * r),
            &generate(&scheme(&text), 0, 0),
            r <= 200,
        );
    }
}
