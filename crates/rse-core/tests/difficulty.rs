//! The difficulty contract on every sample: D = 1 is `generate`, D = 0 is
//! flat but for the frames, every cell is `floor(D·h + u)` of its D = 1
//! height with one `u` per world (`floor(D·h + 0.5)` by the old rule), so
//! the layout is kept, heights grow with D, and no level above 0 is flat.
//! Cells under a ramp are its staircase at its scaled rise instead (a
//! plane scales by its rise: tested on its own below).

use rse_core::{Difficulty, DifficultyRule, Scheme, Terrain, generate, generate_at, generate_by};

/// Whether cell `(x, y)` lies under one of `terrain`'s ramps.
fn under_ramp(terrain: &Terrain, x: u32, y: u32) -> bool {
    terrain.ramps().iter().any(|r| r.covers(x, y))
}

use crate::util::sample_paths;

const LEVELS: [f64; 6] = [0.0, 0.2, 0.35, 0.5, 0.8, 1.0];

/// Every sample, worlds 0..3 of seed 7, at every one of `LEVELS` by
/// `rule`: the obstacles drawn are the full world's, the difficulty is
/// recorded, no cell is lower than at the level below, and `check` holds
/// for (full world, world, difficulty, what to say on failure).
fn each_level(rule: DifficultyRule, check: impl Fn(&Terrain, &Terrain, Difficulty, &str)) {
    for path in sample_paths() {
        let scheme = Scheme::load(&path).unwrap();
        for index in 0..3 {
            let full = generate(&scheme, 7, index);
            let mut previous: Option<Vec<u16>> = None;
            for d in LEVELS.map(|d| Difficulty::new(d).unwrap()) {
                let terrain = generate_by(&scheme, 7, index, d, rule);
                let what = format!("{} world {index} D {d}", path.display());
                assert_eq!(terrain.drawn(), full.drawn(), "{what}");
                assert_eq!(terrain.difficulty(), d, "{what}");
                check(&full, &terrain, d, &what);
                let cells = terrain.heightmap().cells().to_vec();
                if let Some(easier) = &previous {
                    assert!(easier.iter().zip(&cells).all(|(a, b)| a <= b), "{what}");
                }
                previous = Some(cells);
            }
        }
    }
}

#[test]
fn the_nearest_rule_rounds_every_cell_half_up() {
    each_level(DifficultyRule::Nearest, |full, terrain, d, what| {
        let grid = full.grid();
        for y in 0..grid.ny {
            for x in 0..grid.nx {
                if under_ramp(full, x, y) && !grid.is_frame(x, y) {
                    continue;
                }
                let want = if grid.is_frame(x, y) {
                    1
                } else {
                    d.scale(full.heightmap().get(x, y))
                };
                assert_eq!(terrain.heightmap().get(x, y), want, "{what}");
            }
        }
    });
}

#[test]
fn full_difficulty_is_generate_and_zero_is_flat() {
    for path in sample_paths() {
        let scheme = Scheme::load(&path).unwrap();
        let grid = scheme.grid();
        assert_eq!(
            generate_at(&scheme, 3, 1, Difficulty::FULL),
            generate(&scheme, 3, 1)
        );
        let flat = generate_at(&scheme, 3, 1, Difficulty::new(0.0).unwrap());
        for y in 0..grid.ny {
            for x in 0..grid.nx {
                let want = u16::from(grid.is_frame(x, y));
                assert_eq!(flat.heightmap().get(x, y), want, "{}", path.display());
            }
        }
    }
}

/// The rounded-up cells of `terrain` (scaled from `full` at `d`) are those
/// whose fraction `D·h − floor(D·h)` is at least one threshold, but for the
/// world's first highest cell, which is at least one step above `D = 0`.
fn assert_one_offset(full: &Terrain, terrain: &Terrain, d: Difficulty, what: &str) {
    let grid = full.grid();
    let (mut up, mut down) = (f64::INFINITY, f64::NEG_INFINITY);
    let cells = (0..grid.ny)
        .flat_map(|y| (0..grid.nx).map(move |x| (x, y)))
        .filter(|&(x, y)| !grid.is_frame(x, y) && !under_ramp(full, x, y));
    let highest = cells.clone().map(|(x, y)| full.heightmap().get(x, y)).max();
    // The first cell of the highest height: the one kept at a step.
    let anchor = cells
        .clone()
        .find(|&(x, y)| Some(full.heightmap().get(x, y)) == highest && highest > Some(0));
    for y in 0..grid.ny {
        for x in 0..grid.nx {
            let got = terrain.heightmap().get(x, y);
            if grid.is_frame(x, y) {
                assert_eq!(got, 1, "{what}");
                continue;
            }
            if under_ramp(full, x, y) {
                continue;
            }
            let h = full.heightmap().get(x, y);
            let scaled = d.get() * f64::from(h);
            let (low, frac) = (scaled.floor(), scaled - scaled.floor());
            let low = low as u16;
            if got == low + 1 {
                up = up.min(frac);
            } else if Some((x, y)) == anchor && d.get() > 0.0 {
                // Raised to a step, or rounded up or down by the offset.
                assert!(got >= 1, "{what}: the highest cell ({x}, {y}) fell to 0");
            } else if got == low {
                down = down.max(frac);
            } else {
                panic!("{what}: ({x}, {y}) of {h} steps is {got} at D {d}");
            }
        }
    }
    // Fractions that are equal in exact arithmetic (0.2·4, 0.2·9) may differ
    // by a few ulps in f64, either way.
    assert!(
        down < up + 1e-9,
        "{what}: no one offset rounds these cells ({down} ≥ {up})"
    );
}

#[test]
fn the_drawn_rule_rounds_every_cell_by_one_offset_and_keeps_a_step() {
    // What generate_at writes today.
    assert_eq!(DifficultyRule::CURRENT, DifficultyRule::Drawn);
    each_level(DifficultyRule::Drawn, assert_one_offset);
}

#[test]
fn no_level_above_zero_flattens_a_world_with_obstacles() {
    // One 1-step block: the old rule flattened it below D = 0.5.
    let scheme = Scheme::from_csv(
        "# size: 6x6\ntype,height,angle,x1,y1\npeak,1,90,3,3\n",
        None,
    )
    .unwrap();
    for index in 0..20 {
        for level in 1..10 {
            let d = Difficulty::new(f64::from(level) / 9.0).unwrap();
            let terrain = generate_at(&scheme, 1, index, d);
            assert_eq!(
                terrain.heightmap().get(3, 3),
                1,
                "world {index} level {level}"
            );
            let old = generate_by(&scheme, 1, index, d, DifficultyRule::Nearest);
            assert_eq!(old.heightmap().get(3, 3), u16::from(level >= 5));
        }
    }
}

#[test]
fn over_many_worlds_a_cell_averages_d_times_its_height() {
    // Two 3-step cells: floor(3·D + u) averages 3·D over u in the second
    // (the first, the world's highest, is kept at a step at least).
    let csv = "# size: 4x4\ntype,height,angle,x1,y1\npeak,3,90,1,1\npeak,3,90,2,2\n";
    let scheme = Scheme::from_csv(csv, None).unwrap();
    let d = Difficulty::new(0.3).unwrap();
    let worlds = 2000;
    let total: u32 = (0..worlds)
        .map(|index| u32::from(generate_at(&scheme, 5, index, d).heightmap().get(2, 2)))
        .sum();
    let mean = f64::from(total) / worlds as f64;
    // 0.9 expected; the standard error of 2000 draws of {0, 1} is 0.007.
    assert!((mean - 0.9).abs() < 0.05, "mean {mean}");
}

#[test]
fn a_ramp_scales_by_its_rise_and_keeps_a_step_above_zero() {
    let scheme = Scheme::from_csv(
        "# size: 12x3\ntype,height,angle,x1,y1,x2,y2\nramp,8,,0,0,11,2\n",
        None,
    )
    .unwrap();
    for index in 0..10 {
        let mut previous = 0;
        for level in 0..=10 {
            let d = Difficulty::new(f64::from(level) / 10.0).unwrap();
            let terrain = generate_at(&scheme, 3, index, d);
            let [ramp] = terrain.ramps() else {
                panic!("one ramp")
            };
            let rise = ramp.rise;
            // floor(8·D + u) for one u, and a step at least above D = 0.
            let scaled = 8.0 * d.get();
            assert!(
                f64::from(rise) >= scaled.floor() && f64::from(rise) <= scaled.floor() + 1.0,
                "world {index} D {d}: rise {rise}"
            );
            assert_eq!(rise == 0, level == 0, "world {index} D {d}");
            assert!(rise >= previous, "world {index}: rises grow with D");
            previous = rise;
            for x in 0..12 {
                assert_eq!(u32::from(terrain.heightmap().get(x, 1)), x * rise / 12);
            }
        }
    }
}
