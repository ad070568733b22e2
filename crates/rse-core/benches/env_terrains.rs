//! Per-environment terrains in Rust, without Python: 4096
//! environments of `six_obstacles.csv` at 80×80 cells, k = 2; a reset of 64
//! (new terrains written into their slots or tiles by `reset_into`, origins
//! read), and its parts: the generation of one terrain, the write of 64
//! into a pool that is not in cache.
//! bench/envs.py measures the same through the Python package.
//!
//! `cargo bench -p rse-core --bench env_terrains`

use criterion::{Criterion, criterion_group, criterion_main};
use rse_core::{Difficulty, EnvLayout, EnvOptions, EnvRequest, EnvTerrains, Scheme, generate_at};
use std::hint::black_box;

const NUM_ENVS: usize = 4096;

fn scheme_80() -> Scheme {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../schemes/six_obstacles.csv"
    );
    let text = std::fs::read_to_string(path).expect("the sample scheme reads");
    let text = text.replace("# size: 50x50", "# size: 80x80");
    Scheme::from_csv(&text, None).expect("the sample scheme at 80x80 is valid")
}

fn bench(c: &mut Criterion) {
    let scheme = scheme_80();
    let mut group = c.benchmark_group("env_terrains_80x80");
    let mut index = 0u64;
    group.bench_function("generate_one", |b| {
        b.iter(|| {
            index += 1;
            black_box(generate_at(&scheme, 0, index, Difficulty::FULL))
        });
    });
    for (name, layout) in [
        ("reset_64_slots", EnvLayout::Slots),
        (
            "reset_64_tiles",
            EnvLayout::Tiles {
                cols: 64,
                border: 0,
            },
        ),
    ] {
        let options = EnvOptions {
            layout,
            ..EnvRequest {
                num_envs: NUM_ENVS,
                ..EnvRequest::default()
            }
            .resolve(&scheme)
            .expect("valid options")
        };
        let mut envs = EnvTerrains::new(scheme.clone(), options).expect("valid options");
        let (n, rows, cols) = envs.buffer_shape();
        // Touched, as the Python package's buffer is (filled on construction).
        let mut out = vec![envs.ground_sample(); n * rows * cols];
        let mut next = 0usize;
        group.bench_function(name, |b| {
            b.iter(|| {
                // 64 envs spread over the pool, as a step's resets are.
                let ids: Vec<usize> = (0..64).map(|i| (next + i * 61) % NUM_ENVS).collect();
                next += 1;
                envs.reset(&ids, &[Difficulty::FULL; 64])
                    .expect("valid ids");
                envs.write(&ids, &mut out).expect("the whole buffer");
                black_box(ids.iter().map(|&e| envs.origin(e)[2]).sum::<f64>())
            });
        });
        // Where a reset's time goes beyond generation: the write of 64
        // terrains into a pool that is not in cache.
        group.bench_function(name.replace("reset", "write"), |b| {
            b.iter(|| {
                let ids: Vec<usize> = (0..64).map(|i| (next + i * 61) % NUM_ENVS).collect();
                next += 1;
                envs.write(&ids, &mut out).expect("the whole buffer");
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
