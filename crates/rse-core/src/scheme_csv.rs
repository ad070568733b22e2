//! Reading and writing scheme CSV files (docs/schemes.md).
//!
//! Layout: leading `# key: value` comment lines set global parameters (other
//! leading comment lines are kept as free-text notes), then a header row, then
//! one row per obstacle. Columns are found by header name.

use std::fmt::Write as _;

use crate::error::{SchemeError, SchemeErrorKind};
use crate::global_key::GlobalKey;
use crate::globals::Globals;
use crate::globals_patch::GlobalsPatch;
use crate::obstacle::{Field, Obstacle, ObstacleFields, ObstacleKind};
use crate::param::{Param, ParamTextError};
use crate::scheme::{Origin, RowOrigin, Scheme};

/// Schemes read from and written to the scheme file format.
impl Scheme {
    /// Parses scheme CSV text; `file` is the name used in error messages.
    pub fn from_csv(text: &str, file: Option<&str>) -> Result<Self, SchemeError> {
        parse(text, file)
    }

    /// Parses scheme CSV bytes, refusing text that is not UTF-8.
    pub fn from_csv_bytes(bytes: &[u8], file: Option<&str>) -> Result<Self, SchemeError> {
        match std::str::from_utf8(bytes) {
            Ok(text) => Self::from_csv(text, file),
            Err(e) => {
                #[allow(clippy::naive_bytecount)] // once per bad file: not worth a crate
                let line = bytes[..e.valid_up_to()]
                    .iter()
                    .filter(|&&b| b == b'\n')
                    .count() as u64
                    + 1;
                let mut error = SchemeError::new(SchemeErrorKind::NotUtf8).at_line(line);
                error.file = file.map(str::to_owned);
                Err(error)
            }
        }
    }

    /// The canonical CSV text of this scheme; reading it back gives an equal scheme.
    pub fn to_csv(&self) -> String {
        write(self)
    }

    /// The same scheme with other free-text notes (the comment lines written
    /// above the table). A note a scheme file would read back as a global
    /// parameter (`Author: me`) is refused: error field `notes`.
    pub fn with_notes(mut self, notes: Vec<String>) -> Result<Self, SchemeError> {
        let reads_as_global = notes
            .iter()
            .flat_map(|note| note.lines())
            .find_map(|line| split_global(line).map(|(key, _)| key));
        if let Some(key) = reads_as_global {
            return Err(
                SchemeError::new(SchemeErrorKind::NoteReadsAsGlobal(key.to_owned()))
                    .with_field("notes"),
            );
        }
        self.notes = notes;
        Ok(self)
    }
}

/// Rows read from and written to a scheme file's cells.
impl Obstacle {
    /// A row from its cells' text as a scheme file holds it (`("height",
    /// "2..4")`; blank cells are not given), validated as [`Obstacle::new`]
    /// does. The error's `field` names the faulty column.
    pub fn from_cells<'a>(
        cells: impl IntoIterator<Item = (Field, &'a str)>,
    ) -> Result<Self, SchemeError> {
        obstacle_of_cells(cells)
    }

    /// The text of each given cell, in column order, as a scheme file
    /// writes it; [`Obstacle::from_cells`] reads it back to an equal row.
    pub fn cells(&self) -> Vec<(Field, String)> {
        cells_of(self)
    }
}

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
            if let Some((key, value)) = split_global(comment) {
                leading
                    .set(key, value, lines_before_table)
                    .map_err(locate)?;
            } else {
                notes.push(note(comment, lines_before_table).map_err(locate)?);
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

/// The word that starts a note whatever follows (`# note: Try 0.05`): the
/// one single word before a `:` that is not a global parameter.
pub(crate) const NOTE: &str = "note";

/// `key: value` where key is a single word (letters, digits, `_`) other
/// than [`NOTE`]; anything else in a leading comment is a free-text note.
pub(crate) fn split_global(comment: &str) -> Option<(&str, &str)> {
    let (key, value) = comment.split_once(':')?;
    let key = key.trim();
    let is_word = !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    (is_word && !key.eq_ignore_ascii_case(NOTE)).then(|| (key, value.trim()))
}

/// The free-text note of the comment at `line`, or the error of one that
/// misspells a global ([`misspelt_global`]).
fn note(comment: &str, line: u64) -> Result<String, SchemeError> {
    match misspelt_global(comment) {
        Some((found, near)) => {
            let kind = SchemeErrorKind::NearGlobal {
                found: found.to_owned(),
                near,
            };
            Err(SchemeError::new(kind).with_field(found).at_line(line))
        }
        None => Ok(comment.trim().to_owned()),
    }
}

/// A note `words: value` whose words (letters, digits, `_`, `-`, spaces;
/// at most three) spell a global's name with a slip: `step-height: 0.05`
/// would otherwise be kept as a note and its setting silently lost. The
/// words as written and the global they are near.
fn misspelt_global(comment: &str) -> Option<(&str, &'static str)> {
    let (key, _) = comment.split_once(':')?;
    let key = key.trim();
    let wordy = key
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | ' '));
    if key.is_empty() || !wordy || key.split_whitespace().count() > 3 {
        return None;
    }
    crate::globals::nearest_global(key).map(|near| (key, near))
}

/// Global values as read from leading comment lines, with the line of each.
#[derive(Default)]
struct GlobalLines {
    patch: GlobalsPatch,
    lines: Vec<(&'static str, u64)>,
}

impl GlobalLines {
    fn set(&mut self, key: &str, value: &str, line: u64) -> Result<(), SchemeError> {
        let known = GlobalKey::find(key);
        if let Some(key) = known.filter(|k| self.lines.iter().any(|(seen, _)| *seen == k.name())) {
            return Err(SchemeError::new(SchemeErrorKind::DuplicateGlobal)
                .with_field(key.name())
                .at_line(line));
        }
        let key = self.patch.set(key, value).map_err(|e| e.at_line(line))?;
        self.lines.push((key.name(), line));
        Ok(())
    }

    /// The globals, a fault placed on the line of the key it concerns.
    fn build(&self) -> Result<Globals, SchemeError> {
        self.patch.apply(&Globals::default()).map_err(|e| {
            let line = self
                .lines
                .iter()
                .find(|(k, _)| Some(*k) == e.field.as_deref())
                .map(|(_, line)| *line);
            match line {
                Some(line) => e.at_line(line),
                None => e,
            }
        })
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
    let origin = RowOrigin {
        line,
        columns: (1..).zip(columns).map(|(c, &f)| (f, c)).collect(),
    };
    let cells = columns.iter().copied().zip(record.iter());
    let obstacle = obstacle_of_cells(cells).map_err(|mut error| {
        origin.place(&mut error);
        error
    })?;
    Ok((obstacle, origin))
}

/// Reads one cell's text (trimmed, not empty) into the row being built.
fn set_cell(
    kind: &mut Option<ObstacleKind>,
    fields: &mut ObstacleFields,
    field: Field,
    text: &str,
) -> Result<(), SchemeErrorKind> {
    match field {
        Field::Type => *kind = Some(text.parse::<ObstacleKind>()?),
        Field::Height => fields.height = Some(parse_height(text)?),
        Field::Angle => fields.angle = Some(parse_real(text)?),
        Field::Sigma => fields.sigma = Some(parse_real(text)?),
        Field::X1 => fields.x1 = Some(parse_cell(text)?),
        Field::Y1 => fields.y1 = Some(parse_cell(text)?),
        Field::X2 => fields.x2 = Some(parse_cell(text)?),
        Field::Y2 => fields.y2 = Some(parse_cell(text)?),
        Field::Tread => fields.tread = Some(parse_tread(text)?),
    }
    Ok(())
}

/// An obstacle from its cells' text as a scheme file holds them (blank
/// cells are not given); the error's `field` names the column.
pub(crate) fn obstacle_of_cells<'a>(
    cells: impl IntoIterator<Item = (Field, &'a str)>,
) -> Result<Obstacle, SchemeError> {
    let mut kind = None;
    let mut fields = ObstacleFields::default();
    for (field, text) in cells {
        let text = text.trim();
        if text.is_empty() {
            continue;
        }
        set_cell(&mut kind, &mut fields, field, text)
            .map_err(|kind| SchemeError::new(kind).with_field(field.name()))?;
    }
    let kind = kind.ok_or_else(|| {
        SchemeError::new(SchemeErrorKind::MissingField("every row")).with_field("type")
    })?;
    Obstacle::new(kind, fields)
}

/// The text of each cell of `obstacle` that is given, as a scheme file
/// writes it ([`obstacle_of_cells`] reads it back to an equal obstacle).
pub(crate) fn cells_of(obstacle: &Obstacle) -> Vec<(Field, String)> {
    let f = obstacle.fields();
    let whole = |p: Option<Param<u32>>| p.map(|p| p.to_string());
    let real = |p: Option<Param<f64>>| p.map(|p| p.to_string());
    Field::ALL
        .into_iter()
        .filter_map(|field| {
            let text = match field {
                Field::Type => Some(obstacle.kind().name().to_owned()),
                Field::Height => whole(f.height),
                Field::Angle => real(f.angle),
                Field::X1 => whole(f.x1),
                Field::Y1 => whole(f.y1),
                Field::X2 => whole(f.x2),
                Field::Y2 => whole(f.y2),
                Field::Sigma => real(f.sigma),
                Field::Tread => whole(f.tread),
            };
            text.map(|t| (field, t))
        })
        .collect()
}

const WHOLE: &str = "a whole number ≥ 0 or a range lo..hi";
const REAL: &str = "a number or a range lo..hi";

fn parse_height(text: &str) -> Result<Param<u32>, SchemeErrorKind> {
    Param::<u32>::parse_text(text).map_err(|ParamTextError::NotANumber(part)| {
        match part.parse::<i64>() {
            Ok(v) if v < 0 => SchemeErrorKind::NegativeHeight(v),
            Ok(v) if v > i64::from(u32::MAX) => SchemeErrorKind::HeightTooLarge(v as u64),
            // `-0`: a number, but not as a height is written.
            _ => SchemeErrorKind::NotANumber {
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

fn parse_tread(text: &str) -> Result<Param<u32>, SchemeErrorKind> {
    Param::<u32>::parse_text(text).map_err(|_| SchemeErrorKind::NotANumber {
        value: text.to_owned(),
        expected: "a whole number of cells ≥ 1 or a range lo..hi",
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
    for (key, text) in scheme.globals().cells() {
        writeln!(out, "# {key}: {text}").expect(FMT);
    }

    // The optional columns only where a row fills them: a scheme without
    // them is written as it always was.
    let used = |f: Field| match f {
        Field::Sigma => scheme
            .obstacles()
            .iter()
            .any(|o| o.fields().sigma.is_some()),
        Field::Tread => scheme
            .obstacles()
            .iter()
            .any(|o| o.fields().tread.is_some()),
        _ => true,
    };
    let columns: Vec<Field> = Field::ALL.into_iter().filter(|&f| used(f)).collect();
    let mut writer = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    let io = "writing CSV into memory cannot fail";
    writer
        .write_record(columns.iter().map(|f| f.name()))
        .expect(io);
    for obstacle in scheme.obstacles() {
        let cells = cells_of(obstacle);
        let row = columns.iter().map(|column| {
            cells
                .iter()
                .find(|(field, _)| field == column)
                .map_or("", |(_, text)| text.as_str())
        });
        writer.write_record(row).expect(io);
    }
    let table = writer.into_inner().expect(io);
    out.push_str(&String::from_utf8(table).expect("the table is built from UTF-8 strings"));
    out
}
