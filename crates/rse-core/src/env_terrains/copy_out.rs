//! Slots' fields copied out of the pool's buffer into a flat array at
//! given starts, every slot on its own thread: what an adapter writes
//! into a simulator's height fields at a reset (a host model's
//! `hfield_data`, the pinned buffer a GPU upload reads), exact or coarse
//! (one sample a cell, for the robot's large geoms).

use rayon::prelude::*;

use super::options::bad;
use super::{EnvError, EnvLayout, EnvTerrains};

/// Samples written from which [`EnvTerrains::copy_fields`] spreads its
/// fields over threads: below it, waking rayon's threads cost more than
/// the copies. Measured on a 2-core machine, mjlab's reset of stepfield
/// envs (exact fields of 25,600 samples, coarse of 6,400): 4 envs took
/// 0.62 ms on threads and 0.27 ms on one; 82 envs 2.4 ms with this
/// threshold (the coarse fields on threads too), 3.7 ms with 2^20, 5.4
/// ms as numpy copies.
const PARALLEL_FROM: usize = 1 << 18;

/// Which samples of a slot [`EnvTerrains::copy_fields`] writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldSamples {
    /// The slot's field as the pool holds it: `nrow × ncol`.
    Exact,
    /// One sample a cell, at its centre: the mean of the cell's first and
    /// last samples, `(nrow / k) × (ncol / k)` for oversample `k`. A
    /// cell's `k × k` samples are its height (the mean is that, exactly)
    /// or a ramp's plane over it (the mean is the plane at the centre).
    Coarse,
}

impl EnvTerrains {
    /// Samples in one slot's field of `kind`.
    pub fn field_len(&self, kind: FieldSamples) -> usize {
        let (rows, cols) = self.env_shape;
        let k = self.options.oversample as usize;
        match kind {
            FieldSamples::Exact => rows * cols,
            FieldSamples::Coarse => (rows / k) * (cols / k),
        }
    }

    /// Copies the field of slot `slots[i]` (of `kind`) out of `buffer`
    /// (the pool's samples, as [`EnvTerrains::write`] filled them) into
    /// `out` from `starts[i]`, for each `i`, the slots spread over threads
    /// when there are many samples (`PARALLEL_FROM`). The places must
    /// not overlap. Slots only (a tile is part of one map).
    pub fn copy_fields(
        &self,
        buffer: &[f32],
        slots: &[usize],
        starts: &[usize],
        kind: FieldSamples,
        out: &mut [f32],
    ) -> Result<(), EnvError> {
        if !matches!(self.options.layout, EnvLayout::Slots) {
            return Err(bad("layout", "fields are copied out of slots, not tiles"));
        }
        let slot = self.slot_len();
        if buffer.len() != self.num_envs() * slot {
            return Err(bad(
                "samples",
                format!(
                    "{} samples, the pool has {}",
                    buffer.len(),
                    self.num_envs() * slot
                ),
            ));
        }
        if slots.len() != starts.len() {
            return Err(bad(
                "starts",
                format!("{} starts for {} env_ids", starts.len(), slots.len()),
            ));
        }
        if let Some(&e) = slots.iter().find(|&&e| e >= self.num_envs()) {
            return Err(bad(
                "env_ids",
                format!("{e} is not an environment (0 to {})", self.num_envs() - 1),
            ));
        }
        let len = self.field_len(kind);
        let places = split_places(out, starts, len)?;
        let (cols, k) = (self.env_shape.1, self.options.oversample as usize);
        let copy = |(i, place): (usize, &mut [f32])| {
            let field = &buffer[slots[i] * slot..(slots[i] + 1) * slot];
            match kind {
                FieldSamples::Exact => place.copy_from_slice(field),
                FieldSamples::Coarse => coarse_into(field, cols, k, place),
            }
        };
        if places.len() * len >= PARALLEL_FROM {
            places.into_par_iter().for_each(copy);
        } else {
            places.into_iter().for_each(copy);
        }
        Ok(())
    }
}

/// `out`'s places of `len` samples from each of `starts`, borrowed apart
/// (each with its index in `starts`) so threads can fill them, or an
/// error naming `starts` (two overlap) or `data` (one runs past it).
fn split_places<'a>(
    out: &'a mut [f32],
    starts: &[usize],
    len: usize,
) -> Result<Vec<(usize, &'a mut [f32])>, EnvError> {
    let mut order: Vec<usize> = (0..starts.len()).collect();
    order.sort_by_key(|&i| starts[i]);
    let total = out.len();
    let (mut rest, mut at) = (out, 0usize);
    let mut places = Vec::with_capacity(starts.len());
    for i in order {
        let start = starts[i];
        if start < at {
            return Err(bad(
                "starts",
                format!("the field at {start} overlaps the one before it (to {at})"),
            ));
        }
        let end = start.saturating_add(len);
        if end > total {
            return Err(bad(
                "data",
                format!("{total} samples, a field at {start} needs {end}"),
            ));
        }
        let (_, tail) = std::mem::take(&mut rest).split_at_mut(start - at);
        let (place, tail) = tail.split_at_mut(len);
        places.push((i, place));
        (rest, at) = (tail, end);
    }
    Ok(places)
}

/// A slot's coarse samples ([`FieldSamples::Coarse`]) from its `field`
/// (rows of `cols` samples, `k × k` a cell) into `out`.
fn coarse_into(field: &[f32], cols: usize, k: usize, out: &mut [f32]) {
    let nx = cols / k;
    for (cy, row) in out.chunks_mut(nx).enumerate() {
        let first = &field[cy * k * cols..];
        let last = &field[(cy * k + k - 1) * cols..];
        for (cx, sample) in row.iter_mut().enumerate() {
            *sample = (first[cx * k] + last[cx * k + k - 1]) * 0.5;
        }
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // copies compared exactly: the same bits either way
mod tests {
    use super::*;
    use crate::difficulty::Difficulty;
    use crate::env_terrains::{EnvOptions, EnvRequest};
    use crate::scheme::Scheme;

    fn envs(n: usize, oversample: u32) -> (EnvTerrains, Vec<f32>) {
        let scheme = Scheme::from_csv(
            "# size: 6x5\ntype,height,x1,y1,x2,y2\nrandom,0..3,,,,\nramp,2..4,1,1,4,3\n",
            None,
        )
        .unwrap();
        let options = EnvOptions {
            oversample,
            ..EnvRequest {
                num_envs: n,
                ..EnvRequest::default()
            }
            .resolve(&scheme)
            .unwrap()
        };
        let mut envs = EnvTerrains::new(scheme, options).unwrap();
        let ids: Vec<usize> = (0..n).collect();
        envs.reset(&ids, &vec![Difficulty::new(1.0).unwrap(); n])
            .unwrap();
        let (a, b, c) = envs.buffer_shape();
        let mut buffer = vec![0.0; a * b * c];
        envs.write(&ids, &mut buffer).unwrap();
        (envs, buffer)
    }

    #[test]
    fn each_field_goes_to_its_start_and_nothing_else_is_written() {
        let (envs, buffer) = envs(4, 2);
        let len = envs.field_len(FieldSamples::Exact);
        let mut out = vec![-1.0; 5 * len];
        envs.copy_fields(
            &buffer,
            &[3, 1],
            &[2 * len + 1, 1],
            FieldSamples::Exact,
            &mut out,
        )
        .unwrap();
        assert_eq!(out[0], -1.0);
        assert_eq!(&out[1..=len], &buffer[len..2 * len]);
        assert!(out[len + 1..=2 * len].iter().all(|&v| v == -1.0));
        assert_eq!(&out[2 * len + 1..=3 * len], &buffer[3 * len..4 * len]);
        assert!(out[3 * len + 1..].iter().all(|&v| v == -1.0));
    }

    #[test]
    fn a_coarse_sample_is_the_mean_of_its_cells_first_and_last() {
        let (envs, buffer) = envs(2, 3);
        let (rows, cols) = envs.field_shape();
        let len = envs.field_len(FieldSamples::Coarse);
        assert_eq!(len, (rows / 3) * (cols / 3));
        let mut out = vec![0.0; len];
        envs.copy_fields(&buffer, &[1], &[0], FieldSamples::Coarse, &mut out)
            .unwrap();
        let field = &buffer[rows * cols..];
        let nx = cols / 3;
        for (i, &v) in out.iter().enumerate() {
            let (cy, cx) = (i / nx, i % nx);
            let expected =
                (field[3 * cy * cols + 3 * cx] + field[(3 * cy + 2) * cols + 3 * cx + 2]) * 0.5;
            assert_eq!(v, expected, "cell ({cx}, {cy})");
        }
        // Over the ramp a cell's samples lie on its plane: its coarse
        // sample is neither its first nor its last.
        let on_a_plane = (0..len).any(|i| {
            let (cy, cx) = (i / nx, i % nx);
            out[i] != field[3 * cy * cols + 3 * cx]
        });
        assert!(on_a_plane, "the scheme's ramp is in the field");
    }

    #[test]
    fn overlapping_places_a_place_past_the_data_and_a_stray_env_are_refused() {
        let (envs, buffer) = envs(3, 2);
        let len = envs.field_len(FieldSamples::Exact);
        let mut out = vec![0.0; 2 * len];
        let said = |slots: &[usize], starts: &[usize], out: &mut [f32]| {
            envs.copy_fields(&buffer, slots, starts, FieldSamples::Exact, out)
                .unwrap_err()
                .to_string()
        };
        assert!(said(&[0, 1], &[0, len - 1], &mut out).starts_with("starts: the field at"));
        assert!(said(&[0], &[len + 1], &mut out).starts_with("data: "));
        assert!(said(&[3], &[0], &mut out).starts_with("env_ids: 3 is not an environment"));
        assert!(said(&[0, 1], &[0], &mut out).starts_with("starts: 1 starts for 2 env_ids"));
        assert!(
            out.iter().all(|&v| v == 0.0),
            "nothing written when refused"
        );
    }
}
