//! Errors of the core: a bad scheme names where it is (file, line, column, field).

use std::fmt;

/// Any error of the core library.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The scheme (a file, a string or values built in code) is invalid.
    #[error(transparent)]
    Scheme(#[from] SchemeError),
    /// A file could not be read. The message names the file; the
    /// system's reason is the source, printed once after it by `{:#}`
    /// (it was in both, and the CLI printed it twice).
    #[error("cannot read {path}")]
    Io {
        /// The file that failed.
        path: String,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// A preview larger than [`preview::MAX_PIXELS`](crate::preview::MAX_PIXELS).
    #[error("a {width}x{height} pixel preview is more than the {max} pixels drawn at most")]
    PreviewTooLarge {
        /// Width asked for, pixels.
        width: u64,
        /// Height asked for, pixels.
        height: u64,
        /// The cap, pixels.
        max: u64,
    },
    /// A contact sheet larger than [`preview::MAX_PIXELS`](crate::preview::MAX_PIXELS):
    /// its columns and the pixels a cell set its size.
    #[error(
        "a {width}x{height} pixel contact sheet ({cols} columns, {cell_pixels} pixels a cell) is more than the {max} pixels drawn at most"
    )]
    SheetTooLarge {
        /// Width asked for, pixels.
        width: u64,
        /// Height asked for, pixels.
        height: u64,
        /// Columns of tiles.
        cols: u64,
        /// Pixels a cell's side.
        cell_pixels: u64,
        /// The cap, pixels.
        max: u64,
    },
    /// An image could not be encoded.
    #[error("cannot encode the preview")]
    Image(#[from] png::EncodingError),
}

use crate::limits::QUOTE_CHARS;

/// A scheme that cannot be used, with the place of the fault.
///
/// Its `Display` reads `file:line:column: field: message`, leaving out the
/// parts that are unknown (a scheme built in code has no file or line).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct SchemeError {
    /// The file name as the user gave it, or `None` for a string or code.
    pub file: Option<String>,
    /// 1-based line in the file.
    pub line: Option<u64>,
    /// 1-based column (CSV field number) in that line.
    pub column: Option<u64>,
    /// The column header or global key concerned (`x1`, `block_size`, …).
    pub field: Option<String>,
    /// 0-based position of the obstacle in the table, when one is concerned.
    pub obstacle: Option<usize>,
    /// What is wrong.
    pub kind: SchemeErrorKind,
}

impl SchemeError {
    /// An error with no location yet.
    pub(crate) fn new(kind: SchemeErrorKind) -> Self {
        Self {
            file: None,
            line: None,
            column: None,
            field: None,
            obstacle: None,
            kind,
        }
    }

    pub(crate) fn with_field(mut self, field: impl Into<String>) -> Self {
        self.field = Some(field.into());
        self
    }

    pub(crate) fn at_line(mut self, line: u64) -> Self {
        self.line = Some(line);
        self
    }

    pub(crate) fn at_column(mut self, column: u64) -> Self {
        self.column = Some(column);
        self
    }
}

impl fmt::Display for SchemeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let file = self.file.as_deref().unwrap_or("<scheme>");
        write!(f, "{file}")?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(column) = self.column {
                write!(f, ":{column}")?;
            }
        } else if let Some(obstacle) = self.obstacle {
            write!(f, ": obstacle {}", obstacle + 1)?;
        }
        write!(f, ": ")?;
        if let Some(field) = &self.field {
            write!(f, "{field}: ")?;
        }
        write!(f, "{}", self.kind)
    }
}

/// What is wrong with a scheme.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SchemeErrorKind {
    /// The file is not UTF-8 text.
    #[error("the file is not UTF-8 text")]
    NotUtf8,
    /// The CSV itself is malformed (e.g. an unclosed quote).
    #[error("malformed CSV: {0}")]
    Csv(String),
    /// A `# key: value` line names no known global parameter.
    #[error(
        "unknown global parameter `{}` (known: {known}; a note is written `# note: …`)",
        quote(.0),
        known = crate::global_key::GLOBAL_KEYS.join(", ")
    )]
    UnknownGlobal(String),
    /// A leading comment `# word: value` whose word is a global's name
    /// misspelt (`step-height`, `Seeds`): an error, not a note, since the
    /// setting would be silently lost.
    #[error(
        "`{}` is not a global parameter; did you mean `{near}`? (a note may not look like `# {near}: value`: reword it)",
        quote(found)
    )]
    NearGlobal {
        /// The word as written.
        found: String,
        /// The global it is close to.
        near: &'static str,
    },
    /// A free-text note that a scheme file would read back as the global
    /// parameter setting `key: …`.
    #[error(
        "a note would be read back as a global parameter (`{0}: …`): reword the `word:` at its start"
    )]
    NoteReadsAsGlobal(String),
    /// A global parameter is given twice.
    #[error("given twice")]
    DuplicateGlobal,
    /// A global parameter has a value it cannot take.
    #[error("{}: {reason}", if value.is_empty() { "no value".to_owned() } else { format!("invalid value `{}`", quote(value)) })]
    BadGlobal {
        /// The text found.
        value: String,
        /// What is expected.
        reason: String,
    },
    /// A pallet setting (`pallet_size`, `pallet_boundary`) in a scheme
    /// without pallets.
    #[error("is set but pallets are off; add e.g. `# pallets: 2x3`")]
    PalletsOff,
    /// The header names a column that does not exist.
    #[error("unknown column `{}` (known: type, height, angle, x1, y1, x2, y2, sigma)", quote(.0))]
    UnknownColumn(String),
    /// The header names a column twice.
    #[error("column given twice")]
    DuplicateColumn,
    /// The header has no `type` column.
    #[error("the header has no `type` column")]
    MissingTypeColumn,
    /// A row has more fields than the header.
    #[error("{found} fields, but the header has {expected}")]
    TooManyFields {
        /// Fields in the row.
        found: usize,
        /// Fields in the header.
        expected: usize,
    },
    /// The `type` field names no obstacle.
    #[error("unknown obstacle type `{}` (known: random, gaussian, peak, pit, wall, long_pit)", quote(.0))]
    UnknownType(String),
    /// An obstacle lacks a field its type needs.
    #[error("required by {0} but empty")]
    MissingField(&'static str),
    /// An obstacle has a value in a field its type does not use.
    #[error("not used by {0}; leave it empty")]
    UnusedField(&'static str),
    /// A field is not a number of the expected kind.
    #[error("`{}` is not {expected}", quote(value))]
    NotANumber {
        /// The text found.
        value: String,
        /// What is expected, e.g. "a whole number ≥ 0".
        expected: &'static str,
    },
    /// A height below zero.
    #[error("{0} is negative; heights are whole steps ≥ 0")]
    NegativeHeight(i64),
    /// A height above what a cell can hold.
    #[error("{0} is above the largest supported height, {max} steps", max = crate::limits::MAX_HEIGHT)]
    HeightTooLarge(u64),
    /// A height whose top is so many step heights up that an `f32` no
    /// longer tells one step from the next there (see
    /// [`MAX_LATTICE_UNITS`](crate::MAX_LATTICE_UNITS)).
    #[error("{height} steps reach {steps:?} step heights up (base included), more than {max}: an f32 mesh no longer tells one step from the next that high; use a larger step_height or a thinner base", max = crate::limits::MAX_LATTICE_UNITS)]
    TooManySteps {
        /// The height, steps (a range's upper end).
        height: u32,
        /// `(base + height·step_height) / step_height`.
        steps: f64,
    },
    /// A height whose top is too high for the block size (see
    /// [`MAX_TOP_IN_BLOCKS`](crate::MAX_TOP_IN_BLOCKS)).
    #[error("{height} steps reach {top} m, more than {max} block sizes ({limit} m): meshes of walls that slender are not exact in f32; use fewer steps, a smaller step_height or a larger block_size", max = crate::limits::MAX_TOP_IN_BLOCKS)]
    TooTall {
        /// The height, steps (a range's upper end).
        height: u32,
        /// Its top, metres.
        top: f64,
        /// The highest top allowed, metres.
        limit: f64,
    },
    /// An angle outside `[0, 90]` degrees.
    #[error("{0} is outside 0 to 90 degrees")]
    AngleOutOfRange(f64),
    /// A negative or non-finite standard deviation.
    #[error("{0} is not a finite number ≥ 0")]
    BadSigma(f64),
    /// A range `lo..hi` with `lo > hi`.
    #[error("range {}..{} is reversed (lo > hi)", quote(lo), quote(hi))]
    ReversedRange {
        /// Lower end as written.
        lo: String,
        /// Upper end as written.
        hi: String,
    },
    /// A coordinate outside the grid.
    #[error("{value} is outside the grid: {axis} must be from 0 to {max} for a {nx}x{ny} grid")]
    PointOutsideGrid {
        /// The offending coordinate (a range's end).
        value: i64,
        /// `x` or `y`.
        axis: char,
        /// Largest allowed value.
        max: u32,
        /// Grid width.
        nx: u32,
        /// Grid depth.
        ny: u32,
    },
    /// The grid has more cells than the generator accepts.
    #[error("a {nx}x{ny} grid has {cells} cells, more than the limit of {limit}", cells = u64::from(*nx) * u64::from(*ny), limit = crate::limits::MAX_CELLS)]
    GridTooLarge {
        /// Grid width.
        nx: u32,
        /// Grid depth.
        ny: u32,
    },
}

impl SchemeErrorKind {
    /// One error of every kind, for tests that hold every message to a
    /// rule (the editor's: no file syntax, no Rust range, no key spelt with
    /// `_` reaches its page). `index` below does not compile when a kind is
    /// added, and the test beside it fails until the kind has an example.
    #[doc(hidden)]
    pub fn examples() -> Vec<Self> {
        vec![
            Self::NotUtf8,
            Self::Csv("unclosed quote".into()),
            Self::UnknownGlobal("colour".into()),
            Self::NearGlobal {
                found: "step-height".into(),
                near: "step_height",
            },
            Self::NoteReadsAsGlobal("size".into()),
            Self::DuplicateGlobal,
            Self::BadGlobal {
                value: "abc".into(),
                reason: "expected a length in metres".into(),
            },
            Self::PalletsOff,
            Self::UnknownColumn("hieght".into()),
            Self::DuplicateColumn,
            Self::MissingTypeColumn,
            Self::TooManyFields {
                found: 4,
                expected: 2,
            },
            Self::UnknownType("hill".into()),
            Self::MissingField("peak"),
            Self::UnusedField("random"),
            Self::NotANumber {
                value: "two".into(),
                expected: "a whole number ≥ 0",
            },
            Self::NegativeHeight(-1),
            Self::HeightTooLarge(70_000),
            Self::TooManySteps {
                height: 60_000,
                steps: 9e6,
            },
            Self::TooTall {
                height: 9000,
                top: 900.0,
                limit: 400.0,
            },
            Self::AngleOutOfRange(95.0),
            Self::BadSigma(-1.0),
            Self::ReversedRange {
                lo: "5".into(),
                hi: "3".into(),
            },
            Self::PointOutsideGrid {
                value: 50,
                axis: 'x',
                max: 49,
                nx: 50,
                ny: 50,
            },
            Self::GridTooLarge {
                nx: 100_000,
                ny: 100_000,
            },
        ]
    }

    /// The kind's place in the declaration (see [`examples`](Self::examples)).
    #[doc(hidden)]
    pub fn index(&self) -> usize {
        match self {
            Self::NotUtf8 => 0,
            Self::Csv(_) => 1,
            Self::UnknownGlobal(_) => 2,
            Self::NearGlobal { .. } => 3,
            Self::NoteReadsAsGlobal(_) => 4,
            Self::DuplicateGlobal => 5,
            Self::BadGlobal { .. } => 6,
            Self::PalletsOff => 7,
            Self::UnknownColumn(_) => 8,
            Self::DuplicateColumn => 9,
            Self::MissingTypeColumn => 10,
            Self::TooManyFields { .. } => 11,
            Self::UnknownType(_) => 12,
            Self::MissingField(_) => 13,
            Self::UnusedField(_) => 14,
            Self::NotANumber { .. } => 15,
            Self::NegativeHeight(_) => 16,
            Self::HeightTooLarge(_) => 17,
            Self::TooManySteps { .. } => 18,
            Self::TooTall { .. } => 19,
            Self::AngleOutOfRange(_) => 20,
            Self::BadSigma(_) => 21,
            Self::ReversedRange { .. } => 22,
            Self::PointOutsideGrid { .. } => 23,
            Self::GridTooLarge { .. } => 24,
        }
    }
}

/// How an error quotes text from a scheme: [`excerpt`] of
/// [`QUOTE_CHARS`], so a 10 MB field is not echoed whole.
pub(crate) fn quote(text: &str) -> String {
    excerpt(text, QUOTE_CHARS)
}

/// `text` as a message may quote it: escaped (no control character or
/// newline reaches a terminal) and cut to `chars` characters, with `…`
/// where it was cut.
pub fn excerpt(text: &str, chars: usize) -> String {
    let escaped: String = text.chars().flat_map(char::escape_debug).collect();
    match escaped.char_indices().nth(chars) {
        Some((at, _)) => format!("{}…", &escaped[..at]),
        None => escaped,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_has_one_example() {
        let examples = SchemeErrorKind::examples();
        let indexes: Vec<usize> = examples.iter().map(SchemeErrorKind::index).collect();
        assert_eq!(
            indexes,
            (0..examples.len()).collect::<Vec<_>>(),
            "one example a kind, in order"
        );
    }

    #[test]
    fn no_message_uses_rust_range_syntax() {
        for kind in SchemeErrorKind::examples() {
            assert!(!kind.to_string().contains("..="), "{kind}");
        }
    }
}
