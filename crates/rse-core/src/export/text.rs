//! Numbers as mesh text, fast and byte for byte as `Display` writes them:
//! a terrain's coordinates take few distinct values (its grid lines and
//! step levels), so each is formatted once and looked up after; integers
//! go through `itoa`. Formatting was a fifth of a batch's time.

use rustc_hash::FxHashMap;

/// The `Display` text of every distinct coordinate of some points,
/// formatted once.
pub(crate) struct CoordinateText {
    /// A distinct value's bits → its text's place in `text`.
    index: FxHashMap<u32, usize>,
    text: Vec<String>,
}

impl CoordinateText {
    /// The texts of every coordinate of `points`.
    pub(crate) fn new(points: &[[f32; 3]]) -> Self {
        let mut index = FxHashMap::default();
        let mut text = Vec::new();
        for &c in points.iter().flatten() {
            index.entry(c.to_bits()).or_insert_with(|| {
                text.push(c.to_string());
                text.len() - 1
            });
        }
        CoordinateText { index, text }
    }

    /// `value`'s text, as `format!("{value}")` writes it.
    ///
    /// # Panics
    /// If `value` is not a coordinate of the points given to [`new`](Self::new).
    pub(crate) fn get(&self, value: f32) -> &str {
        &self.text[self.index[&value.to_bits()]]
    }

    /// Appends `x y z` (the three texts, `between` each) to `out`.
    pub(crate) fn push_point(&self, out: &mut String, [x, y, z]: [f32; 3], between: &str) {
        out.push_str(self.get(x));
        out.push_str(between);
        out.push_str(self.get(y));
        out.push_str(between);
        out.push_str(self.get(z));
    }
}

/// Appends `n` as `Display` writes it.
pub(crate) fn push_int(out: &mut String, n: impl itoa::Integer) {
    out.push_str(itoa::Buffer::new().format(n));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texts_are_what_display_writes() {
        let points = [
            [0.0, -0.0, 0.1],
            [1.5e-7, 3.4e38, f32::MIN_POSITIVE],
            [0.3, 12.25, -7.0],
        ];
        let text = CoordinateText::new(&points);
        for c in points.iter().flatten() {
            assert_eq!(text.get(*c), c.to_string());
        }
        let mut out = String::new();
        text.push_point(&mut out, points[2], " ");
        assert_eq!(out, "0.3 12.25 -7");
        push_int(&mut out, 4_294_967_295u32);
        assert_eq!(out, "0.3 12.25 -74294967295");
    }
}
