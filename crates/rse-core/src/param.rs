//! A scheme value that is either fixed or an inclusive random range `lo..hi`.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// A number in a scheme: fixed, or drawn uniformly per world from `lo..=hi`.
///
/// Serialised (JSON) as a plain number or as `[lo, hi]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Param<T> {
    /// Always this value.
    Fixed(T),
    /// Drawn per world, uniformly, from `lo` to `hi` inclusive.
    Range(T, T),
}

impl<T: Copy + PartialOrd> Param<T> {
    /// The smallest value it can take.
    pub fn lo(&self) -> T {
        match *self {
            Param::Fixed(v) | Param::Range(v, _) => v,
        }
    }

    /// The largest value it can take.
    pub fn hi(&self) -> T {
        match *self {
            Param::Fixed(v) | Param::Range(_, v) => v,
        }
    }

    /// `true` for a range with `lo > hi`.
    pub fn is_reversed(&self) -> bool {
        self.lo() > self.hi()
    }

    /// Applies `f` to both ends.
    pub fn map<U>(self, f: impl Fn(T) -> U) -> Param<U> {
        match self {
            Param::Fixed(v) => Param::Fixed(f(v)),
            Param::Range(lo, hi) => Param::Range(f(lo), f(hi)),
        }
    }
}

impl<T: fmt::Display> fmt::Display for Param<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Param::Fixed(v) => write!(f, "{v}"),
            Param::Range(lo, hi) => write!(f, "{lo}{RANGE}{hi}"),
        }
    }
}

/// Why a field's text is not a `Param`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ParamTextError {
    /// One end is not a number of the wanted kind; holds that end's text.
    NotANumber(String),
}

impl<T: FromStr> Param<T> {
    /// Parses `v` or `lo..hi` (spaces around the parts are allowed).
    pub(crate) fn parse_text(text: &str) -> Result<Self, ParamTextError> {
        let one = |s: &str| {
            let s = s.trim();
            s.parse::<T>()
                .map_err(|_| ParamTextError::NotANumber(s.to_owned()))
        };
        match text.split_once(RANGE) {
            Some((lo, hi)) => Ok(Param::Range(one(lo)?, one(hi)?)),
            None => Ok(Param::Fixed(one(text)?)),
        }
    }
}

/// What separates a range's ends in a field's text.
const RANGE: &str = "..";

/// A field's text split into its ends as a form shows them: `[lo, hi]` for
/// a range `lo..hi`, `[v, ""]` for one value (the inverse of
/// [`range_text`]; neither end is parsed).
pub fn range_parts(text: &str) -> [&str; 2] {
    match text.split_once(RANGE) {
        Some((lo, hi)) => [lo, hi],
        None => [text, ""],
    }
}

/// A field's text from the ends a form holds: `lo..hi`, or `lo` alone when
/// `hi` is blank.
pub fn range_text(lo: &str, hi: &str) -> String {
    let (lo, hi) = (lo.trim(), hi.trim());
    if hi.is_empty() {
        lo.to_owned()
    } else {
        format!("{lo}{RANGE}{hi}")
    }
}

#[cfg(test)]
mod tests {
    use super::{Param, range_parts, range_text};

    #[test]
    fn a_fields_ends_split_and_join_back() {
        assert_eq!(range_parts("2..4"), ["2", "4"]);
        assert_eq!(range_parts("3"), ["3", ""]);
        assert_eq!(range_text(" 2 ", "4"), "2..4");
        assert_eq!(range_text("3", "  "), "3");
        let range: Param<u32> = Param::parse_text(&range_text("2", "4")).unwrap();
        assert_eq!(range, Param::Range(2, 4));
        assert_eq!(range_parts(&range.to_string()), ["2", "4"]);
    }
}
