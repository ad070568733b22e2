//! What a global key's value must be beyond its type: its range, declared
//! with the key in the table of [`for_each_global_key`](crate::for_each_global_key)
//! (`range:`) and checked by [`GlobalsPatch::check_ranges`](crate::GlobalsPatch::check_ranges)
//! wherever a value enters (a scheme file, a flag, a Python keyword, the
//! editor, a world's record), so no skin holds a range of its own.

use crate::limits::MIN_LENGTH;

/// A range of values of type `T`: why a value is outside it.
pub trait GlobalRange<T> {
    /// `Err(why)` for a value outside the range, said as the end of
    /// "`key` … must be …".
    fn check(&self, value: &T) -> Result<(), String>;
}

/// What a range allows, in words, and a value outside it.
pub trait RangeText {
    /// What the value must be (docs/schemes.md's table, the editor), or
    /// `""` where its type says it all.
    fn describe(&self) -> &'static str;

    /// A value outside the range as a scheme file writes it, the one the
    /// tests push through every skin to see each refuse it; `None` where
    /// every value of the type is in range.
    fn outside(&self) -> Option<&'static str>;
}

/// Every value of the type.
#[derive(Debug, Clone, Copy)]
pub struct AnyValue;

impl<T> GlobalRange<T> for AnyValue {
    fn check(&self, _: &T) -> Result<(), String> {
        Ok(())
    }
}

impl RangeText for AnyValue {
    fn describe(&self) -> &'static str {
        ""
    }

    fn outside(&self) -> Option<&'static str> {
        None
    }
}

/// The values the type itself refuses to hold (a colour's components,
/// each 0 to 1, are `Color`'s to check): nothing left to check, but said
/// in the docs and pushed through the skins all the same.
#[derive(Debug, Clone, Copy)]
pub struct CheckedByType {
    /// What the value must be.
    pub describe: &'static str,
    /// A text the type refuses.
    pub outside: &'static str,
}

impl<T> GlobalRange<T> for CheckedByType {
    fn check(&self, _: &T) -> Result<(), String> {
        Ok(())
    }
}

impl RangeText for CheckedByType {
    fn describe(&self) -> &'static str {
        self.describe
    }

    fn outside(&self) -> Option<&'static str> {
        Some(self.outside)
    }
}

const MIN_LENGTH_REASON: &str =
    "must be at least 0.001 m: shorter is not exact in an f32 mesh, nor told apart by check";

/// A length of at least [`MIN_LENGTH`] metres.
#[derive(Debug, Clone, Copy)]
pub struct Length;

impl GlobalRange<f64> for Length {
    fn check(&self, &value: &f64) -> Result<(), String> {
        if !(value.is_finite() && value > 0.0) {
            return Err("must be a length in metres > 0".to_owned());
        }
        if value < MIN_LENGTH {
            return Err(MIN_LENGTH_REASON.to_owned());
        }
        Ok(())
    }
}

impl RangeText for Length {
    fn describe(&self) -> &'static str {
        "at least 0.001 m"
    }

    fn outside(&self) -> Option<&'static str> {
        Some("0.0005")
    }
}

/// A length of 0 (what 0 means said by `.0`) or at least [`MIN_LENGTH`]
/// metres.
#[derive(Debug, Clone, Copy)]
pub struct LengthOrZero(pub &'static str);

impl GlobalRange<f64> for LengthOrZero {
    fn check(&self, &value: &f64) -> Result<(), String> {
        if !(value.is_finite() && value >= 0.0) {
            return Err("must be a length in metres ≥ 0".to_owned());
        }
        if value > 0.0 && value < MIN_LENGTH {
            return Err(format!(
                "must be 0 ({}) or at least 0.001 m: thinner is not exact in an f32 mesh, nor told apart by check",
                self.0
            ));
        }
        Ok(())
    }
}

impl RangeText for LengthOrZero {
    fn describe(&self) -> &'static str {
        "0, or at least 0.001 m"
    }

    fn outside(&self) -> Option<&'static str> {
        Some("-0.5")
    }
}

/// A whole number of at least one of `.0` ("world", "cell").
#[derive(Debug, Clone, Copy)]
pub struct AtLeastOne(pub &'static str);

impl<T: Copy + Into<u64>> GlobalRange<T> for AtLeastOne {
    fn check(&self, &value: &T) -> Result<(), String> {
        if value.into() == 0 {
            return Err(format!("needs at least one {}", self.0));
        }
        Ok(())
    }
}

impl RangeText for AtLeastOne {
    fn describe(&self) -> &'static str {
        "at least 1"
    }

    fn outside(&self) -> Option<&'static str> {
        Some("0")
    }
}

/// Two whole numbers of at least one of `.0` each ("cell", "pallet"); for
/// an optional pair (pallets), `None` (off) too.
#[derive(Debug, Clone, Copy)]
pub struct EachAtLeastOne(pub &'static str);

impl GlobalRange<[u32; 2]> for EachAtLeastOne {
    fn check(&self, value: &[u32; 2]) -> Result<(), String> {
        if value.contains(&0) {
            return Err(format!("needs at least one {} each way", self.0));
        }
        Ok(())
    }
}

impl GlobalRange<Option<[u32; 2]>> for EachAtLeastOne {
    fn check(&self, value: &Option<[u32; 2]>) -> Result<(), String> {
        value.as_ref().map_or(Ok(()), |pair| self.check(pair))
    }
}

impl RangeText for EachAtLeastOne {
    fn describe(&self) -> &'static str {
        "at least 1 each way"
    }

    fn outside(&self) -> Option<&'static str> {
        Some("0x2")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_range_refuses_its_outside_value_and_keeps_its_edge() {
        assert!(Length.check(&0.0005).is_err());
        assert!(Length.check(&-1.0).is_err());
        assert!(Length.check(&f64::NAN).is_err());
        assert!(Length.check(&MIN_LENGTH).is_ok());
        let slab = LengthOrZero("no slab");
        assert!(slab.check(&0.0).is_ok());
        assert!(slab.check(&-0.5).is_err());
        assert!(slab.check(&0.0005).unwrap_err().contains("no slab"));
        assert!(AtLeastOne("world").check(&0_u64).is_err());
        assert!(AtLeastOne("world").check(&1_u32).is_ok());
        assert!(EachAtLeastOne("cell").check(&[0, 2]).is_err());
        assert!(EachAtLeastOne("pallet").check(&None).is_ok());
        assert!(EachAtLeastOne("pallet").check(&Some([1, 0])).is_err());
    }
}
