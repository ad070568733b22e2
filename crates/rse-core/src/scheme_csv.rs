//! Reading and writing scheme CSV files (docs/schemes.md).
//!
//! Layout: leading `# key: value` comment lines set global parameters (other
//! leading comment lines are kept as free-text notes), then a header row, then
//! one row per obstacle. Columns are found by header name.

use std::fmt::Write as _;

use crate::error::{SchemeError, SchemeErrorKind};
use crate::globals::{self, DEFAULT_PALLET_SIZE, GLOBAL_KEYS, Globals, Pallets};
use crate::obstacle::{Field, Obstacle, ObstacleFields, ObstacleKind};
use crate::param::{Param, ParamTextError};
use crate::scheme::{Origin, RowOrigin, Scheme};

/// Parses scheme text; `file` is the name used in error messages.
pub(crate) fn parse(text: &str, file: Option<&str>) -> Result<Scheme, SchemeError> {
    let locate = |mut error: SchemeError| {
        error.file = file.map(str::to_owned);
        error
    };
    // Spreadsheets on Windows save CSV with a byte-order mark.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);

    let mut leading = GlobalLines::default();
    let mut notes = Vec::new();
    let mut table_start = 0;
    let mut lines_before_table = 0u64;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim();
        let comment = trimmed.strip_prefix('#');
        if !trimmed.is_empty() && comment.is_none() {
            break;
        }
        lines_before_table += 1;
        table_start += line.len();
        if let Some(comment) = comment {
            match split_global(comment) {
                Some((key, value)) => leading
                    .set(key, value, lines_before_table)
                    .map_err(locate)?,
                None => notes.push(comment.trim().to_owned()),
            }
        }
    }
    let globals = leading.build().map_err(locate)?;

    let (obstacles, rows) =
        parse_table(&text[table_start..], lines_before_table).map_err(locate)?;
    let origin = Origin {
        file: file.map(str::to_owned),
        rows,
        global_lines: leading.lines,
    };
    Scheme::with_origin(globals, obstacles, notes, origin)
}

/// `key: value` where key is a single word (letters, digits, `_`); anything
/// else in a leading comment is a free-text note.
fn split_global(comment: &str) -> Option<(&str, &str)> {
    let (key, value) = comment.split_once(':')?;
    let key = key.trim();
    let is_word = !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    is_word.then(|| (key, value.trim()))
}

/// Global values as read from leading comment lines, with the line of each.
#[derive(Default)]
struct GlobalLines {
    globals: Globals,
    /// `None` when not given or `off`.
    pallets: Option<[u32; 2]>,
    pallet_size: Option<u32>,
    pallet_boundary: Option<bool>,
    lines: Vec<(&'static str, u64)>,
}

impl GlobalLines {
    fn set(&mut self, key: &str, value: &str, line: u64) -> Result<(), SchemeError> {
        let lower = key.to_ascii_lowercase();
        let Some(&key) = GLOBAL_KEYS.iter().find(|k| **k == lower) else {
            return Err(
                SchemeError::new(SchemeErrorKind::UnknownGlobal(key.to_owned()))
                    .with_field(key)
                    .at_line(line),
            );
        };
        let fail = |kind| Err(SchemeError::new(kind).with_field(key).at_line(line));
        if self.lines.iter().any(|(k, _)| *k == key) {
            return fail(SchemeErrorKind::DuplicateGlobal);
        }
        self.lines.push((key, line));
        let bad = |reason: String| {
            fail(SchemeErrorKind::BadGlobal {
                value: value.to_owned(),
                reason,
            })
        };
        let g = &mut self.globals;
        let parsed = match key {
            "size" => globals::parse_dims(value).map(|d| g.size = d),
            "pallets" => parse_pallets(value).map(|p| self.pallets = p),
            "pallet_size" => {
                parse_number(value, "a whole number of cells").map(|n| self.pallet_size = Some(n))
            }
            "pallet_boundary" => parse_bool(value).map(|b| self.pallet_boundary = Some(b)),
            "block_size" => parse_number(value, "a length in metres").map(|v| g.block_size = v),
            "step_height" => parse_number(value, "a length in metres").map(|v| g.step_height = v),
            "base" => parse_number(value, "a length in metres").map(|v| g.base = v),
            "amount" => parse_number(value, "a whole number of worlds").map(|v| g.amount = v),
            "seed" => parse_number(value, "a whole number 0..=2^64-1").map(|v| g.seed = v),
            _ => unreachable!("every key of GLOBAL_KEYS is handled"),
        };
        parsed.or_else(bad)
    }

    fn build(&self) -> Result<Globals, SchemeError> {
        let mut globals = self.globals;
        match self.pallets {
            Some(count) => {
                globals.pallets = Some(Pallets {
                    size: self.pallet_size.unwrap_or(DEFAULT_PALLET_SIZE),
                    count,
                    boundary: self.pallet_boundary.unwrap_or(true),
                });
            }
            None => {
                for key in ["pallet_size", "pallet_boundary"] {
                    if let Some((_, line)) = self.lines.iter().find(|(k, _)| *k == key) {
                        return Err(SchemeError::new(SchemeErrorKind::PalletsOff)
                            .with_field(key)
                            .at_line(*line));
                    }
                }
            }
        }
        Ok(globals)
    }
}

/// `PXxPY`, or `off`/`none`/`false` for no pallets.
fn parse_pallets(value: &str) -> Result<Option<[u32; 2]>, String> {
    match value.to_ascii_lowercase().as_str() {
        "off" | "none" | "false" | "no" => Ok(None),
        _ => globals::parse_dims(value).map(Some),
    }
}

/// `true`/`false`, `yes`/`no`, `on`/`off`, `1`/`0` (case-insensitive).
pub(crate) fn parse_bool(value: &str) -> Result<bool, String> {
    match value.trim().to_ascii_lowercase().as_str() {
        "true" | "yes" | "on" | "1" => Ok(true),
        "false" | "no" | "off" | "0" => Ok(false),
        _ => Err("expected true or false".to_owned()),
    }
}

fn parse_number<T: std::str::FromStr + ToFloat>(value: &str, what: &str) -> Result<T, String> {
    value
        .trim()
        .parse::<T>()
        .ok()
        .filter(ToFloat::is_finite_number)
        .ok_or_else(|| format!("expected {what}"))
}

/// Lets one parser refuse `inf` and `NaN`, which `f64::from_str` accepts.
trait ToFloat {
    fn is_finite_number(&self) -> bool;
}

impl ToFloat for f64 {
    fn is_finite_number(&self) -> bool {
        self.is_finite()
    }
}

impl ToFloat for u32 {
    fn is_finite_number(&self) -> bool {
        true
    }
}

impl ToFloat for u64 {
    fn is_finite_number(&self) -> bool {
        true
    }
}

/// Parses the header and rows. `lines_before` is the number of lines above
/// the header, so that reported line numbers are those of the whole file.
fn parse_table(
    table: &str,
    lines_before: u64,
) -> Result<(Vec<Obstacle>, Vec<RowOrigin>), SchemeError> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(table.as_bytes());
    let mut records = reader.records();
    let csv_error = |e: csv::Error| {
        let line = e
            .position()
            .map_or(lines_before + 1, |p| lines_before + p.line());
        SchemeError::new(SchemeErrorKind::Csv(e.to_string())).at_line(line)
    };

    let Some(header) = records.next().transpose().map_err(csv_error)? else {
        return Ok((Vec::new(), Vec::new()));
    };
    let header_line = lines_before + header.position().map_or(1, csv::Position::line);
    let mut columns = Vec::with_capacity(header.len());
    for (i, name) in header.iter().enumerate() {
        let fail = |kind| {
            Err(SchemeError::new(kind)
                .with_field(name.trim())
                .at_line(header_line)
                .at_column(i as u64 + 1))
        };
        let Some(field) = Field::from_header(name) else {
            return fail(SchemeErrorKind::UnknownColumn(name.trim().to_owned()));
        };
        if columns.contains(&field) {
            return fail(SchemeErrorKind::DuplicateColumn);
        }
        columns.push(field);
    }
    if !columns.contains(&Field::Type) {
        return Err(SchemeError::new(SchemeErrorKind::MissingTypeColumn).at_line(header_line));
    }

    let mut obstacles = Vec::new();
    let mut rows = Vec::new();
    for record in records {
        let record = record.map_err(csv_error)?;
        let line = lines_before + record.position().map_or(0, csv::Position::line);
        // Spreadsheets pad tables with rows of empty cells.
        if record.iter().all(|f| f.trim().is_empty()) {
            continue;
        }
        if record.len() > columns.len() {
            return Err(SchemeError::new(SchemeErrorKind::TooManyFields {
                found: record.len(),
                expected: columns.len(),
            })
            .at_line(line));
        }
        let (obstacle, origin) = parse_row(&record, &columns, line)?;
        obstacles.push(obstacle);
        rows.push(origin);
    }
    Ok((obstacles, rows))
}

fn parse_row(
    record: &csv::StringRecord,
    columns: &[Field],
    line: u64,
) -> Result<(Obstacle, RowOrigin), SchemeError> {
    let mut kind = None;
    let mut fields = ObstacleFields::default();
    let mut origin = RowOrigin {
        line,
        columns: Vec::new(),
    };
    for (i, (&field, text)) in columns.iter().zip(record.iter()).enumerate() {
        let column = i as u64 + 1;
        origin.columns.push((field, column));
        let text = text.trim();
        if text.is_empty() {
            continue;
        }
        let at = |kind| {
            SchemeError::new(kind)
                .with_field(field.name())
                .at_line(line)
                .at_column(column)
        };
        match field {
            Field::Type => kind = Some(text.parse::<ObstacleKind>().map_err(at)?),
            Field::Height => fields.height = Some(parse_height(text).map_err(at)?),
            Field::Angle => fields.angle = Some(parse_real(text).map_err(at)?),
            Field::Sigma => fields.sigma = Some(parse_real(text).map_err(at)?),
            Field::X1 => fields.x1 = Some(parse_cell(text).map_err(at)?),
            Field::Y1 => fields.y1 = Some(parse_cell(text).map_err(at)?),
            Field::X2 => fields.x2 = Some(parse_cell(text).map_err(at)?),
            Field::Y2 => fields.y2 = Some(parse_cell(text).map_err(at)?),
        }
    }
    let column_of = |name: Option<&str>| {
        let field = name.and_then(Field::from_header)?;
        origin
            .columns
            .iter()
            .find(|(f, _)| *f == field)
            .map(|(_, c)| *c)
    };
    let Some(kind) = kind else {
        let error = SchemeError::new(SchemeErrorKind::MissingField("every row"))
            .with_field("type")
            .at_line(line);
        let column = column_of(Some("type"));
        return Err(SchemeError { column, ..error });
    };
    let obstacle = Obstacle::new(kind, fields).map_err(|mut error| {
        error.line = Some(line);
        error.column = column_of(error.field.as_deref());
        error
    })?;
    Ok((obstacle, origin))
}

const WHOLE: &str = "a whole number ≥ 0 or a range lo..hi";
const REAL: &str = "a number or a range lo..hi";

fn parse_height(text: &str) -> Result<Param<u32>, SchemeErrorKind> {
    Param::<u32>::parse_text(text).map_err(|ParamTextError::NotANumber(part)| {
        match part.parse::<i64>() {
            Ok(v) if v < 0 => SchemeErrorKind::NegativeHeight(v),
            Ok(v) => SchemeErrorKind::HeightTooLarge(v as u64),
            Err(_) => SchemeErrorKind::NotANumber {
                value: text.to_owned(),
                expected: WHOLE,
            },
        }
    })
}

fn parse_cell(text: &str) -> Result<Param<u32>, SchemeErrorKind> {
    Param::<u32>::parse_text(text).map_err(|_| SchemeErrorKind::NotANumber {
        value: text.to_owned(),
        expected: "a cell index (a whole number ≥ 0) or a range lo..hi",
    })
}

fn parse_real(text: &str) -> Result<Param<f64>, SchemeErrorKind> {
    let not_a_number = || SchemeErrorKind::NotANumber {
        value: text.to_owned(),
        expected: REAL,
    };
    let param = Param::<f64>::parse_text(text).map_err(|_| not_a_number())?;
    if param.lo().is_finite() && param.hi().is_finite() {
        Ok(param)
    } else {
        Err(not_a_number())
    }
}

const FMT: &str = "writing to a String cannot fail";

/// The canonical text of `scheme`: notes, globals, then the table.
pub(crate) fn write(scheme: &Scheme) -> String {
    let mut out = String::new();
    for note in scheme.notes() {
        // `"".lines()` is empty, but a bare `#` line is a note too.
        let lines = if note.is_empty() {
            vec![""]
        } else {
            note.lines().collect()
        };
        for line in lines {
            if line.is_empty() {
                out.push_str("#\n");
            } else {
                writeln!(out, "# {line}").expect(FMT);
            }
        }
    }
    let g = scheme.globals();
    let defaults = Globals::default();
    if g.pallets.is_none() || g.size != defaults.size {
        writeln!(out, "# size: {}", globals::format_dims(g.size)).expect(FMT);
    }
    if let Some(p) = g.pallets {
        writeln!(out, "# pallets: {}", globals::format_dims(p.count)).expect(FMT);
        writeln!(out, "# pallet_size: {}", p.size).expect(FMT);
        writeln!(out, "# pallet_boundary: {}", p.boundary).expect(FMT);
    }
    writeln!(out, "# block_size: {}", g.block_size).expect(FMT);
    writeln!(out, "# step_height: {}", g.step_height).expect(FMT);
    if g.base.to_bits() != defaults.base.to_bits() {
        writeln!(out, "# base: {}", g.base).expect(FMT);
    }
    if g.amount != defaults.amount {
        writeln!(out, "# amount: {}", g.amount).expect(FMT);
    }
    if g.seed != defaults.seed {
        writeln!(out, "# seed: {}", g.seed).expect(FMT);
    }

    let with_sigma = scheme
        .obstacles()
        .iter()
        .any(|o| o.fields().sigma.is_some());
    let columns: Vec<Field> = Field::ALL
        .into_iter()
        .filter(|&f| f != Field::Sigma || with_sigma)
        .collect();
    let mut writer = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    let io = "writing CSV into memory cannot fail";
    writer
        .write_record(columns.iter().map(|f| f.name()))
        .expect(io);
    for obstacle in scheme.obstacles() {
        let f = obstacle.fields();
        let show = |p: Option<Param<u32>>| p.map(|p| p.to_string()).unwrap_or_default();
        let show_real = |p: Option<Param<f64>>| p.map(|p| p.to_string()).unwrap_or_default();
        let row: Vec<String> = columns
            .iter()
            .map(|field| match field {
                Field::Type => obstacle.kind().name().to_owned(),
                Field::Height => show(f.height),
                Field::Angle => show_real(f.angle),
                Field::X1 => show(f.x1),
                Field::Y1 => show(f.y1),
                Field::X2 => show(f.x2),
                Field::Y2 => show(f.y2),
                Field::Sigma => show_real(f.sigma),
            })
            .collect();
        writer.write_record(&row).expect(io);
    }
    let table = writer.into_inner().expect(io);
    out.push_str(&String::from_utf8(table).expect("the table is built from UTF-8 strings"));
    out
}
