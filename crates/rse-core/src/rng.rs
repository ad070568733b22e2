//! The random stream of one world, and the samplers drawn from it.
//!
//! World `i` of a batch with base seed `B` uses `ChaCha8` (from `rand_chacha`,
//! which promises a stable stream) keyed with `B` as 8 little-endian bytes
//! followed by 24 zero bytes, on stream (nonce) `i`, from block 0. So world `i`
//! depends on `(B, i)` alone (docs/schemes.md).
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

    /// The next 32 random bits (one `ChaCha` word; per-cell values need no more).
    #[inline]
    pub(crate) fn next_u32(&mut self) -> u32 {
        self.0.next_u32()
    }

    /// Uniform in `0..=max` from 32-bit draws, by Lemire's multiply-and-reject
    /// method (unbiased; one draw almost always).
    #[inline]
    pub(crate) fn up_to(&mut self, max: u32) -> u32 {
        const WORD: u64 = 1 << 32;
        let span = u64::from(max) + 1;
        let mut product = u64::from(self.next_u32()) * span;
        if product % WORD < span {
            let threshold = (WORD - span) % span;
            while product % WORD < threshold {
                product = u64::from(self.next_u32()) * span;
            }
        }
        (product >> 32) as u32
    }

    /// Fills `out` with the next `out.len()` 32-bit words of the stream, as
    /// that many `next_u32` calls would, but in bulk (twice as fast).
    pub(crate) fn fill_words(&mut self, out: &mut [u32]) {
        let mut bytes = [0u8; 4 * 1024];
        for chunk in out.chunks_mut(1024) {
            let bytes = &mut bytes[..4 * chunk.len()];
            self.0.fill_bytes(bytes);
            for (word, le) in chunk.iter_mut().zip(bytes.chunks_exact(4)) {
                *word = u32::from_le_bytes([le[0], le[1], le[2], le[3]]);
            }
        }
    }

    /// Fills `out` with `up_to(max)` values, drawing from the stream exactly
    /// as successive `up_to` calls would, in bulk. A rejection is rare
    /// (`threshold / 2³²` per draw, about 1 in 10⁹ for the heights of a
    /// scheme), so the batch is checked and mapped in bulk; only when a
    /// draw is rejected is it redrawn from its first word the careful way.
    pub(crate) fn fill_up_to(&mut self, max: u32, out: &mut [u32]) {
        const WORD: u64 = 1 << 32;
        let span = u64::from(max) + 1;
        let threshold = (WORD - span) % span;
        let start = self.0.get_word_pos();
        self.fill_words(out);
        let Ok(span) = u32::try_from(span) else {
            return; // max = u32::MAX: every word is its own value, none rejected
        };
        // One pass the compiler vectorizes (32×32-bit products): the values,
        // and the lowest low word, which a rejected draw has below the
        // threshold.
        let mut lowest = u32::MAX;
        for w in out.iter_mut() {
            let product = u64::from(*w) * u64::from(span);
            lowest = lowest.min(product as u32);
            *w = (product >> 32) as u32;
        }
        if u64::from(lowest) < threshold {
            self.0.set_word_pos(start);
            self.fill_up_to_rejecting(max, out);
        }
    }

    /// [`fill_up_to`](Self::fill_up_to) where a rejection happens: in bulk
    /// up to the rejected word, then rewinding to it and going on one draw
    /// at a time past it.
    fn fill_up_to_rejecting(&mut self, max: u32, out: &mut [u32]) {
        const WORD: u64 = 1 << 32;
        let span = u64::from(max) + 1;
        let threshold = (WORD - span) % span;
        let mut done = 0;
        while done < out.len() {
            let rest = &mut out[done..];
            let start = self.0.get_word_pos();
            self.fill_words(rest);
            let mut rejected = None;
            for (i, value) in rest.iter_mut().enumerate() {
                let product = u64::from(*value) * span;
                if product % WORD < threshold {
                    rejected = Some(i);
                    break;
                }
                *value = (product >> 32) as u32;
            }
            let Some(i) = rejected else { return };
            self.0.set_word_pos(start + i as u128);
            rest[i] = self.up_to(max);
            done += i + 1;
        }
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

/// `round(N(mean, sigma))` clamped to `0..=max`, drawn with one `u32` by
/// inverting the discrete distribution's cumulative table. It has exactly
/// the distribution of drawing a normal, rounding and clamping, at the cost
/// of one draw and a short search per cell.
pub(crate) struct ClampedRoundedNormal {
    /// `thresholds[k]` = P(value ≤ k) scaled to 2³², for `k < max`. Held in
    /// `u64` so that a probability of 1 (2³²) is above every 32-bit draw.
    thresholds: Vec<u64>,
    /// The value for each top byte of the word, or `MIXED` where a
    /// threshold falls inside that byte's range and the full search decides.
    by_top_byte: [u32; 256],
    /// Thresholds of 0, below every draw.
    always: u32,
    /// The thresholds strictly between 0 and 2³², as words.
    live: Vec<u32>,
}

const MIXED: u32 = u32::MAX;

/// Beyond this argument `erfc` scaled to 2³² is exactly 0 (erfc(8) ≈ 1e-29)
/// and below its negative exactly 2³² (2 − 1e-29 is 2 in `f64`): there a
/// threshold needs no `erfc`.
const ERFC_FLAT: f64 = 8.0;

/// Cell visits one `erfc` of a gaussian's table costs (~35 ns measured by
/// bench/budget.py, a visit being ~5 ns): with a visit for every entry of
/// the table, what [`ClampedRoundedNormal::new`] costs, for `check`'s and
/// the editor's budgets.
pub(crate) const ERFC_VISITS: u64 = 7;

/// How many gaussian tables one generation keeps to share ([`GaussianTables`]).
pub(crate) const KEPT_TABLES: usize = 8;

/// The key of a gaussian's table: its height (which sets the mean) and the
/// bits of its spread.
pub(crate) type TableKey = (u32, u64);

/// The gaussian tables of one world's generation: rows of the same height
/// and spread share one (4000 alike built 4000). The [`KEPT_TABLES`] used
/// last are kept, so a world of many different rows holds a few megabytes
/// at most.
#[derive(Default)]
pub(crate) struct GaussianTables {
    kept: Vec<(TableKey, std::rc::Rc<ClampedRoundedNormal>)>,
}

impl GaussianTables {
    /// The table of a gaussian of height `max` and spread `sigma`.
    pub(crate) fn get(&mut self, max: u32, sigma: f64) -> std::rc::Rc<ClampedRoundedNormal> {
        let key = (max, sigma.to_bits());
        if let Some(i) = self.kept.iter().position(|(k, _)| *k == key) {
            let entry = self.kept.remove(i);
            self.kept.push(entry);
        } else {
            if self.kept.len() == KEPT_TABLES {
                self.kept.remove(0);
            }
            let table = ClampedRoundedNormal::new(f64::from(max) / 2.0, sigma, max);
            self.kept.push((key, std::rc::Rc::new(table)));
        }
        std::rc::Rc::clone(&self.kept.last().expect("just kept").1)
    }
}

/// The cell visits of the tables a generation builds for gaussian rows of
/// `keys` in table order (`(key, height, spread)`; no key: the row draws its
/// height or spread, and builds its own), through [`GaussianTables`]'s
/// reuse exactly: what `check` and the editor price.
pub(crate) fn tables_visits(rows: impl Iterator<Item = (Option<TableKey>, u32, f64)>) -> u64 {
    let mut kept: Vec<TableKey> = Vec::new();
    let mut visits = 0u64;
    for (key, max, sigma) in rows {
        if let Some(key) = key {
            if let Some(i) = kept.iter().position(|k| *k == key) {
                let k = kept.remove(i);
                kept.push(k);
                continue;
            }
            if kept.len() == KEPT_TABLES {
                kept.remove(0);
            }
            kept.push(key);
        }
        visits = visits.saturating_add(table_visits(max, sigma));
    }
    visits
}

/// The cell visits the table of a gaussian of height `max` and spread
/// `sigma` costs to build: one per entry, and [`ERFC_VISITS`] for each
/// entry within `ERFC_FLAT` spreads of the mean (those that call `erfc`).
pub(crate) fn table_visits(max: u32, sigma: f64) -> u64 {
    let window = (2.0 * ERFC_FLAT * std::f64::consts::SQRT_2 * sigma.max(0.0)).ceil() + 2.0;
    let erfcs = window.min(f64::from(max)) as u64;
    u64::from(max).saturating_add(erfcs.saturating_mul(ERFC_VISITS))
}

/// Most thresholds for which [`ClampedRoundedNormal::fill_values`] counts
/// them word by word rather than looking each word up.
const COUNTED: usize = 16;

impl ClampedRoundedNormal {
    pub(crate) fn new(mean: f64, sigma: f64, max: u32) -> Self {
        let thresholds: Vec<u64> = (0..max)
            .map(|k| {
                // value ≤ k  ⇔  the normal is below k + ½ (ties have probability 0).
                let edge = f64::from(k) + 0.5;
                let cdf = if sigma > 0.0 {
                    let x = (mean - edge) / (sigma * std::f64::consts::SQRT_2);
                    // Past ±ERFC_FLAT the threshold is 0 or 2³² exactly,
                    // as erfc itself would give: only the edges near the
                    // mean cost an erfc (65,535 of them took 1.4 ms a row).
                    if x > ERFC_FLAT {
                        0.0
                    } else if x < -ERFC_FLAT {
                        1.0
                    } else {
                        0.5 * libm::erfc(x)
                    }
                } else if mean < edge {
                    1.0
                } else {
                    0.0
                };
                (cdf * 4_294_967_296.0) as u64
            })
            .collect();
        // The value of a word is how many thresholds are at or below it
        // (the search `value_of` does); the bytes are walked in order with
        // the thresholds, both sorted: a byte is mixed when a threshold
        // falls after its first word and not after its last.
        let mut below = 0;
        let by_top_byte = std::array::from_fn(|byte| {
            let first = (byte as u64) << 24;
            let last = first + (1 << 24) - 1;
            while thresholds.get(below).is_some_and(|&t| t <= first) {
                below += 1;
            }
            if thresholds.get(below).is_some_and(|&t| t <= last) {
                MIXED
            } else {
                below as u32
            }
        });
        let always = thresholds.iter().filter(|&&t| t == 0).count() as u32;
        let live = thresholds
            .iter()
            .filter_map(|&t| u32::try_from(t).ok().filter(|&t| t > 0))
            .collect();
        ClampedRoundedNormal {
            thresholds,
            by_top_byte,
            always,
            live,
        }
    }

    /// [`value_of`](Self::value_of) of each of `words`, into `values`. With
    /// few thresholds strictly inside the word range (a gaussian's sigma
    /// of a step or so leaves a dozen at most), a word's value is counted as
    /// how many of them it reaches, one vectorized pass per threshold; with
    /// more, each word is looked up.
    pub(crate) fn fill_values(&self, words: &[u32], values: &mut [u32]) {
        match self.live.len() {
            0..=4 => self.count::<4>(words, values),
            5..=8 => self.count::<8>(words, values),
            9..=COUNTED => self.count::<COUNTED>(words, values),
            _ => {
                for (v, &w) in values.iter_mut().zip(words) {
                    *v = self.value_of(w);
                }
            }
        }
    }

    /// The values of `words` counted against the live thresholds padded
    /// to `N` with zeros (reached by every word, so taken off again): a
    /// fixed number of comparisons per word, which the compiler unrolls
    /// and vectorizes. `N ≥ live.len()`.
    fn count<const N: usize>(&self, words: &[u32], values: &mut [u32]) {
        let mut live = [0u32; N];
        live[..self.live.len()].copy_from_slice(&self.live);
        let base = self.always.wrapping_sub((N - self.live.len()) as u32);
        for (v, &w) in values.iter_mut().zip(words) {
            let reached: u32 = live.iter().map(|&t| u32::from(w >= t)).sum();
            *v = base.wrapping_add(reached);
        }
    }

    /// The value for one 32-bit random word.
    #[inline]
    pub(crate) fn value_of(&self, word: u32) -> u32 {
        match self.by_top_byte[(word >> 24) as usize] {
            MIXED => self.thresholds.partition_point(|&t| t <= u64::from(word)) as u32,
            value => value,
        }
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
    fn bulk_words_are_the_stream_in_order() {
        let mut one = WorldRng::new(5, 2);
        let mut bulk = WorldRng::new(5, 2);
        // Start mid-block so that bulk filling must honour the position.
        assert_eq!(one.next_u32(), bulk.next_u32());
        let mut words = vec![0; 3000];
        bulk.fill_words(&mut words);
        let expected: Vec<u32> = (0..3000).map(|_| one.next_u32()).collect();
        assert_eq!(words, expected);
        assert_eq!(one.next_u64(), bulk.next_u64());
    }

    #[test]
    fn bulk_up_to_draws_as_one_at_a_time_even_with_rejections() {
        // A span of 2³¹ + 1 rejects about half of all draws.
        for max in [0, 2, 4, 1 << 31, u32::MAX - 5] {
            let mut one = WorldRng::new(6, 1);
            let mut bulk = WorldRng::new(6, 1);
            let mut values = vec![0; 2500];
            bulk.fill_up_to(max, &mut values);
            let expected: Vec<u32> = (0..2500).map(|_| one.up_to(max)).collect();
            assert_eq!(values, expected, "max {max}");
            assert_eq!(
                one.next_u32(),
                bulk.next_u32(),
                "max {max}: same position after"
            );
        }
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

    /// The byte table, and the bulk values, give what the full search
    /// gives, at each byte's edges and around every threshold.
    #[test]
    fn rounded_normal_table_agrees_with_the_search() {
        let mut paths = Vec::new();
        for (mean, sigma, max) in [
            (1.5, 0.5, 3),
            (2.0, 1.0, 4),
            (0.5, 0.01, 1),
            (9.0, 3.0, 18),
            (1.0, 0.0, 2),
            // 5 to 8, then 9 to 16 thresholds inside the word range: counted.
            (3.0, 1.0, 7),
            (5.0, 1.5, 12),
            // More thresholds inside the word range than are counted: looked up.
            (40.0, 8.0, 80),
        ] {
            let normal = ClampedRoundedNormal::new(mean, sigma, max);
            paths.push(normal.live.len());
            let search = |w: u32| normal.thresholds.partition_point(|&t| t <= u64::from(w)) as u32;
            let edges = (0..=255u32).flat_map(|b| [b << 24, (b << 24) | 0x00ff_ffff]);
            let near = normal.thresholds.iter().flat_map(|&t| {
                [t.saturating_sub(1), t, t + 1].map(|w| w.min(u64::from(u32::MAX)) as u32)
            });
            let words: Vec<u32> = edges.chain(near).collect();
            let mut values = vec![0; words.len()];
            normal.fill_values(&words, &mut values);
            for (&w, &v) in words.iter().zip(&values) {
                let case = format!("N({mean}, {sigma}) to {max}, word {w:#x}");
                assert_eq!(normal.value_of(w), search(w), "{case}");
                assert_eq!(v, search(w), "{case}: in bulk");
            }
        }
        // Every way of filling values was taken: 4, 8 and 16 counted, looked up.
        for band in [0..=4, 5..=8, 9..=COUNTED, COUNTED + 1..=usize::MAX] {
            assert!(
                paths.iter().any(|n| band.contains(n)),
                "{band:?}: {paths:?}"
            );
        }
    }

    #[test]
    fn rounded_normal_matches_its_distribution() {
        // N(2, 1) rounded and clamped to 0..=4: P(2) = P(1.5 < X < 2.5) ≈ 0.383.
        let normal = ClampedRoundedNormal::new(2.0, 1.0, 4);
        let mut rng = WorldRng::new(3, 0);
        let n = 20_000;
        let mut counts = [0u32; 5];
        for _ in 0..n {
            counts[normal.value_of(rng.next_u32()) as usize] += 1;
        }
        let p = |k: usize| f64::from(counts[k]) / f64::from(n);
        assert!((p(2) - 0.3829).abs() < 0.015, "{counts:?}");
        assert!((p(0) - 0.0668).abs() < 0.01, "{counts:?}");
        assert!((p(4) - 0.0668).abs() < 0.01, "{counts:?}");
    }

    #[test]
    fn rounded_normal_with_zero_sigma_rounds_half_up() {
        for word in [0, 1 << 31, u32::MAX] {
            assert_eq!(ClampedRoundedNormal::new(1.5, 0.0, 3).value_of(word), 2);
            assert_eq!(ClampedRoundedNormal::new(2.0, 0.0, 4).value_of(word), 2);
            assert_eq!(ClampedRoundedNormal::new(0.0, 0.0, 0).value_of(word), 0);
        }
    }
}
