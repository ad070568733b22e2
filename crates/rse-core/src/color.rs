//! The terrain's colour (`# color: 0.72 0.58 0.42`): red, green and blue
//! from 0 to 1, drawn by every target (its material, `.mtl`, USD display
//! colour).

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::global_value::{GlobalText, ParseGlobal};

/// Red, green and blue, each from 0 to 1 (linear, as every target's
/// material takes them).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "[f64; 3]", into = "[f64; 3]")]
pub struct Color([f64; 3]);

impl Color {
    /// Matte light wood, the colour of a NIST stepfield's blocks.
    pub const WOOD: Color = Color([0.72, 0.58, 0.42]);

    /// Light grey, the ground's colour around the terrain.
    pub const LIGHT_GREY: Color = Color([0.8, 0.8, 0.8]);

    /// `[r, g, b]`, each a finite number from 0 to 1.
    ///
    /// # Errors
    /// A component outside 0..=1, or not finite, with why.
    pub fn new(rgb: [f64; 3]) -> Result<Color, String> {
        match rgb.iter().find(|c| !(0.0..=1.0).contains(*c)) {
            Some(c) => Err(format!(
                "{c} is not from 0 to 1: red, green and blue each go from 0 to 1, e.g. 0.72 0.58 0.42"
            )),
            None => Ok(Color(rgb)),
        }
    }

    /// `[r, g, b]`.
    pub fn rgb(self) -> [f64; 3] {
        self.0
    }
}

impl Default for Color {
    fn default() -> Self {
        Color::WOOD
    }
}

impl TryFrom<[f64; 3]> for Color {
    type Error = String;

    fn try_from(rgb: [f64; 3]) -> Result<Self, String> {
        Color::new(rgb)
    }
}

impl From<Color> for [f64; 3] {
    fn from(color: Color) -> Self {
        color.0
    }
}

/// `R G B` (spaces), as every target's text writes a colour.
impl fmt::Display for Color {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [r, g, b] = self.0;
        write!(f, "{r} {g} {b}")
    }
}

/// `0.72 0.58 0.42` or `0.72,0.58,0.42`.
impl FromStr for Color {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let parts: Vec<&str> = text
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|part| !part.is_empty())
            .collect();
        let [r, g, b] = parts[..] else {
            return Err(format!(
                "`{}` is not three numbers (red green blue, each 0 to 1), e.g. 0.72 0.58 0.42",
                text.trim()
            ));
        };
        let number = |part: &str| {
            part.parse::<f64>()
                .map_err(|_| format!("`{part}` is not a number"))
        };
        Color::new([number(r)?, number(g)?, number(b)?])
    }
}

impl ParseGlobal for Color {
    fn parse_global(text: &str, _: &str) -> Result<Self, String> {
        text.parse()
    }
}

impl GlobalText for Color {
    fn global_text(&self) -> String {
        self.to_string()
    }

    fn same_global(&self, other: &Self) -> bool {
        self.0.map(f64::to_bits) == other.0.map(f64::to_bits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_colour_is_read_back_from_its_text() {
        for text in ["0.72 0.58 0.42", "1 0 0.5", "0.1,0.2,0.3"] {
            let color: Color = text.parse().unwrap();
            assert_eq!(color.to_string().parse::<Color>().unwrap(), color);
        }
        assert_eq!(Color::default().to_string(), "0.72 0.58 0.42");
    }

    #[test]
    fn a_colour_outside_0_to_1_or_not_three_numbers_is_refused() {
        for text in ["1.5 0 0", "0 0", "0 0 0 0", "red", "NaN 0 0", "-0.1 0 0"] {
            let e = text.parse::<Color>().unwrap_err();
            assert!(!e.is_empty(), "{text}");
        }
    }
}
