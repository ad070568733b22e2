//! Difficulty: a factor in `[0, 1]` that scales every obstacle height of a
//! world while keeping its layout, for curricula, and the rule that rounds
//! the scaled heights to whole steps (`docs/schemes.md`, "Difficulty").

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// A difficulty `D`, finite and `0 ≤ D ≤ 1`. A non-frame cell of height
/// `h` steps becomes `floor(D·h + u)` steps, `u` drawn once per world
/// ([`DifficultyRule::Drawn`]); frames stay one step.
///
/// `D = 1` leaves every height as it is, bit for bit; `D = 0` flattens
/// every obstacle. The same `(seed, index)` at two difficulties draws the
/// same obstacles and the same `u`, so a harder world is the easier one
/// with taller blocks (`floor(D·h + u)` is monotone in both `D` and `h`).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct Difficulty(f64);

/// A difficulty outside `[0, 1]` or not a number.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("difficulty {value}: expected a number from 0 to 1")]
pub struct DifficultyError {
    /// What was given, as text.
    pub value: String,
}

impl Difficulty {
    /// Today's terrains: every height as drawn.
    pub const FULL: Difficulty = Difficulty(1.0);

    /// `d`, refused unless finite and in `[0, 1]`.
    pub fn new(d: f64) -> Result<Self, DifficultyError> {
        if (0.0..=1.0).contains(&d) {
            // `-0.0` is in range; store `+0.0` so the two cannot differ in
            // any output.
            Ok(Difficulty(d + 0.0))
        } else {
            Err(DifficultyError {
                value: d.to_string(),
            })
        }
    }

    /// The factor `D`, from 0 to 1.
    pub fn get(self) -> f64 {
        self.0
    }

    /// `true` for [`Difficulty::FULL`].
    pub fn is_full(self) -> bool {
        // Exactly 1: only then is every height kept (new() never stores
        // anything above 1).
        self.0 >= 1.0
    }

    /// A height of `h` steps at this difficulty, rounded half up:
    /// `floor(D·h + 0.5)` ([`DifficultyRule::Nearest`]).
    pub fn scale(self, h: u16) -> u16 {
        self.scale_offset(h, 0.5)
    }

    /// A height of `h` steps at this difficulty, rounded down after adding
    /// `offset` (`0 ≤ offset < 1`): `floor(D·h + offset)`.
    pub fn scale_offset(self, h: u16, offset: f64) -> u16 {
        // `D·h ≤ h ≤ 65535`, so the result fits; at D = 1 it is `h` exactly
        // when `h + offset` is exact, which [`unit_offset`] makes sure of.
        (self.0 * f64::from(h) + offset).floor() as u16
    }

    /// The `i`-th of `n` evenly spaced difficulties from `lo` to `hi`:
    /// `lo + (hi − lo)·i/(n − 1)`, and `hi` when `n = 1` (the rows of an
    /// atlas).
    pub fn lerp(lo: Difficulty, hi: Difficulty, i: u32, n: u32) -> Difficulty {
        if n <= 1 {
            return hi;
        }
        let t = f64::from(i) / f64::from(n - 1);
        // The ends exactly, whatever rounding does in between.
        let d = match i {
            0 => lo.0,
            i if i + 1 == n => hi.0,
            _ => lo.0 + (hi.0 - lo.0) * t,
        };
        Difficulty(d.clamp(0.0, 1.0))
    }
}

/// How a scaled height `D·h` becomes whole steps. Recorded in `rse.json`
/// (`"difficulty_rule"`) beside a difficulty below 1, so `check` rebuilds a
/// world by the rule it was written with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DifficultyRule {
    /// `floor(D·h + 0.5)`: the rule of worlds written before the drawn
    /// rule (their `rse.json` names no rule). Dead levels: a scheme of
    /// 1-step blocks is flat at every `D < 0.5`.
    Nearest,
    /// `floor(D·h + u)`, `u` one draw per world from its own stream (after
    /// the obstacles, so they are the same at every `D`), and the world's
    /// highest cell (the first in row order; frames aside) at least one
    /// step whenever `D > 0`. Over many worlds a cell's expected height is
    /// exactly `D·h`, so the mean height rises with `D` without a dead zone,
    /// and no world of a non-flat draw is flat above `D = 0`.
    Drawn,
}

impl DifficultyRule {
    /// The rule worlds are written with today.
    pub const CURRENT: DifficultyRule = DifficultyRule::Drawn;

    /// Its name in `rse.json`.
    pub fn name(self) -> &'static str {
        match self {
            DifficultyRule::Nearest => "nearest",
            DifficultyRule::Drawn => "drawn",
        }
    }
}

/// A rounding offset in `[0, 1)` from 32 random bits: a multiple of `2⁻³²`,
/// so `h + offset` is exact in f64 for every `h ≤ 65535` (16 + 32 bits)
/// and `floor(1·h + offset)` is `h`.
pub(crate) fn unit_offset(bits: u32) -> f64 {
    f64::from(bits) / 4_294_967_296.0
}

impl Default for Difficulty {
    fn default() -> Self {
        Difficulty::FULL
    }
}

impl TryFrom<f64> for Difficulty {
    type Error = DifficultyError;

    fn try_from(d: f64) -> Result<Self, DifficultyError> {
        Difficulty::new(d)
    }
}

impl From<Difficulty> for f64 {
    fn from(d: Difficulty) -> f64 {
        d.0
    }
}

impl FromStr for Difficulty {
    type Err = DifficultyError;

    fn from_str(s: &str) -> Result<Self, DifficultyError> {
        let bad = || DifficultyError {
            value: format!("{s:?}"),
        };
        let d: f64 = s.trim().parse().map_err(|_| bad())?;
        Difficulty::new(d).map_err(|_| bad())
    }
}

impl fmt::Display for Difficulty {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_keeps_every_height() {
        for h in [0, 1, 2, 7, 1000, u16::MAX] {
            assert_eq!(Difficulty::FULL.scale(h), h);
        }
    }

    #[test]
    fn heights_round_half_up() {
        let half = Difficulty::new(0.5).unwrap();
        assert_eq!([1, 2, 3, 4, 5].map(|h| half.scale(h)), [1, 1, 2, 2, 3]);
        assert_eq!(Difficulty::new(0.0).unwrap().scale(u16::MAX), 0);
    }

    #[test]
    fn scaling_is_monotone_in_difficulty() {
        let ds: Vec<Difficulty> = (0..=100)
            .map(|i| Difficulty::new(f64::from(i) / 100.0).unwrap())
            .collect();
        for h in 0..=300u16 {
            for pair in ds.windows(2) {
                assert!(pair[0].scale(h) <= pair[1].scale(h), "h {h} {pair:?}");
            }
        }
    }

    #[test]
    fn full_keeps_every_height_at_any_offset() {
        for bits in [0, 1, u32::MAX / 2, u32::MAX] {
            let offset = unit_offset(bits);
            assert!(offset < 1.0);
            for h in [0, 1, 2, 7, 1000, u16::MAX] {
                assert_eq!(Difficulty::FULL.scale_offset(h, offset), h);
            }
        }
    }

    #[test]
    fn out_of_range_and_text_are_refused() {
        for bad in ["2", "-0.1", "NaN", "inf", "hard", ""] {
            let err = bad.parse::<Difficulty>().unwrap_err();
            assert!(err.to_string().contains("from 0 to 1"), "{err}");
        }
        assert!(Difficulty::new(f64::NAN).is_err());
        assert_eq!("-0".parse::<Difficulty>().unwrap().get().to_bits(), 0);
    }

    #[test]
    fn lerp_hits_both_ends() {
        let (lo, hi) = (Difficulty::new(0.1).unwrap(), Difficulty::new(0.7).unwrap());
        assert_eq!(Difficulty::lerp(lo, hi, 0, 7), lo);
        assert_eq!(Difficulty::lerp(lo, hi, 6, 7), hi);
        assert_eq!(Difficulty::lerp(lo, hi, 0, 1), hi);
        assert!((Difficulty::lerp(lo, hi, 3, 7).get() - 0.4).abs() < 1e-12);
    }

    #[test]
    fn json_refuses_out_of_range() {
        assert!(serde_json::from_str::<Difficulty>("1.5").is_err());
        assert_eq!(
            serde_json::from_str::<Difficulty>("0.25").unwrap(),
            Difficulty::new(0.25).unwrap()
        );
    }
}
