//! How a global key's value is read from its text in a scheme file and
//! written back, picked by the value's type ([`ParseGlobal`],
//! [`GlobalText`]): the table of keys names a type, and its impls here (or
//! beside the type, as `Color`'s) are its parser and writer.

/// A global's value read from its text, the parser picked by the value's
/// type (each key's type in the table is its own).
pub(crate) trait ParseGlobal: Sized {
    /// The value of `text`; `expects` says what it must be.
    fn parse_global(text: &str, expects: &str) -> Result<Self, String>;
}

/// `size`: `NXxNY`.
impl ParseGlobal for [u32; 2] {
    fn parse_global(text: &str, _: &str) -> Result<Self, String> {
        parse_dims(text)
    }
}

/// `pallets`: a count, or off.
impl ParseGlobal for Option<[u32; 2]> {
    fn parse_global(text: &str, _: &str) -> Result<Self, String> {
        parse_pallets(text)
    }
}

impl ParseGlobal for bool {
    fn parse_global(text: &str, _: &str) -> Result<Self, String> {
        parse_bool(text)
    }
}

impl ParseGlobal for u32 {
    fn parse_global(text: &str, expects: &str) -> Result<Self, String> {
        parse_number(text, expects)
    }
}

impl ParseGlobal for u64 {
    fn parse_global(text: &str, expects: &str) -> Result<Self, String> {
        parse_number(text, expects)
    }
}

impl ParseGlobal for f64 {
    fn parse_global(text: &str, expects: &str) -> Result<Self, String> {
        parse_number(text, expects)
    }
}

/// `PXxPY`, or `off`/`none`/`false`/`no` for no pallets: the `pallets`
/// value of a scheme file, the editor and `--pallets` alike (its range,
/// at least one each way, is the key's: `GlobalsPatch::set_key` checks it).
pub fn parse_pallets(value: &str) -> Result<Option<[u32; 2]>, String> {
    match value.trim().to_ascii_lowercase().as_str() {
        "off" | "none" | "false" | "no" => Ok(None),
        _ => parse_dims(value).map(Some),
    }
}

/// `true`/`false`, `yes`/`no`, `on`/`off`, `1`/`0` (case-insensitive).
fn parse_bool(value: &str) -> Result<bool, String> {
    match value.trim().to_ascii_lowercase().as_str() {
        "true" | "yes" | "on" | "1" => Ok(true),
        "false" | "no" | "off" | "0" => Ok(false),
        _ => Err("expected true or false".to_owned()),
    }
}

fn parse_number<T: std::str::FromStr + IsFinite>(value: &str, what: &str) -> Result<T, String> {
    value
        .trim()
        .parse::<T>()
        .ok()
        .filter(IsFinite::is_finite_number)
        .ok_or_else(|| format!("expected {what}"))
}

/// Lets one parser refuse `inf` and `NaN`, which `f64::from_str` accepts.
trait IsFinite {
    fn is_finite_number(&self) -> bool;
}

impl IsFinite for f64 {
    fn is_finite_number(&self) -> bool {
        self.is_finite()
    }
}

impl IsFinite for u32 {
    fn is_finite_number(&self) -> bool {
        true
    }
}

impl IsFinite for u64 {
    fn is_finite_number(&self) -> bool {
        true
    }
}

/// A global's value as its canonical text in a scheme file (read back by
/// its `ParseGlobal`), the writer picked by the value's type.
pub(crate) trait GlobalText {
    /// The text a scheme file writes.
    fn global_text(&self) -> String;

    /// The same value, as the scheme file tells them apart (`-0.0` is not
    /// `0.0`: its text differs).
    fn same_global(&self, other: &Self) -> bool;
}

impl GlobalText for f64 {
    fn global_text(&self) -> String {
        self.to_string()
    }

    fn same_global(&self, other: &Self) -> bool {
        self.to_bits() == other.to_bits()
    }
}

impl GlobalText for u64 {
    fn global_text(&self) -> String {
        self.to_string()
    }

    fn same_global(&self, other: &Self) -> bool {
        self == other
    }
}

impl GlobalText for u32 {
    fn global_text(&self) -> String {
        self.to_string()
    }

    fn same_global(&self, other: &Self) -> bool {
        self == other
    }
}

impl GlobalText for bool {
    fn global_text(&self) -> String {
        self.to_string()
    }

    fn same_global(&self, other: &Self) -> bool {
        self == other
    }
}

impl GlobalText for [u32; 2] {
    fn global_text(&self) -> String {
        format_dims(*self)
    }

    fn same_global(&self, other: &Self) -> bool {
        self == other
    }
}

/// `pallets`: a count, or `off`.
impl GlobalText for Option<[u32; 2]> {
    fn global_text(&self) -> String {
        self.map_or_else(|| "off".to_owned(), format_dims)
    }

    fn same_global(&self, other: &Self) -> bool {
        self == other
    }
}

/// Parses `NXxNY` (also `NX×NY`, `NX*NY`, spaces allowed) into `[nx, ny]`.
pub fn parse_dims(text: &str) -> Result<[u32; 2], String> {
    let text = text.trim();
    let (a, b) = text
        .split_once(['x', 'X', '×', '*'])
        .ok_or_else(|| format!("`{text}` is not of the form NXxNY, e.g. 50x50"))?;
    // Named whole: "sixty by forty" splits at its first `x`, and `si` is
    // no help to whoever typed it.
    let one = |s: &str| {
        s.trim()
            .parse::<u32>()
            .map_err(|_| format!("`{text}` is not two whole numbers NXxNY, e.g. 50x50"))
    };
    Ok([one(a)?, one(b)?])
}

/// Writes `[nx, ny]` as `NXxNY`.
pub fn format_dims(dims: [u32; 2]) -> String {
    format!("{}x{}", dims[0], dims[1])
}
