//! What rse-core's table-printing benches share: a median of repeated
//! runs.

use std::time::{Duration, Instant};

/// The median time of `run`: at least `min_runs` runs, then more while
/// `budget` lasts, up to `max_runs`.
pub fn median_time(
    mut run: impl FnMut(),
    budget: Duration,
    min_runs: usize,
    max_runs: usize,
) -> Duration {
    let mut times = Vec::new();
    let start = Instant::now();
    while times.len() < min_runs || (start.elapsed() < budget && times.len() < max_runs) {
        let t = Instant::now();
        run();
        times.push(t.elapsed());
    }
    times.sort();
    times[times.len() / 2]
}
