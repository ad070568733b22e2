//! Property tests: determinism, bounds, order rules, round trips, and a parser
//! that never panics on any input.

use proptest::prelude::*;
use rse_core::{Globals, Obstacle, ObstacleFields, ObstacleKind, Pallets, Param, Scheme, generate};

fn int_param(max: u32) -> impl Strategy<Value = Param<u32>> {
    prop_oneof![
        (0..=max).prop_map(Param::Fixed),
        (0..=max, 0..=max).prop_map(|(a, b)| Param::Range(a.min(b), a.max(b))),
    ]
}

fn real_param(lo: f64, hi: f64) -> impl Strategy<Value = Param<f64>> {
    prop_oneof![
        (lo..=hi).prop_map(Param::Fixed),
        (lo..=hi, lo..=hi).prop_map(|(a, b)| Param::Range(a.min(b), a.max(b))),
        // whole degrees, the common case in files
        (lo as u32..=hi as u32).prop_map(|a| Param::Fixed(f64::from(a))),
    ]
}

fn obstacle(nx: u32, ny: u32) -> impl Strategy<Value = Obstacle> {
    (
        prop::sample::select(ObstacleKind::ALL.to_vec()),
        int_param(6),
        real_param(0.0, 90.0),
        (
            int_param(nx - 1),
            int_param(ny - 1),
            int_param(nx - 1),
            int_param(ny - 1),
        ),
        prop::option::of(real_param(0.0, 3.0)),
        prop_oneof![
            (1u32..=4).prop_map(Param::Fixed),
            (1u32..=4, 1u32..=4).prop_map(|(a, b)| Param::Range(a.min(b), a.max(b))),
        ],
    )
        .prop_map(|(kind, height, angle, (x1, y1, x2, y2), sigma, tread)| {
            use ObstacleKind::{LongPit, Peak, Pit, Pyramid, PyramidPit, Wall};
            let geometric = !matches!(kind, ObstacleKind::Random | ObstacleKind::Gaussian);
            let sloped = matches!(kind, Peak | Pit | Wall | LongPit);
            let two_points = matches!(kind, Wall | LongPit) || kind.is_rectangle();
            let fields = ObstacleFields {
                height: Some(height),
                angle: sloped.then_some(angle),
                x1: geometric.then_some(x1),
                y1: geometric.then_some(y1),
                x2: two_points.then_some(x2),
                y2: two_points.then_some(y2),
                sigma: sigma.filter(|_| kind == ObstacleKind::Gaussian),
                tread: matches!(kind, Pyramid | PyramidPit).then_some(tread),
            };
            Obstacle::new(kind, fields).expect("the strategy builds valid rows")
        })
}

fn globals() -> impl Strategy<Value = Globals> {
    (
        (1u32..=24, 1u32..=24),
        prop::option::of((1u32..=4, 1u32..=3, 1u32..=3, any::<bool>())),
        prop::sample::select(vec![0.05, 0.1, 0.2]),
        prop::sample::select(vec![0.025, 0.05, 0.1]),
        prop::sample::select(vec![0.0, 0.02]),
    )
        .prop_map(
            |((nx, ny), pallets, block_size, step_height, base)| Globals {
                size: [nx, ny],
                pallets: pallets.map(|(size, px, py, boundary)| Pallets {
                    size,
                    count: [px, py],
                    boundary,
                }),
                block_size,
                step_height,
                base,
                ..Globals::default()
            },
        )
}

fn scheme() -> impl Strategy<Value = Scheme> {
    globals().prop_flat_map(|g| {
        let grid = g.grid();
        prop::collection::vec(obstacle(grid.nx, grid.ny), 0..6)
            .prop_map(move |obstacles| Scheme::new(g, obstacles).expect("valid by construction"))
    })
}

fn has_range(o: &Obstacle) -> bool {
    let f = o.fields();
    let ints = [f.height, f.x1, f.y1, f.x2, f.y2];
    let reals = [f.angle, f.sigma];
    ints.iter().any(|p| matches!(p, Some(Param::Range(..))))
        || reals.iter().any(|p| matches!(p, Some(Param::Range(..))))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn same_inputs_same_heights(s in scheme(), seed: u64, index in 0u64..1000) {
        prop_assert_eq!(generate(&s, seed, index), generate(&s, seed, index));
    }

    #[test]
    fn heights_stay_within_zero_and_the_tallest_obstacle(s in scheme(), seed: u64) {
        let terrain = generate(&s, seed, 3);
        let tallest = s.obstacles().iter().map(|o| o.fields().height.unwrap().hi()).max().unwrap_or(0);
        let frame = u32::from(s.grid().frame_period.is_some());
        let highest = u32::from(terrain.heightmap().max());
        prop_assert!(highest <= tallest.max(frame), "{} > {}", highest, tallest.max(frame));
        let grid = s.grid();
        prop_assert_eq!(terrain.heightmap().cells().len(), grid.cells());
        for y in 0..grid.ny {
            for x in 0..grid.nx {
                if grid.is_frame(x, y) {
                    prop_assert_eq!(terrain.heightmap().get(x, y), 1);
                }
            }
        }
    }

    #[test]
    fn raising_fixed_obstacles_commute(s in scheme(), rotate in 0usize..6) {
        // Max is commutative: without draws (no ranges, no per-cell values)
        // and without subtraction, the order of the table does not matter.
        let fixed: Vec<Obstacle> = s
            .obstacles()
            .iter()
            .filter(|o| matches!(o.kind(), ObstacleKind::Peak | ObstacleKind::Wall) && !has_range(o))
            .cloned()
            .collect();
        let mut turned = fixed.clone();
        if !turned.is_empty() {
            let by = rotate % turned.len();
            turned.rotate_left(by);
        }
        let a = Scheme::new(*s.globals(), fixed).unwrap();
        let b = Scheme::new(*s.globals(), turned).unwrap();
        let (ta, tb) = (generate(&a, 1, 0), generate(&b, 1, 0));
        prop_assert_eq!(ta.heightmap(), tb.heightmap());
    }

    #[test]
    fn a_pit_never_raises_and_a_raise_never_lowers(s in scheme()) {
        // Appending an obstacle after the table changes each cell only in its direction.
        let before = generate(&s, 2, 0);
        let grid = s.grid();
        for kind in [ObstacleKind::Peak, ObstacleKind::Pit] {
            let fields = ObstacleFields {
                height: Some(Param::Fixed(2)),
                angle: Some(Param::Fixed(45.0)),
                x1: Some(Param::Fixed(grid.nx / 2)),
                y1: Some(Param::Fixed(grid.ny / 2)),
                ..ObstacleFields::default()
            };
            let mut table = s.obstacles().to_vec();
            table.push(Obstacle::new(kind, fields).unwrap());
            let after = generate(&Scheme::new(*s.globals(), table).unwrap(), 2, 0);
            for (i, (&a, &b)) in before.heightmap().cells().iter().zip(after.heightmap().cells()).enumerate() {
                let (x, y) = (i as u32 % grid.nx, i as u32 / grid.nx);
                if grid.is_frame(x, y) {
                    continue;
                }
                if kind.lowers() { prop_assert!(b <= a) } else { prop_assert!(b >= a) }
            }
        }
    }

    #[test]
    fn csv_round_trip_is_exact(s in scheme()) {
        let text = s.to_csv();
        let back = Scheme::from_csv(&text, None).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(&back, &s);
        prop_assert_eq!(back.to_csv(), text);
    }

    #[test]
    fn parser_never_panics_on_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let _ = Scheme::from_csv_bytes(&bytes, Some("fuzz.csv"));
    }

    #[test]
    fn parser_never_panics_on_scheme_like_text(
        lines in prop::collection::vec(
            prop::collection::vec(
                prop::sample::select(vec![
                    "# size: 5x5", "# pallets: 2x2", "# pallet_size: 0", "#", "type", "height",
                    "angle", "x1", "y1", "x2", "y2", "sigma", "random", "peak", "wall", "pit",
                    "long pit", "gaussian", "3", "-1", "0..4", "4..0", "90", "45.5", "1e9",
                    "99999999999", "", " ", "\"", "..", "NaN", "x", ":", "\u{feff}",
                ]),
                0..9,
            ),
            0..8,
        )
    ) {
        let text: String = lines.iter().map(|fields| fields.join(",") + "\n").collect();
        if let Ok(s) = Scheme::from_csv(&text, None) {
            let _ = generate(&s, 0, 0);
            prop_assert_eq!(Scheme::from_csv(&s.to_csv(), None).ok(), Some(s));
        }
    }
}
