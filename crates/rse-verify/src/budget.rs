//! `check`'s rebuild budget as a user sets it (`check --budget F`,
//! `rse.check(budget=F)`): a multiple of the default, validated here once,
//! so the command line and Python read it with the same rule and words.

use std::fmt;
use std::str::FromStr;

/// A multiple of the default rebuild budget
/// ([`REBUILD_VISITS`](crate::limits::REBUILD_VISITS) cell visits and the
/// memory available per world checked at once): a finite number above 0.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
pub struct Budget(f64);

/// A budget factor that is not a finite number above 0.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("budget: `{0}` is not a number above 0 (a multiple of check's default budget)")]
pub struct BudgetError(pub String);

impl Budget {
    /// The default budget, factor 1.
    pub const DEFAULT: Budget = Budget(1.0);

    /// `factor` times the default budget; refused unless finite and above 0.
    pub fn new(factor: f64) -> Result<Self, BudgetError> {
        if factor.is_finite() && factor > 0.0 {
            Ok(Budget(factor))
        } else {
            Err(BudgetError(factor.to_string()))
        }
    }

    /// The multiple of the default budget, above 0.
    pub fn factor(self) -> f64 {
        self.0
    }

    /// `base` scaled by the factor, saturating at `u64::MAX`.
    pub(crate) fn scale(self, base: u64) -> u64 {
        (base as f64 * self.0).min(u64::MAX as f64) as u64
    }
}

impl Default for Budget {
    fn default() -> Self {
        Budget::DEFAULT
    }
}

impl fmt::Display for Budget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

impl FromStr for Budget {
    type Err = BudgetError;

    fn from_str(text: &str) -> Result<Self, BudgetError> {
        match text.trim().parse::<f64>() {
            Ok(factor) => Budget::new(factor).map_err(|_| BudgetError(text.to_owned())),
            Err(_) => Err(BudgetError(text.to_owned())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_finite_factors_above_zero_are_budgets() {
        assert_eq!(Budget::default().factor().to_bits(), 1f64.to_bits());
        assert_eq!(
            "2.5".parse::<Budget>().unwrap().factor().to_bits(),
            2.5f64.to_bits()
        );
        for bad in ["0", "-1", "nan", "inf", "lots", ""] {
            let error = bad.parse::<Budget>().unwrap_err().to_string();
            assert!(error.starts_with("budget: `"), "{bad}: {error}");
        }
        assert!(Budget::new(f64::NAN).is_err() && Budget::new(0.0).is_err());
        assert_eq!(Budget::new(1e300).unwrap().scale(1 << 40), u64::MAX);
    }
}
