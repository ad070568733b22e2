//! The editor's scheme as the page holds it — globals and table rows as the
//! text typed in each field — built into a core scheme by core's own
//! field parsers ([`GlobalsPatch::set`], [`Obstacle::from_cells`]), and a
//! core fault turned back into the field it concerns.

use std::collections::BTreeMap;

use rse_core::{
    Field, Globals, GlobalsPatch, Obstacle, Scheme, SchemeError, range_parts, range_text,
};
use serde::{Deserialize, Serialize};

/// The page's scheme: every value as typed (empty: not given).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct PageScheme {
    /// Global parameters by key (`size`, `pallets`, …).
    pub globals: BTreeMap<String, String>,
    /// Table rows by column: `type`, `height`, `angle`, `x1`, `y1`, `x2`,
    /// `y2`, `sigma`.
    pub obstacles: Vec<BTreeMap<String, Cell>>,
    /// The free-text notes atop the file, one per line (kept on save).
    #[serde(default)]
    pub notes: String,
}

/// One table cell: the two inputs of a column (`["2", "4"]` for a range,
/// `["3", ""]` for one value), or, as the page sends `type`, one text.
/// Answers give every column but `type` as its two ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Cell {
    /// A column's low and high inputs (high blank: one value).
    Ends([String; 2]),
    /// A cell's whole text, as a scheme file holds it.
    Text(String),
}

impl Cell {
    /// The cell's text as core's field parsers read it.
    fn text(&self) -> String {
        match self {
            Cell::Ends([lo, hi]) => range_text(lo, hi),
            Cell::Text(text) => text.clone(),
        }
    }

    /// The page's cell for `field` holding `text`, as a scheme file writes it.
    fn of(field: Field, text: &str) -> Self {
        match field {
            Field::Type => Cell::Text(text.to_owned()),
            _ => Cell::Ends(range_parts(text).map(str::to_owned)),
        }
    }
}

/// Where a fault is, for the page to mark the field.
#[derive(Debug, Clone, Serialize)]
pub struct FieldError {
    /// The obstacle row (0-based), or `None` for a global.
    pub row: Option<usize>,
    /// The column or global key, when known.
    pub field: Option<String>,
    /// What is wrong, in the page's words (`words::scheme_fault`).
    pub message: String,
}

impl FieldError {
    fn of(e: &SchemeError, row: Option<usize>) -> Self {
        FieldError {
            row: row.or(e.obstacle),
            field: e.field.clone(),
            message: crate::words::scheme_fault(&e.kind),
        }
    }
}

impl PageScheme {
    /// The validated scheme, or the field to mark.
    pub fn scheme(&self) -> Result<Scheme, FieldError> {
        let mut patch = GlobalsPatch::default();
        for (key, text) in &self.globals {
            if !text.trim().is_empty() {
                patch.set(key, text).map_err(|e| FieldError::of(&e, None))?;
            }
        }
        let globals = patch
            .apply(&Globals::default())
            .map_err(|e| FieldError::of(&e, None))?;
        let obstacles = self
            .obstacles
            .iter()
            .enumerate()
            .map(|(row, cells)| {
                let texts: Vec<(&String, String)> = cells
                    .iter()
                    .map(|(column, cell)| (column, cell.text()))
                    .collect();
                let cells = texts.iter().map(|(column, text)| {
                    Field::from_header(column)
                        .map(|field| (field, text.as_str()))
                        .ok_or_else(|| FieldError {
                            row: Some(row),
                            field: Some((*column).clone()),
                            message: format!("unknown column `{column}`"),
                        })
                });
                let cells = cells.collect::<Result<Vec<_>, _>>()?;
                Obstacle::from_cells(cells).map_err(|e| FieldError::of(&e, Some(row)))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let notes = self.notes.lines().map(|l| l.trim().to_owned()).collect();
        Scheme::new(globals, obstacles)
            .and_then(|scheme| scheme.with_notes(notes))
            .map_err(|e| FieldError::of(&e, None))
    }

    /// The page's view of a scheme: each field as a scheme file writes it.
    pub fn from_scheme(scheme: &Scheme) -> Self {
        let cells = |pairs: Vec<(Field, String)>| {
            pairs
                .into_iter()
                .map(|(field, text)| (field.name().to_owned(), Cell::of(field, &text)))
                .collect()
        };
        PageScheme {
            globals: scheme
                .globals()
                .cells()
                .into_iter()
                .map(|(key, text)| (key.name().to_owned(), text))
                .collect(),
            obstacles: scheme
                .obstacles()
                .iter()
                .map(|o| cells(o.cells()))
                .collect(),
            notes: scheme.notes().join("\n"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rse_core::Param;

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
                        .map(|(k, v)| ((*k).to_owned(), Cell::Text((*v).to_owned())))
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
        assert_eq!(
            back.obstacles[0]["height"],
            Cell::Ends(["2".into(), "4".into()])
        );
        assert_eq!(
            back.obstacles[0]["angle"],
            Cell::Ends(["45".into(), String::new()])
        );
        assert_eq!(back.obstacles[0]["type"], Cell::Text("peak".into()));
        assert_eq!(back.globals["size"], "20x10");
        assert_eq!(back.notes, "a note\n\nwith a blank line");
        assert_eq!(scheme.notes(), ["a note", "", "with a blank line"]);
        assert_eq!(back.scheme().unwrap().to_csv(), scheme.to_csv());
    }

    #[test]
    fn the_page_sends_a_columns_two_ends() {
        let p: PageScheme = serde_json::from_str(
            r#"{"globals": {"size": "10x10"}, "obstacles": [
                {"type": "random", "height": ["1", "3"], "sigma": ["", ""]},
                {"type": "random", "height": "2"}]}"#,
        )
        .unwrap();
        let scheme = p.scheme().unwrap();
        assert_eq!(
            scheme.obstacles()[0].fields().height,
            Some(Param::Range(1, 3))
        );
        assert_eq!(scheme.obstacles()[1].fields().height, Some(Param::Fixed(2)));
        let answer = serde_json::to_value(PageScheme::from_scheme(&scheme)).unwrap();
        assert_eq!(
            answer["obstacles"][0]["height"],
            serde_json::json!(["1", "3"])
        );
        assert_eq!(
            answer["obstacles"][1]["height"],
            serde_json::json!(["2", ""])
        );
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

    /// Every key's value outside its range (rse-core's table declares
    /// both) is refused on that key's field, in the range's words.
    #[test]
    fn a_value_outside_a_keys_range_is_refused_on_its_field() {
        let mut walked = 0;
        for key in rse_core::GlobalKey::ALL {
            let Some(outside) = key.outside_example() else {
                continue;
            };
            let needs_pallets = [
                rse_core::GlobalKey::PalletSize,
                rse_core::GlobalKey::PalletBoundary,
            ]
            .contains(&key);
            let mut globals = vec![(key.name(), outside)];
            if needs_pallets {
                globals.push(("pallets", "1x1"));
            }
            let e = page(&globals, &[]).scheme().unwrap_err();
            assert_eq!(
                (e.row, e.field.as_deref()),
                (None, Some(key.name())),
                "{e:?}"
            );
            walked += 1;
        }
        assert!(walked >= 8, "{walked} keys with a range");
    }

    #[test]
    fn a_note_read_back_as_a_global_is_refused_on_the_notes_field() {
        let mut p = page(&[], &[]);
        p.notes = "fine\nAuthor: me".to_owned();
        let e = p.scheme().unwrap_err();
        assert_eq!((e.row, e.field.as_deref()), (None, Some("notes")), "{e:?}");
        assert!(e.message.contains("starts with `Author:`"), "{}", e.message);
    }

    #[test]
    fn a_pallet_boundary_off_without_pallets_is_not_a_fault() {
        assert!(page(&[("pallet_boundary", "false")], &[]).scheme().is_ok());
        let e = page(&[("pallet_size", "4")], &[]).scheme().unwrap_err();
        assert_eq!(e.field.as_deref(), Some("pallet_size"));
    }

    #[test]
    fn an_unknown_column_is_named() {
        let e = page(&[], &[&[("type", "random"), ("hieght", "2")]])
            .scheme()
            .unwrap_err();
        assert_eq!((e.row, e.field.as_deref()), (Some(0), Some("hieght")));
    }
}
