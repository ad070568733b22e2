//! The random stream of one world, and the samplers drawn from it.
//!
//! World `i` of a batch with base seed `B` uses `ChaCha8` (from `rand_chacha`,
//! which promises a stable stream) keyed with `B` as 8 little-endian bytes
//! followed by 24 zero bytes, on stream (nonce) `i`, from block 0. So world `i`
//! depends on `(B, i)` alone (SPEC §4).
//!
//! The samplers are written here rather than taken from `rand`'s
//! distributions on purpose: `rand` reserves the right to change how a
//! distribution consumes the stream between versions, and every change would
//! silently change every world we generate. These are a few lines each, pinned
//! by the golden hashes, and use only exact IEEE operations and `libm`.

use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};

/// The random stream of world `(seed, index)`.
pub(crate) struct WorldRng(ChaCha8Rng);

impl WorldRng {
    pub(crate) fn new(seed: u64, index: u64) -> Self {
        let mut key = [0u8; 32];
        key[..8].copy_from_slice(&seed.to_le_bytes());
        let mut rng = ChaCha8Rng::from_seed(key);
        rng.set_stream(index);
        WorldRng(rng)
    }

    /// The next 64 random bits.
    #[inline]
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `0..=max`, by Lemire's multiply-and-reject method (unbiased;
    /// one draw almost always).
    #[inline]
    pub(crate) fn up_to(&mut self, max: u32) -> u32 {
        let span = u64::from(max) + 1;
        let mut product = u128::from(self.next_u64()) * u128::from(span);
        if (product as u64) < span {
            let threshold = span.wrapping_neg() % span;
            while (product as u64) < threshold {
                product = u128::from(self.next_u64()) * u128::from(span);
            }
        }
        (product >> 64) as u32
    }

    /// Uniform in `lo..=hi`; `lo ≤ hi`.
    pub(crate) fn int_in(&mut self, lo: u32, hi: u32) -> u32 {
        lo + self.up_to(hi - lo)
    }

    /// Uniform in `[lo, hi)` (`lo` itself when `lo == hi`): 53 random bits.
    pub(crate) fn real_in(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        lo + (hi - lo) * unit
    }
}

/// `round(N(mean, sigma))` clamped to `0..=max`, drawn with one `u64` by
/// inverting the discrete distribution's cumulative table. It has exactly
/// the distribution of drawing a normal, rounding and clamping, at the cost
/// of one draw and a short search per cell.
pub(crate) struct ClampedRoundedNormal {
    /// `thresholds[k]` = P(value ≤ k) scaled to 2⁶⁴, for `k < max`.
    thresholds: Vec<u64>,
}

impl ClampedRoundedNormal {
    pub(crate) fn new(mean: f64, sigma: f64, max: u32) -> Self {
        let thresholds = (0..max)
            .map(|k| {
                // value ≤ k  ⇔  the normal is below k + ½ (ties have probability 0).
                let edge = f64::from(k) + 0.5;
                let cdf = if sigma > 0.0 {
                    0.5 * libm::erfc((mean - edge) / (sigma * std::f64::consts::SQRT_2))
                } else if mean < edge {
                    1.0
                } else {
                    0.0
                };
                // `as` saturates: a probability of 1 maps to u64::MAX.
                (cdf * 18_446_744_073_709_551_616.0) as u64
            })
            .collect();
        ClampedRoundedNormal { thresholds }
    }

    #[inline]
    pub(crate) fn sample(&self, rng: &mut WorldRng) -> u32 {
        let u = rng.next_u64();
        self.thresholds.partition_point(|&t| t <= u) as u32
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are the point of these tests
mod tests {
    use super::*;

    #[test]
    fn same_pair_same_stream_and_other_pairs_differ() {
        let draw = |s, i| {
            let mut r = WorldRng::new(s, i);
            [r.next_u64(), r.next_u64()]
        };
        assert_eq!(draw(7, 3), draw(7, 3));
        assert_ne!(draw(7, 3), draw(7, 4));
        assert_ne!(draw(7, 3), draw(8, 3));
    }

    #[test]
    fn up_to_covers_every_value_and_nothing_more() {
        let mut rng = WorldRng::new(1, 0);
        let mut seen = [0u32; 5];
        for _ in 0..5000 {
            seen[rng.up_to(4) as usize] += 1;
        }
        for count in seen {
            assert!((850..1150).contains(&count), "{seen:?}");
        }
        assert_eq!(rng.up_to(0), 0);
    }

    #[test]
    fn real_in_stays_in_range() {
        let mut rng = WorldRng::new(2, 0);
        for _ in 0..1000 {
            let v = rng.real_in(30.0, 60.0);
            assert!((30.0..60.0).contains(&v));
        }
        assert_eq!(rng.real_in(5.0, 5.0), 5.0);
    }

    #[test]
    fn rounded_normal_matches_its_distribution() {
        // N(2, 1) rounded and clamped to 0..=4: P(2) = P(1.5 < X < 2.5) ≈ 0.383.
        let normal = ClampedRoundedNormal::new(2.0, 1.0, 4);
        let mut rng = WorldRng::new(3, 0);
        let n = 20_000;
        let mut counts = [0u32; 5];
        for _ in 0..n {
            counts[normal.sample(&mut rng) as usize] += 1;
        }
        let p = |k: usize| f64::from(counts[k]) / f64::from(n);
        assert!((p(2) - 0.3829).abs() < 0.015, "{counts:?}");
        assert!((p(0) - 0.0668).abs() < 0.01, "{counts:?}");
        assert!((p(4) - 0.0668).abs() < 0.01, "{counts:?}");
    }

    #[test]
    fn rounded_normal_with_zero_sigma_rounds_half_up() {
        let mut rng = WorldRng::new(4, 0);
        assert_eq!(ClampedRoundedNormal::new(1.5, 0.0, 3).sample(&mut rng), 2);
        assert_eq!(ClampedRoundedNormal::new(2.0, 0.0, 4).sample(&mut rng), 2);
        assert_eq!(ClampedRoundedNormal::new(0.0, 0.0, 0).sample(&mut rng), 0);
    }
}
