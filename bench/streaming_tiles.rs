//! The experiment behind docs/envs.md's "Speed and memory": writing 64
//! terrains of 80×80 cells at k = 2 into a pool of 4096, as slots
//! (contiguous) and as tiles (160 rows of 640 bytes, 40 KiB apart in a map
//! 64 tiles wide), with ordinary stores (what rse does) and with
//! non-temporal stores, which skip reading each cache line before writing
//! it. On one core, x86-64 only. It is not part of the workspace: the
//! streaming stores need `unsafe`, which rse's crates forbid; this measures
//! what allowing them would buy.
//!
//! rustc -O bench/streaming_tiles.rs -o target/streaming_tiles && target/streaming_tiles

use std::arch::x86_64::{_mm_loadu_ps, _mm_sfence, _mm_stream_ps};
use std::hint::black_box;
use std::time::Instant;

const ENVS: usize = 4096;
const CELLS: usize = 80;
const SAMPLES: usize = 2 * CELLS; // k = 2
const TILES_ACROSS: usize = 64;
const MAP_ROW: usize = TILES_ACROSS * SAMPLES;

/// One terrain's samples into `out` (rows `stride` apart from `x0`): each
/// cell row spread to a sample row, then copied to the next, as rse does.
fn write_ordinary(cells: &[u16], value: &[f32], out: &mut [f32], x0: usize, stride: usize) {
    for y in 0..CELLS {
        let start = 2 * y * stride + x0;
        let (pairs, _) = out[start..start + SAMPLES].as_chunks_mut::<2>();
        for (pair, &h) in pairs.iter_mut().zip(&cells[y * CELLS..(y + 1) * CELLS]) {
            *pair = [value[usize::from(h)]; 2];
        }
        out.copy_within(start..start + SAMPLES, start + stride);
    }
}

/// The same, each sample row built in a buffer and streamed out.
fn write_streaming(cells: &[u16], value: &[f32], out: &mut [f32], x0: usize, stride: usize) {
    let mut row = [0f32; SAMPLES];
    for y in 0..CELLS {
        let (pairs, _) = row.as_chunks_mut::<2>();
        for (pair, &h) in pairs.iter_mut().zip(&cells[y * CELLS..(y + 1) * CELLS]) {
            *pair = [value[usize::from(h)]; 2];
        }
        for j in 0..2 {
            let start = (2 * y + j) * stride + x0;
            let to = out[start..start + SAMPLES].as_mut_ptr();
            assert!(
                (to as usize).is_multiple_of(16),
                "streaming stores need 16-byte alignment"
            );
            for i in (0..SAMPLES).step_by(4) {
                // SAFETY: `to + i .. to + i + 4` lies inside the row just
                // borrowed, 16-byte aligned (checked above); `row` has the
                // same length.
                unsafe { _mm_stream_ps(to.add(i), _mm_loadu_ps(row.as_ptr().add(i))) };
            }
        }
    }
    // SAFETY: a fence has no memory-safety precondition; it orders the
    // streaming stores before anything that reads `out`.
    unsafe { _mm_sfence() };
}

fn main() {
    let mut pool = vec![0.5f32; ENVS * SAMPLES * SAMPLES];
    let mut state = 12345u32;
    let terrains: Vec<Vec<u16>> = (0..64)
        .map(|_| {
            (0..CELLS * CELLS)
                .map(|_| {
                    state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                    ((state >> 24) % 9) as u16
                })
                .collect()
        })
        .collect();
    let value: Vec<f32> = (0..9).map(|h| h as f32 / 9.0).collect();
    type Write = fn(&[u16], &[f32], &mut [f32], usize, usize);
    for (layout, stores, write) in [
        ("tiles", "ordinary", write_ordinary as Write),
        ("tiles", "streaming", write_streaming as Write),
        ("slots", "ordinary", write_ordinary as Write),
        ("slots", "streaming", write_streaming as Write),
    ] {
        let mut times = Vec::new();
        for round in 0..300 {
            let start = Instant::now();
            for (i, cells) in terrains.iter().enumerate() {
                let e = (round + i * 61) % ENVS;
                if layout == "tiles" {
                    let band = SAMPLES * MAP_ROW;
                    let (row, col) = (e / TILES_ACROSS, e % TILES_ACROSS);
                    let out = &mut pool[row * band..(row + 1) * band];
                    write(cells, &value, out, col * SAMPLES, MAP_ROW);
                } else {
                    let slot = SAMPLES * SAMPLES;
                    write(
                        cells,
                        &value,
                        &mut pool[e * slot..(e + 1) * slot],
                        0,
                        SAMPLES,
                    );
                }
            }
            times.push(start.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        println!(
            "write 64 {layout} with {stores} stores: median {:.0} µs",
            times[times.len() / 2] * 1e6
        );
    }
    black_box(&pool);
}
