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
            Param::Range(lo, hi) => write!(f, "{lo}..{hi}"),
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
        match text.split_once("..") {
            Some((lo, hi)) => Ok(Param::Range(one(lo)?, one(hi)?)),
            None => Ok(Param::Fixed(one(text)?)),
        }
    }
}
