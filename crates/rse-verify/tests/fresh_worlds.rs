//! A world `batch` has just written always passes `check`: random extreme
//! schemes inside every documented limit (slender walls, millimetre steps
//! and blocks, tall bases, every obstacle type (stairs, pyramids and ramps too), every target, both mesh
//! modes), seeded so that a failure comes back the same on any machine.

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use rse_core::Scheme;
use rse_verify::{CheckOptions, CheckReport, check_paths};
use rse_world::{BatchConfig, MeshMode, Targets, Templates, WorldConfig, write_batch};

/// A scheme's CSV text: lengths from the smallest allowed to large, heights
/// up to what the lengths allow, rows of every type.
fn extreme_scheme() -> impl Strategy<Value = String> {
    let lengths = (
        prop::sample::select(vec![0.001, 0.01, 0.1, 1.0, 7.3]),
        prop::sample::select(vec![0.001, 0.01, 0.05, 0.1, 0.37]),
        prop::sample::select(vec![0.0, 0.001, 0.3, 2.0]),
    );
    let size = (1u32..=40, 1u32..=40);
    let rows = prop::collection::vec(
        (
            prop::sample::select(vec![
                "random",
                "gaussian",
                "peak",
                "pit",
                "wall",
                "long_pit",
                "stairs",
                "pyramid",
                "pyramid_pit",
                "ramp",
                "crossing_ramps",
            ]),
            prop_oneof![1u32..=4, 1u32..=65_535, Just(9_999)],
            prop::sample::select(vec![0.0, 1.0, 30.0, 45.0, 89.0, 90.0]),
            (0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0),
        ),
        1..5,
    );
    (lengths, size, rows).prop_map(|((block, step, base), (nx, ny), rows)| {
        // The tallest height the lengths allow (the parser's own limits).
        let tallest = ((1000.0_f64 * block - base) / step)
            .floor()
            .clamp(1.0, 65_535.0) as u32;
        let mut text = format!(
            "# size: {nx}x{ny}\n# block_size: {block}\n# step_height: {step}\n# base: {base}\n"
        );
        text.push_str("type,height,angle,x1,y1,x2,y2,tread\n");
        for (kind, height, angle, (a, b, c, d)) in rows {
            let h = height.min(tallest);
            let at = |f: f64, n: u32| ((f * f64::from(n)) as u32).min(n - 1);
            let (x1, y1, x2, y2) = (at(a, nx), at(b, ny), at(c, nx), at(d, ny));
            // A pyramid's tread from the angle's draw: 1 to 4 cells.
            let tread = 1 + (angle as u32) % 4;
            let row = match kind {
                "random" | "gaussian" => format!("{kind},{h},,,,,,"),
                "peak" | "pit" => format!("{kind},{h},{angle},{x1},{y1},,,"),
                "stairs" | "ramp" | "crossing_ramps" => format!("{kind},{h},,{x1},{y1},{x2},{y2},"),
                "pyramid" | "pyramid_pit" => format!("{kind},{h},,{x1},{y1},{x2},{y2},{tread}"),
                _ => format!("{kind},{h},{angle},{x1},{y1},{x2},{y2},"),
            };
            text.push_str(&row);
            text.push('\n');
        }
        text
    })
}

/// `amount` worlds of `scheme` written by `batch` with `world`'s options
/// into a fresh folder, and `check`'s report on them.
fn written_and_checked(scheme: &Scheme, amount: u64, world: WorldConfig) -> CheckReport {
    let batch = BatchConfig {
        amount: Some(amount),
        world,
        ..BatchConfig::default()
    };
    batch_checked(scheme, batch, &CheckOptions::default())
}

/// The worlds of `scheme` that `batch` writes into a fresh folder, and
/// `check`'s report on them with `check`'s options.
fn batch_checked(scheme: &Scheme, batch: BatchConfig, check: &CheckOptions) -> CheckReport {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("worlds");
    let options = batch.resolve(scheme, out.clone()).unwrap();
    write_batch(scheme, &Templates::builtin(), &options, &|_| {}).unwrap();
    check_paths(&[out], check, &|| {}).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 24,
        rng_seed: RngSeed::Fixed(41),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn a_world_batch_writes_passes_check(text in extreme_scheme(), blocks in any::<bool>()) {
        // Past a documented limit the scheme is refused up front: not a world.
        let Ok(scheme) = Scheme::from_csv(&text, None) else { return Ok(()) };
        let report = written_and_checked(&scheme, 2, WorldConfig {
            targets: Some(Targets::all()),
            mesh: Some(if blocks { MeshMode::Blocks } else { MeshMode::Single }),
            ..WorldConfig::default()
        });
        prop_assert!(
            report.first_fault().is_none(),
            "{}\nfirst fault: {}\nscheme:\n{text}",
            report.verdict(),
            report.first_fault().unwrap_or_default()
        );
    }
}

/// The scheme that made 3 of 10 fresh worlds fail `check`: 0.01 m steps on
/// 0.1 m blocks, `random,9999` (tops of 999.9 block sizes, inside every
/// limit): every world passes.
#[test]
fn slender_random_walls_pass() {
    let scheme = Scheme::from_csv(
        "# size: 30x30\n# step_height: 0.01\ntype,height\nrandom,9999\n",
        None,
    )
    .unwrap();
    let report = written_and_checked(
        &scheme,
        10,
        WorldConfig {
            targets: Some(Targets::parse("obj").unwrap()),
            ..WorldConfig::default()
        },
    );
    assert!(report.first_fault().is_none(), "{}", report.verdict());
}

/// A terrain narrower than the smoke test's balls, of 30 cm towers on 2 cm
/// blocks (16 × 6 cm): a ball that rolls off a tower rolls on across the
/// floor, past the 0.5 m a box may slide (found by 150 cases of the
/// property test below, in 4 of 8 seeds). Every world passes `--physics`.
#[test]
fn balls_rolling_off_a_tiny_terrain_pass_the_physics_check() {
    let scheme = Scheme::from_csv(
        "# size: 8x3\n# block_size: 0.02\ntype,height\nrandom,3\n",
        None,
    )
    .unwrap();
    let check = CheckOptions {
        physics: true,
        ..CheckOptions::default()
    };
    for seed in [0, 1, 2] {
        let batch = BatchConfig {
            amount: Some(4),
            seed: Some(seed),
            world: WorldConfig {
                targets: Some(Targets::parse("obj").unwrap()),
                ..WorldConfig::default()
            },
            ..BatchConfig::default()
        };
        let report = batch_checked(&scheme, batch, &check);
        assert!(
            report.first_fault().is_none(),
            "seed {seed}: {}",
            report.first_fault().unwrap_or_default()
        );
    }
}

/// The fifth round's shapes: tall walls along long thin grids (their fan
/// edges once made the T-junction search give up), 1-cell strips (the
/// volume once drifted past its tolerance), 1 mm blocks; the physics
/// smoke test on the small ones it judges (blocks of 1 cm and up), and
/// its refusal, by name, below that; cones, the box cover's worst shape.
fn fifth_round_scheme() -> impl Strategy<Value = (String, bool)> {
    prop_oneof![
        // A tall wall along a long thin grid.
        (
            1u32..=9,
            200u32..=1000,
            1u32..=1000,
            prop::sample::select(vec![45.0, 80.0, 90.0])
        )
            .prop_map(|(nx, ny, h, angle)| {
                let x = nx / 2;
                (
                    format!(
                        "# size: {nx}x{ny}\ntype,height,angle,x1,y1,x2,y2\nrandom,1,,,,,\n\
                         wall,{h},{angle},{x},0,{x},{}\n",
                        ny - 1
                    ),
                    false,
                )
            }),
        // A 1-cell strip.
        (1u32..=5_000, 1u32..=65_535).prop_map(|(n, h)| {
            (
                format!("# size: 1x{n}\n# step_height: 0.001\ntype,height\nrandom,{h}\n"),
                false,
            )
        }),
        // Millimetre blocks.
        (1u32..=60, 1u32..=60, 1u32..=1000).prop_map(|(nx, ny, h)| {
            (
                format!(
                    "# size: {nx}x{ny}\n# block_size: 0.001\n# step_height: 0.001\n\
                     type,height\nrandom,{h}\n"
                ),
                false,
            )
        }),
        // A cone, the box cover's worst shape (every level a thin ring),
        // with its box list.
        (10u32..=80, prop::sample::select(vec![20.0, 45.0, 80.0])).prop_map(|(r, angle)| {
            (
                format!(
                    "# size: {0}x{0}\ntype,height,angle,x1,y1\npeak,{r},{angle},{r},{r}\n",
                    2 * r
                ),
                false,
            )
        }),
        // Small worlds the physics smoke test judges.
        (
            1u32..=12,
            1u32..=12,
            prop::sample::select(vec![0.01, 0.02, 0.1, 0.3]),
            1u32..=8
        )
            .prop_map(|(nx, ny, block, h)| {
                (
                    format!("# size: {nx}x{ny}\n# block_size: {block}\ntype,height\nrandom,{h}\n"),
                    true,
                )
            }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 12,
        rng_seed: RngSeed::Fixed(50),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn a_world_of_the_fifth_rounds_shapes_passes_check((text, physics) in fifth_round_scheme()) {
        let Ok(scheme) = Scheme::from_csv(&text, None) else { return Ok(()) };
        let world = WorldConfig {
            // The mesh and the box list (URDF's), every shape.
            targets: Some(Targets::parse("obj,urdf").unwrap()),
            ..WorldConfig::default()
        };
        let batch = BatchConfig { amount: Some(2), world, ..BatchConfig::default() };
        let check = CheckOptions { physics, ..CheckOptions::default() };
        let report = batch_checked(&scheme, batch, &check);
        prop_assert!(
            report.first_fault().is_none(),
            "{}\nfirst fault: {}\nscheme:\n{text}",
            report.verdict(),
            report.first_fault().unwrap_or_default()
        );
    }
}

/// The sixth round's shapes, each checked on a pool of 128 threads (the
/// budget was once the memory divided by them): long strips both ways
/// with every target, flat worlds of fine blocks under the physics smoke
/// test (once priced per cell, 37 times what it took), and fields of
/// random steps.
fn sixth_round_scheme() -> impl Strategy<Value = (String, bool)> {
    prop_oneof![
        // A long strip, along x or y.
        (1_000u32..=20_000, 1u32..=1000, any::<bool>()).prop_map(|(n, h, along_x)| {
            let (nx, ny) = if along_x { (n, 1) } else { (1, n) };
            (
                format!("# size: {nx}x{ny}\n# block_size: 0.05\ntype,height\nrandom,{h}\n"),
                false,
            )
        }),
        // A flat world of fine blocks, on a base or not, physics on.
        (
            20u32..=300,
            20u32..=300,
            prop::sample::select(vec![0.01, 0.02]),
            any::<bool>()
        )
            .prop_map(|(nx, ny, block, base)| {
                let base = if base { "# base: 0.01\n" } else { "" };
                (
                    format!(
                        "# size: {nx}x{ny}\n# block_size: {block}\n{base}type,height\nrandom,0\n"
                    ),
                    true,
                )
            }),
        // Random steps of any height.
        (10u32..=120, 10u32..=120, 1u32..=1000).prop_map(|(nx, ny, h)| {
            (
                format!("# size: {nx}x{ny}\ntype,height\nrandom,{h}\n"),
                false,
            )
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 10,
        rng_seed: RngSeed::Fixed(62),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn a_world_of_the_sixth_rounds_shapes_passes_check_on_many_threads(
        (text, physics) in sixth_round_scheme()
    ) {
        let Ok(scheme) = Scheme::from_csv(&text, None) else { return Ok(()) };
        let targets = if physics { "obj,urdf" } else { "obj,gazebo,webots,mujoco,urdf,usd" };
        let world = WorldConfig {
            targets: Some(Targets::parse(targets).unwrap()),
            ..WorldConfig::default()
        };
        let batch = BatchConfig { amount: Some(3), world, ..BatchConfig::default() };
        let check = CheckOptions { physics, ..CheckOptions::default() };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(128).build().unwrap();
        let report = pool.install(|| batch_checked(&scheme, batch, &check));
        prop_assert!(
            report.first_fault().is_none(),
            "{}\nfirst fault: {}\nscheme:\n{text}",
            report.verdict(),
            report.first_fault().unwrap_or_default()
        );
    }
}
