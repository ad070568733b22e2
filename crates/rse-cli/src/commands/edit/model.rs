//! The editor's scheme as the page holds it — globals and table rows as the
//! strings typed in the fields — turned into scheme CSV for rse-core, and
//! core errors turned back into the field they concern.

use std::fmt::Write as _;

use rse_core::{Field, GLOBAL_KEYS, Scheme, SchemeError};
use serde::{Deserialize, Serialize};

/// The page's scheme: every value as typed (empty: not given).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct PageScheme {
    /// Global parameters by key (`size`, `pallets`, …).
    pub globals: std::collections::BTreeMap<String, String>,
    /// Table rows: `type`, `height`, `angle`, `x1`, `y1`, `x2`, `y2`, `sigma`.
    pub obstacles: Vec<std::collections::BTreeMap<String, String>>,
    /// The free-text notes atop the file, one per line (kept on save).
    #[serde(default)]
    pub notes: String,
}

/// Where a fault is, for the page to mark the field.
#[derive(Debug, Clone, Serialize)]
pub struct FieldError {
    /// The obstacle row (0-based), or `None` for a global.
    pub row: Option<usize>,
    /// The column or global key, when known.
    pub field: Option<String>,
    /// What is wrong, as rse-core says it.
    pub message: String,
}

impl PageScheme {
    /// The scheme CSV text of the page's values, and the CSV line of each
    /// global key and each row (for mapping errors back).
    fn to_csv(&self) -> Result<(String, Vec<Place>), FieldError> {
        let mut text = String::new();
        let mut places = Vec::new();
        for (key, value) in &self.globals {
            let value = value.trim();
            if value.is_empty() {
                continue;
            }
            if !GLOBAL_KEYS.contains(&key.as_str()) {
                return Err(FieldError {
                    row: None,
                    field: Some(key.clone()),
                    message: format!("unknown global parameter `{key}`"),
                });
            }
            check_cell(value, None, key)?;
            let _ = writeln!(text, "# {key}: {value}");
            places.push(Place::Global(key.clone()));
        }
        let columns = Field::ALL.map(Field::name);
        text.push_str(&columns.join(","));
        text.push('\n');
        places.push(Place::Header);
        for (row, fields) in self.obstacles.iter().enumerate() {
            let cells = columns
                .iter()
                .map(|c| {
                    let value = fields.get(*c).map_or("", |v| v.trim());
                    check_cell(value, Some(row), c).map(|()| value)
                })
                .collect::<Result<Vec<_>, _>>()?;
            text.push_str(&cells.join(","));
            text.push('\n');
            places.push(Place::Row(row));
        }
        Ok((text, places))
    }

    /// The validated scheme, or the field to mark.
    pub fn scheme(&self) -> Result<Scheme, FieldError> {
        let (text, places) = self.to_csv()?;
        let notes = self.notes.lines().map(|l| l.trim().to_owned()).collect();
        let scheme = Scheme::from_csv(&text, None)
            .map_err(|e| locate(&e, &places))?
            .with_notes(notes);
        // A note must read back as a note: `Author: me` would be taken for
        // a global parameter (and refused) the next time the file is read.
        if let Err(e) = Scheme::from_csv(&scheme.to_csv(), None) {
            return Err(FieldError {
                row: None,
                field: Some("notes".to_owned()),
                message: format!(
                    "a note would be read back as a global parameter ({}): reword the `word:` at its start",
                    e.kind
                ),
            });
        }
        Ok(scheme)
    }

    /// The page's view of a scheme.
    pub fn from_scheme(scheme: &Scheme) -> Self {
        // Read back through the canonical CSV: the page shows what a file holds.
        let csv = scheme.to_csv();
        let mut page = PageScheme {
            notes: scheme.notes().join("\n"),
            ..PageScheme::default()
        };
        let mut header: Vec<String> = Vec::new();
        for line in csv.lines() {
            if let Some(global) = line.strip_prefix('#') {
                // Notes come first in the canonical text; they are in `notes`.
                if let Some((key, value)) = global.split_once(':') {
                    let key = key.trim();
                    if GLOBAL_KEYS.contains(&key) {
                        page.globals.insert(key.to_owned(), value.trim().to_owned());
                    }
                }
            } else if header.is_empty() {
                header = line.split(',').map(str::to_owned).collect();
            } else {
                let row = header
                    .iter()
                    .cloned()
                    .zip(line.split(',').map(str::to_owned))
                    .filter(|(_, v)| !v.is_empty())
                    .collect();
                page.obstacles.push(row);
            }
        }
        page
    }
}

/// What a line of the composed CSV holds.
enum Place {
    Global(String),
    Header,
    Row(usize),
}

/// Refuses what would break the CSV itself (the page's fields are plain
/// values: no commas, quotes or line breaks).
fn check_cell(value: &str, row: Option<usize>, field: &str) -> Result<(), FieldError> {
    if value.contains([',', '"', '\n', '\r', '#']) {
        return Err(FieldError {
            row,
            field: Some(field.to_owned()),
            message: "may not contain , \" # or a line break".to_owned(),
        });
    }
    Ok(())
}

/// The field of a core error in the composed CSV.
fn locate(e: &SchemeError, places: &[Place]) -> FieldError {
    let line = e
        .line
        .and_then(|l| places.get(usize::try_from(l).ok()?.checked_sub(1)?));
    let row = match (e.obstacle, line) {
        (Some(i), _) | (None, Some(&Place::Row(i))) => Some(i),
        _ => None,
    };
    let field = e.field.clone().or_else(|| match line {
        Some(Place::Global(key)) => Some(key.clone()),
        _ => None,
    });
    FieldError {
        row,
        field,
        message: e.kind.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn page(globals: &[(&str, &str)], rows: &[&[(&str, &str)]]) -> PageScheme {
        PageScheme {
            globals: globals
                .iter()
                .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
                .collect(),
            obstacles: rows
                .iter()
                .map(|r| {
                    r.iter()
                        .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
                        .collect()
                })
                .collect(),
            notes: "a note\n\nwith a blank line".to_owned(),
        }
    }

    #[test]
    fn a_page_scheme_round_trips_through_a_core_scheme() {
        let p = page(
            &[("size", "20x10"), ("step_height", "0.05")],
            &[&[
                ("type", "peak"),
                ("height", "2..4"),
                ("angle", "45"),
                ("x1", "5"),
                ("y1", "3"),
            ]],
        );
        let scheme = p.scheme().unwrap();
        assert_eq!(scheme.grid().nx, 20);
        let back = PageScheme::from_scheme(&scheme);
        assert_eq!(back.obstacles[0]["height"], "2..4");
        assert_eq!(back.globals["size"], "20x10");
        assert_eq!(back.notes, "a note\n\nwith a blank line");
        assert_eq!(scheme.notes(), ["a note", "", "with a blank line"]);
        assert_eq!(back.scheme().unwrap().to_csv(), scheme.to_csv());
    }

    #[test]
    fn errors_name_the_row_and_field() {
        let p = page(
            &[("size", "10x10")],
            &[
                &[("type", "random"), ("height", "2")],
                &[
                    ("type", "peak"),
                    ("height", "2"),
                    ("angle", "45"),
                    ("x1", "12"),
                    ("y1", "3"),
                ],
            ],
        );
        let e = p.scheme().unwrap_err();
        assert_eq!((e.row, e.field.as_deref()), (Some(1), Some("x1")));
        let bad_global = page(&[("block_size", "-1")], &[]);
        let e = bad_global.scheme().unwrap_err();
        assert_eq!(
            (e.row, e.field.as_deref()),
            (None, Some("block_size")),
            "{e:?}"
        );
    }
}
