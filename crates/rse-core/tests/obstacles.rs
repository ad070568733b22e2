//! Each obstacle against values worked out by hand from docs/schemes.md.
//!
//! With S = 0.1 m and step = 0.1 m, a cell `d` cells from the top gets
//! `floor((H·0.1 − d·0.1·tan a) / 0.1)` steps, i.e. `floor(H − d·tan a)`.

use rse_core::{ObstacleKind, generate};

use crate::util::{heights, picture, scheme};

const HEADER: &str = "type,height,angle,x1,y1,x2,y2\n";

fn grid(nx: u32, ny: u32, rows: &str) -> String {
    format!("# size: {nx}x{ny}\n{HEADER}{rows}")
}

#[test]
fn peak_at_45_degrees_falls_one_step_per_cell() {
    let map = heights(&grid(11, 11, "peak,3,45,5,5,,\n"));
    assert_eq!(map.get(5, 5), 3);
    assert_eq!(map.get(6, 5), 2); // d = 1: 3 − 1
    assert_eq!(map.get(5, 7), 1); // d = 2
    assert_eq!(map.get(8, 5), 0); // d = 3: exactly 0
    assert_eq!(map.get(6, 6), 1); // d = √2: floor(1.586)
    assert_eq!(map.get(7, 6), 0); // d = √5: floor(0.764)
    assert_eq!(map.get(4, 4), 1); // symmetric
}

#[test]
fn peak_at_30_degrees_reaches_five_cells() {
    // tan 30° = 0.57735: 3 − d·0.57735 → d=1: 2.42, 2: 1.85, 3: 1.27, 4: 0.69, 5: 0.11.
    let map = heights(&grid(13, 1, "peak,3,30,0,0,,\n"));
    assert_eq!(map.row(0)[..7], [3, 2, 1, 1, 0, 0, 0]);
}

#[test]
fn peak_uses_step_height_and_block_size() {
    // step 0.05, S 0.1, H 4 (0.2 m), 45°: d = 1 cell = 0.1 m → 0.1 m = 2 steps.
    let text = format!("# size: 9x1\n# step_height: 0.05\n{HEADER}peak,4,45,0,0,,\n");
    assert_eq!(heights(&text).row(0)[..5], [4, 2, 0, 0, 0]);
    // S 0.2: one cell = 0.2 m → 0 steps beside the top.
    let text = format!("# size: 9x1\n# block_size: 0.2\n{HEADER}peak,2,45,0,0,,\n");
    assert_eq!(heights(&text).row(0)[..3], [2, 0, 0]);
}

#[test]
fn peak_at_90_degrees_is_one_block_and_at_0_lifts_everything() {
    let map = heights(&grid(5, 5, "peak,4,90,2,2,,\n"));
    assert_eq!(map.cells().iter().map(|&h| u32::from(h)).sum::<u32>(), 4);
    assert_eq!(map.get(2, 2), 4);
    let map = heights(&grid(5, 5, "peak,4,0,2,2,,\n"));
    assert!(map.cells().iter().all(|&h| h == 4));
}

#[test]
fn wall_touches_only_cells_that_project_onto_it() {
    let map = heights(&grid(11, 7, "wall,2,45,2,3,8,3\n"));
    assert_eq!(
        picture(&map),
        [
            "00000000000",
            "00000000000",
            "00111111100",
            "00222222200",
            "00111111100",
            "00000000000",
            "00000000000",
        ]
    );
}

#[test]
fn diagonal_wall_is_three_blocks_wide_at_90_degrees() {
    // Cells beside a 45° line are exactly √2/2 from it, which counts as the top.
    let map = heights(&grid(6, 6, "wall,2,90,0,0,4,4\n"));
    for y in 0..6u32 {
        for x in 0..6u32 {
            let on = x.abs_diff(y) <= 1 && x + y <= 8;
            assert_eq!(map.get(x, y), if on { 2 } else { 0 }, "cell ({x}, {y})");
        }
    }
}

#[test]
fn sloped_diagonal_wall_uses_perpendicular_distance() {
    // From (0,0) to (6,6); cell (4,2) is 2/√2·… = √2 cells from the line:
    // 3 − √2 = 1.59 → 1 at 45°. Cell (3,1) likewise; (5,1) is 2√2 away → 0.
    let map = heights(&grid(8, 8, "wall,3,45,0,0,6,6\n"));
    assert_eq!(map.get(3, 3), 3);
    assert_eq!(map.get(4, 3), 3); // √2/2 away
    assert_eq!(map.get(4, 2), 1);
    assert_eq!(map.get(3, 1), 1);
    assert_eq!(map.get(5, 1), 0);
    assert_eq!(map.get(7, 7), 0); // beyond the end: does not project
}

#[test]
fn degenerate_wall_is_a_peak() {
    for kind in ["wall", "long_pit"] {
        let wall = grid(9, 9, &format!("peak,4,0,0,0,,\n{kind},3,30,4,4,4,4\n"));
        let point = if kind == "wall" { "peak" } else { "pit" };
        let peak = grid(9, 9, &format!("peak,4,0,0,0,,\n{point},3,30,4,4,,\n"));
        assert_eq!(heights(&wall), heights(&peak), "{kind}");
    }
}

#[test]
fn pits_subtract_and_never_go_below_zero() {
    let map = heights(&grid(
        5,
        5,
        "peak,2,90,2,2,,\npit,5,90,2,2,,\npit,1,90,0,0,,\n",
    ));
    assert!(map.cells().iter().all(|&h| h == 0));
    // Lift to 3, then a 45° pit of 2: centre 1, neighbours 3 − 1 = 2, beyond 3.
    let map = heights(&grid(5, 1, "peak,3,0,0,0,,\npit,2,45,2,0,,\n"));
    assert_eq!(map.row(0), [3, 2, 1, 2, 3]);
}

#[test]
fn long_pit_cuts_a_trench() {
    let map = heights(&grid(5, 5, "peak,3,0,0,0,,\nlong_pit,2,90,0,2,4,2\n"));
    assert_eq!(picture(&map), ["33333", "33333", "11111", "33333", "33333"]);
}

#[test]
fn raising_obstacles_take_the_maximum() {
    let high_then_low = heights(&grid(5, 5, "peak,3,90,2,2,,\npeak,1,0,0,0,,\n"));
    assert_eq!(high_then_low.get(2, 2), 3);
    assert_eq!(high_then_low.get(0, 0), 1);
    let low_then_high = heights(&grid(5, 5, "peak,1,0,0,0,,\npeak,3,90,2,2,,\n"));
    assert_eq!(high_then_low, low_then_high);
}

#[test]
fn order_matters_between_raising_and_lowering() {
    let pit_first = heights(&grid(5, 1, "pit,2,90,2,0,,\npeak,3,0,0,0,,\n"));
    assert_eq!(pit_first.row(0), [3, 3, 3, 3, 3]);
    let pit_last = heights(&grid(5, 1, "peak,3,0,0,0,,\npit,2,90,2,0,,\n"));
    assert_eq!(pit_last.row(0), [3, 3, 1, 3, 3]);
}

#[test]
fn random_fills_every_value_from_zero_to_h() {
    let map = heights(&grid(60, 60, "random,4,,,,,\n"));
    let mut counts = [0u32; 5];
    for &h in map.cells() {
        counts[usize::from(h)] += 1;
    }
    // 3600 cells, 720 expected each.
    assert!(
        counts.iter().all(|&c| (600..840).contains(&c)),
        "{counts:?}"
    );
}

#[test]
fn gaussian_centres_on_half_the_height() {
    let map = heights("# size: 60x60\ntype,height,sigma\ngaussian,4,1\n");
    let mean = map.cells().iter().map(|&h| f64::from(h)).sum::<f64>() / 3600.0;
    assert!((mean - 2.0).abs() < 0.05, "mean {mean}");
    assert!(map.cells().iter().all(|&h| h <= 4));
    // sigma 0: every cell is exactly H/2.
    let flat = heights("# size: 4x4\ntype,height,sigma\ngaussian,4,0\n");
    assert!(flat.cells().iter().all(|&h| h == 2));
}

#[test]
fn pallets_3_with_2x3_give_9x13_and_frames_of_one_step() {
    let text =
        format!("# pallets: 2x3\n# pallet_size: 3\n{HEADER}peak,4,0,1,1,,\npit,2,90,4,4,,\n");
    let terrain = generate(&scheme(&text), 0, 0);
    let map = terrain.heightmap();
    assert_eq!((map.nx(), map.ny()), (9, 13));
    for y in 0..13 {
        for x in 0..9 {
            let frame = x % 4 == 0 || y % 4 == 0;
            let expected = if frame { 1 } else { 4 };
            assert_eq!(map.get(x, y), expected, "cell ({x}, {y})");
        }
    }
}

#[test]
fn pallets_without_boundary_have_no_frame() {
    let text = format!(
        "# pallets: 2x3\n# pallet_size: 3\n# pallet_boundary: false\n{HEADER}peak,4,0,1,1,,\n"
    );
    let map = heights(&text);
    assert_eq!((map.nx(), map.ny()), (6, 9));
    assert!(map.cells().iter().all(|&h| h == 4));
}

#[test]
fn ranges_are_drawn_per_world_within_bounds() {
    let s = scheme(&grid(20, 20, "peak,2..5,10..80,3..15,4..16,,\n"));
    let mut points = std::collections::BTreeSet::new();
    for index in 0..50 {
        let terrain = generate(&s, 9, index);
        let drawn = &terrain.drawn()[0];
        assert_eq!(drawn.kind, ObstacleKind::Peak);
        let [x, y] = drawn.p1.unwrap();
        assert!((3..=15).contains(&x) && (4..=16).contains(&y));
        assert!((2..=5).contains(&drawn.height));
        let angle = drawn.angle.unwrap();
        assert!((10.0..80.0).contains(&angle));
        assert_eq!(terrain.heightmap().get(x, y), drawn.height as u16);
        points.insert((x, y));
    }
    assert!(
        points.len() > 20,
        "only {} distinct points in 50 worlds",
        points.len()
    );
}

#[test]
fn a_world_does_not_depend_on_its_neighbours() {
    let s = scheme(&grid(10, 10, "random,3,,,,,\npeak,3,45,0..9,0..9,,\n"));
    let alone = generate(&s, 5, 7);
    let after_others: Vec<_> = (0..10).map(|i| generate(&s, 5, i)).collect();
    assert_eq!(after_others[7], alone);
    assert_ne!(after_others[6].heightmap(), alone.heightmap());
    assert_ne!(generate(&s, 6, 7).heightmap(), alone.heightmap());
}

#[test]
fn empty_table_gives_a_flat_zero_map() {
    let map = heights("# size: 3x2\ntype,height\n");
    assert_eq!(map.cells(), [0; 6]);
}

const STAIRS: &str = "type,height,angle,x1,y1,x2,y2,tread\n";

fn stairs_grid(nx: u32, ny: u32, rows: &str) -> String {
    format!("# size: {nx}x{ny}\n{STAIRS}{rows}")
}

#[test]
fn stairs_climb_one_tread_at_a_time_from_the_first_corner() {
    // A run of 8 cells, 4 steps: treads of 2 cells, the last at H.
    let map = heights(&stairs_grid(10, 4, "stairs,4,,1,1,8,2,\n"));
    assert_eq!(
        picture(&map),
        ["0000000000", "0112233440", "0112233440", "0000000000"]
    );
    // From the other corner: the same flight, down along x.
    let down = heights(&stairs_grid(10, 4, "stairs,4,,8,2,1,1,\n"));
    assert_eq!(
        picture(&down),
        ["0000000000", "0443322110", "0443322110", "0000000000"]
    );
    // Along the longer side: y here; a run shorter than H makes risers of
    // several steps (ceil((i + 1)·H / run): 2, 4, 6).
    let tall = heights(&stairs_grid(2, 3, "stairs,6,,0,0,1,2,\n"));
    assert_eq!(picture(&tall), ["66", "44", "22"]); // y up: the first row printed is the last
}

#[test]
fn pyramids_rise_a_step_a_ring_to_a_plateau_and_pyramid_pits_go_down() {
    let map = heights(&stairs_grid(9, 7, "pyramid,2,,0,0,8,6,2\n"));
    assert_eq!(
        picture(&map),
        [
            "111111111",
            "111111111",
            "112222211",
            "112222211",
            "112222211",
            "111111111",
            "111111111"
        ]
    );
    // Down into raised ground: each ring a step deeper, to H.
    let pit = heights(&stairs_grid(
        7,
        7,
        "peak,4,0,0,0,,,\npyramid_pit,3,,0,0,6,6,1\n",
    ));
    assert_eq!(pit.row(3), [3, 2, 1, 1, 1, 2, 3]);
    assert_eq!(pit.get(3, 3), 1);
}

#[test]
fn a_tread_of_zero_is_refused_naming_its_column() {
    let error =
        rse_core::Scheme::from_csv(&stairs_grid(5, 5, "pyramid,2,,0,0,4,4,0\n"), None).unwrap_err();
    assert_eq!(error.field.as_deref(), Some("tread"), "{error}");
    let error =
        rse_core::Scheme::from_csv(&stairs_grid(5, 5, "stairs,2,30,0,0,4,4,\n"), None).unwrap_err();
    assert_eq!(error.field.as_deref(), Some("angle"), "{error}");
    let error =
        rse_core::Scheme::from_csv(&stairs_grid(5, 5, "pyramid,2,,0,0,4,4,\n"), None).unwrap_err();
    assert_eq!(error.field.as_deref(), Some("tread"), "{error}");
}

#[test]
fn stairs_and_pyramids_read_back_as_written() {
    let text = stairs_grid(
        12,
        9,
        "stairs,3..5,,0,0,11,2..4,\npyramid_pit,2,,1,1,9..11,8,1..3\n",
    );
    let scheme = scheme(&text);
    let again = rse_core::Scheme::from_csv(&scheme.to_csv(), None).unwrap();
    assert_eq!(again.obstacles(), scheme.obstacles());
    assert!(scheme.to_csv().contains(",tread\n"), "{}", scheme.to_csv());
    // A scheme without stairs is written without the column, as before.
    assert!(
        !rse_core::Scheme::from_csv(&grid(5, 5, "peak,1,45,2,2,,\n"), None)
            .unwrap()
            .to_csv()
            .contains("tread")
    );
    assert_eq!(
        generate(&scheme, 3, 1).drawn()[1].kind,
        ObstacleKind::PyramidPit
    );
}
