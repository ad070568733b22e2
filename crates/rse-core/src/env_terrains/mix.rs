//! A mix of schemes by proportion, as mjlab and Isaac Lab mix sub-terrains:
//! which scheme each environment draws, from the seed and its global id
//! alone, so every process of a run and every tool (`rse-gen
//! contact-sheet`, the framework adapters) agrees on it.

use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};

use super::options::{EnvError, bad};
use crate::globals::Grid;
use crate::scheme::Scheme;
use crate::shared_globals::{Together, unshared};

/// Bytes 8‥16 of the `ChaCha8` key of the mix's draws ("rse mix\0"): the
/// worlds' keys have zeros there, so a mix draw never shares a stream with
/// any world of any seed.
const MIX_DOMAIN: u64 = u64::from_le_bytes(*b"rse mix\0");

/// The proportions of a mix of schemes, normalised.
#[derive(Debug, Clone, PartialEq)]
pub struct SchemeMix {
    /// Upper ends of each scheme's share of `[0, 1)`, the last exactly 1.
    cumulative: Vec<f64>,
}

impl SchemeMix {
    /// A mix of `proportions.len()` schemes. Each proportion is finite and
    /// 0 or more, at least one above 0; they need not sum to 1 (mjlab's
    /// `proportion`s do not either: each is its share of their sum).
    pub fn new(proportions: &[f64]) -> Result<Self, EnvError> {
        if proportions.is_empty() {
            return Err(bad("proportions", "no scheme to mix"));
        }
        if let Some((i, p)) = proportions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.is_finite() || **p < 0.0)
        {
            return Err(bad(
                "proportions",
                format!(
                    "scheme {}'s proportion is {p}; expected a number 0 or more",
                    i + 1
                ),
            ));
        }
        let largest = proportions.iter().copied().fold(0.0, f64::max);
        if largest == 0.0 {
            return Err(bad(
                "proportions",
                "every proportion is 0; give at least one scheme a share above 0",
            ));
        }
        // Shares of the sum; where the sum overflows (1e308 twice), shares
        // of the largest first, which sum to no more than their count.
        // Sums that fit are divided as they are, so every mix that drew
        // before draws the same.
        let total: f64 = proportions.iter().sum();
        let (scale, total) = if total.is_finite() {
            (1.0, total)
        } else {
            (largest, proportions.iter().map(|p| p / largest).sum())
        };
        let mut sum = 0.0;
        let mut cumulative: Vec<f64> = proportions
            .iter()
            .map(|p| {
                sum += p / scale;
                sum / total
            })
            .collect();
        // Rounding may leave the last end a hair below 1.
        if let Some(last) = cumulative.iter().rposition(|_| true) {
            cumulative[last] = 1.0;
        }
        Ok(SchemeMix { cumulative })
    }

    /// How many schemes are mixed.
    pub fn len(&self) -> usize {
        self.cumulative.len()
    }

    /// Whether the mix has no scheme (never: [`SchemeMix::new`] refuses it).
    pub fn is_empty(&self) -> bool {
        self.cumulative.is_empty()
    }

    /// The scheme (its index in the proportions) that global environment
    /// `env` of base seed `seed` draws: `u`, the top 53 bits of the first
    /// word of `ChaCha8` keyed with `seed` and "rse mix\0" (bytes 8 to 16) on stream
    /// `env`, as a fraction of 1, falls in that scheme's share. A scheme of
    /// proportion 0 is never drawn.
    pub fn scheme_of(&self, seed: u64, env: u64) -> usize {
        let mut key = [0u8; 32];
        key[..8].copy_from_slice(&seed.to_le_bytes());
        key[8..16].copy_from_slice(&MIX_DOMAIN.to_le_bytes());
        let mut rng = ChaCha8Rng::from_seed(key);
        rng.set_stream(env);
        let u = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        // The first share whose upper end is past u; a zero share's end
        // equals the one before it, so it is skipped.
        self.cumulative
            .iter()
            .position(|&end| u < end)
            .unwrap_or(self.cumulative.len() - 1)
    }

    /// The schemes of global environments `env_offset ‥ env_offset + n`.
    pub fn schemes_of(&self, seed: u64, env_offset: u64, n: usize) -> Vec<usize> {
        (0..n as u64)
            .map(|e| self.scheme_of(seed, env_offset + e))
            .collect()
    }
}

/// Whether `schemes` can be mixed in one pool: at least one, all sharing
/// the first's block size, as one field's sample spacing needs. Their
/// grids, step heights and bases may differ: every slot fits the largest
/// grid, and a field's samples are tops in metres over
/// one scale, the highest top any scheme can have. Refused naming the
/// first that differs.
pub fn check_mixable(schemes: &[Scheme]) -> Result<(), EnvError> {
    let Some(first) = schemes.first() else {
        return Err(bad("schemes", "no scheme to draw terrains from"));
    };
    let unshared = schemes
        .iter()
        .enumerate()
        .find_map(|(i, s)| unshared(first.globals(), s.globals(), Together::Mix).map(|u| (i, u)));
    match unshared {
        None => Ok(()),
        Some((i, u)) => Err(bad(
            "schemes",
            format!(
                "scheme {} has {} {}{unit}, scheme 1 {}{unit}: the schemes of a mix share their {}; their grids, step heights and bases may differ",
                i + 1,
                u.key,
                u.found,
                u.expected,
                u.key,
                unit = u
                    .key
                    .unit()
                    .map(|unit| format!(" {unit}"))
                    .unwrap_or_default(),
            ),
        )),
    }
}

/// The grid every slot of a mix of `schemes` has: the most cells along x
/// and along y of any (no pallet frames of its own: each terrain keeps
/// its own).
pub(super) fn largest_grid(schemes: &[Scheme]) -> Grid {
    let first = schemes
        .first()
        .map(Scheme::grid)
        .expect("a mix has a scheme");
    if schemes.iter().all(|s| s.grid() == first) {
        return first;
    }
    Grid {
        nx: schemes
            .iter()
            .map(|s| s.grid().nx)
            .max()
            .unwrap_or(first.nx),
        ny: schemes
            .iter()
            .map(|s| s.grid().ny)
            .max()
            .unwrap_or(first.ny),
        frame_period: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_follow_the_proportions() {
        let mix = SchemeMix::new(&[3.0, 1.0, 0.0, 4.0]).unwrap();
        let drawn = mix.schemes_of(7, 0, 80_000);
        let count = |s: usize| drawn.iter().filter(|&&d| d == s).count() as f64 / 80_000.0;
        assert!((count(0) - 0.375).abs() < 0.01, "{}", count(0));
        assert!((count(1) - 0.125).abs() < 0.01, "{}", count(1));
        assert!(drawn.iter().all(|&d| d != 2), "a share of 0 is never drawn");
        assert!((count(3) - 0.5).abs() < 0.01, "{}", count(3));
    }

    #[test]
    fn an_envs_scheme_depends_on_its_global_id_and_the_seed_alone() {
        let mix = SchemeMix::new(&[1.0, 1.0]).unwrap();
        let whole = mix.schemes_of(3, 0, 64);
        // Two processes of 32 envs each draw what one of 64 draws.
        let split = [mix.schemes_of(3, 0, 32), mix.schemes_of(3, 32, 32)].concat();
        assert_eq!(whole, split);
        assert_ne!(
            whole,
            mix.schemes_of(4, 0, 64),
            "another seed, another draw"
        );
        // Pinned: a change of the rule changes every mixed run.
        assert_eq!(&whole[..12], &[0, 0, 0, 0, 1, 0, 1, 1, 0, 0, 1, 1]);
    }

    #[test]
    fn bad_proportions_are_refused_naming_them() {
        for bad in [
            &[][..],
            &[0.0, 0.0],
            &[1.0, -1.0],
            &[f64::NAN],
            &[f64::INFINITY, 1.0],
        ] {
            let err = SchemeMix::new(bad).unwrap_err();
            assert!(err.to_string().starts_with("proportions: "), "{err}");
        }
    }

    #[test]
    fn proportions_whose_sum_overflows_are_shares_all_the_same() {
        // 1e308 twice sums to infinity: each is still half, not "0".
        for huge in [[1e308, 1e308, 0.0], [f64::MAX, f64::MAX, 0.0]] {
            let mix = SchemeMix::new(&huge).unwrap();
            assert_eq!(mix.cumulative, [0.5, 1.0, 1.0]);
        }
        let mix = SchemeMix::new(&[f64::MAX, 1e307]).unwrap();
        assert!(mix.cumulative[0] > 0.9, "{:?}", mix.cumulative);
    }

    #[test]
    fn schemes_of_one_block_size_mix_whatever_their_grid_step_and_base() {
        let scheme = |text: &str| Scheme::from_csv(text, None).unwrap();
        let a = scheme("# size: 20x10\ntype,height\nrandom,2\n");
        let steps =
            scheme("# size: 20x10\n# step_height: 0.01\n# base: 0.3\ntype,height\nrandom,9\n");
        let small = scheme("# size: 12x14\ntype,height\nrandom,2\n");
        assert!(check_mixable(&[a.clone(), steps, small.clone()]).is_ok());
        let slot = largest_grid(&[a.clone(), small]);
        assert_eq!((slot.nx, slot.ny), (20, 14));
        assert_eq!(largest_grid(std::slice::from_ref(&a)), a.grid());
        let other = scheme("# size: 20x10\n# block_size: 0.2\ntype,height\nrandom,2\n");
        let err = check_mixable(&[a, other]).unwrap_err();
        assert!(
            err.to_string()
                .starts_with("schemes: scheme 2 has block_size 0.2 m, scheme 1 0.1 m"),
            "{err}"
        );
    }

    #[test]
    fn one_scheme_is_every_env() {
        let mix = SchemeMix::new(&[0.2]).unwrap();
        assert!(mix.schemes_of(0, 0, 100).iter().all(|&s| s == 0));
    }
}
