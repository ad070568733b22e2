//! Generation speed: a 50×50 scheme with one obstacle of each type (target
//! < 50 µs per world, aim 20 µs) and a 1000×1000 one (target < 40 ms), one core.
//!
//! `cargo bench -p rse-core --bench generate`

use criterion::{Criterion, criterion_group, criterion_main};
use rse_core::{Scheme, generate};
use std::hint::black_box;

const SIX_OBSTACLES_1000: &str = "# size: 1000x1000
type,height,angle,x1,y1,x2,y2
random,2,,,,,
gaussian,3,,,,,
peak,6,40,200..800,200..800,,
wall,5,35,100,100..900,900,100..900
pit,2,60,200..800,200..800,,
long_pit,2,90,500,0,500,999
";

fn bench(c: &mut Criterion) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../schemes/six_obstacles.csv"
    );
    let small = Scheme::load(path).expect("the sample scheme loads");
    let large = Scheme::from_csv(SIX_OBSTACLES_1000, None).expect("the bench scheme is valid");

    let mut group = c.benchmark_group("generate");
    let mut index = 0u64;
    group.bench_function("six_obstacles_50x50", |b| {
        b.iter(|| {
            index += 1;
            black_box(generate(&small, 0, index))
        });
    });
    group.sample_size(20);
    group.bench_function("six_obstacles_1000x1000", |b| {
        b.iter(|| {
            index += 1;
            black_box(generate(&large, 0, index))
        });
    });
    group.finish();

    // Where the time of the 50×50 world goes: each of its rows alone.
    let mut group = c.benchmark_group("one_obstacle_50x50");
    let text = std::fs::read_to_string(path).expect("the sample scheme reads");
    let (head, rows) = text.split_once("type,").expect("a header row");
    let (header, rows) = rows.split_once('\n').expect("rows");
    for row in rows.lines() {
        let one = format!("{head}type,{header}\n{row}\n");
        let scheme = Scheme::from_csv(&one, None).expect("each row is valid alone");
        let name = row.split(',').next().unwrap_or("row");
        group.bench_function(name, |b| {
            b.iter(|| {
                index += 1;
                black_box(generate(&scheme, 0, index))
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
