//! Global parameters of a scheme (docs/schemes.md) and the grid they define.

use serde::ser::SerializeStruct as _;
use serde::{Deserialize, Serialize, Serializer};

use crate::error::{SchemeError, SchemeErrorKind};
use crate::for_each_global_key;
use crate::global_key::{GLOBAL_KEYS, GlobalKey};
use crate::global_value::GlobalText;
use crate::limits::{MAX_CELLS, MAX_EXTENT, MAX_LATTICE_UNITS, MAX_TOP_IN_BLOCKS};

/// The global whose name `word` most likely misspells (any case, `-` or a
/// space for `_`, one edit away for a short name, two for a long one), if
/// any: `step-height` → `step_height`, `Seeds` → `seed`.
pub(crate) fn nearest_global(word: &str) -> Option<&'static str> {
    let word: String = word
        .trim()
        .chars()
        .map(|c| {
            if c == '-' || c == ' ' {
                '_'
            } else {
                c.to_ascii_lowercase()
            }
        })
        .collect();
    GLOBAL_KEYS
        .iter()
        .map(|&key| (strsim::levenshtein(&word, key), key))
        .filter(|&(distance, key)| distance <= if key.len() <= 5 { 1 } else { 2 })
        .min()
        .map(|(_, key)| key)
}

/// The fault of global `key` holding `value`, with why it cannot.
fn bad(key: GlobalKey, value: String, reason: &str) -> Result<(), SchemeError> {
    Err(SchemeError::new(SchemeErrorKind::BadGlobal {
        value,
        reason: reason.to_owned(),
    })
    .with_field(key.name()))
}

/// Pallet layout: `count[0] × count[1]` pallets of `size × size` cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Pallets {
    /// Pallet side in cells (inside the frame).
    pub size: u32,
    /// Pallets along x and y.
    pub count: [u32; 2],
    /// A 1-cell frame, 1 step high, around every pallet.
    pub boundary: bool,
}

/// [`Globals`], its defaults and the canonical text of its stored keys,
/// from the table of [`for_each_global_key`]: the grid's fields by hand
/// (`size`, and `pallets`, which the three pallet keys share), then a
/// field for each key `stored` in one of its own. Munches the table entry
/// by entry, keeping the stored keys.
macro_rules! declare_globals {
    (@munch [$($fields:tt)*] [$($keys:tt)*]) => {
        /// The global parameters of a scheme (docs/schemes.md). Lengths in
        /// metres.
        #[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
        // A world's record written before a key was added reads as its
        // default.
        #[serde(default)]
        pub struct Globals {
            /// `[nx, ny]` in cells, used when `pallets` is `None`.
            pub size: [u32; 2],
            /// Pallet layout; when set, it defines the grid and `size` is
            /// ignored.
            pub pallets: Option<Pallets>,
            $($fields)*
        }

        declare_globals!(@keys $($keys)*);
    };
    (@keys $($variant:ident $field:ident ($default:expr) $text:ident $record:ident;)*) => {
        impl Default for Globals {
            fn default() -> Self {
                Globals {
                    size: [10, 10],
                    pallets: None,
                    $($field: $default,)*
                }
            }
        }

        impl Globals {
            /// The keys stored in a field of their own; the rest (the
            /// grid's) are written out by hand.
            #[cfg(test)]
            pub(crate) const STORED: &[GlobalKey] = &[$(GlobalKey::$variant),*];

            /// The canonical text of a stored key, `None` where the scheme
            /// file leaves it out (its table's `text`) or where `key` is
            /// the grid's.
            pub(crate) fn stored_text(&self, key: GlobalKey) -> Option<String> {
                let defaults = Globals::default();
                match key {
                    $(GlobalKey::$variant => {
                        canonical_text!($text, self.$field, defaults.$field)
                    })*
                    _ => None,
                }
            }

            /// Serializes these globals as a world's `rse.json` records
            /// them: every key, but those recorded `unless_default` left
            /// out at their default (keys added after worlds were written,
            /// whose records must keep their bytes). `Serialize` writes
            /// every key (the templates' context, a pickled terrain).
            ///
            /// # Errors
            /// The serializer's.
            pub fn serialize_record<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                let defaults = Globals::default();
                let mut record = serializer.serialize_struct("Globals", 2 + [$(stringify!($field)),*].len())?;
                record.serialize_field("size", &self.size)?;
                record.serialize_field("pallets", &self.pallets)?;
                $(record_field!($record, record, $field, self.$field, defaults.$field);)*
                record.end()
            }

            /// A stored key's default as its text; `None` for the grid's.
            pub(crate) fn stored_default_text(key: GlobalKey) -> Option<String> {
                let defaults = Globals::default();
                match key {
                    $(GlobalKey::$variant => Some(defaults.$field.global_text()),)*
                    _ => None,
                }
            }

        }
    };
    (@munch [$($fields:tt)*] [$($keys:tt)*]
        $(#[doc = $what:literal])*
        $variant:ident { $field:ident: $ty:ty, range: $range:expr, stored: by_hand, flag: $flag:tt }
        $($rest:tt)*
    ) => {
        declare_globals!(@munch [$($fields)*] [$($keys)*] $($rest)*);
    };
    (@munch [$($fields:tt)*] [$($keys:tt)*]
        $(#[doc = $what:literal])*
        $variant:ident {
            $field:ident: $ty:ty,
            range: $range:expr,
            stored: { default: $default:expr, text: $text:ident, record: $record:ident },
            flag: $flag:tt
        }
        $($rest:tt)*
    ) => {
        declare_globals!(@munch
            [$($fields)* $(#[doc = $what])* pub $field: $ty,]
            [$($keys)* $variant $field ($default) $text $record;]
            $($rest)*);
    };
    ($($table:tt)*) => {
        declare_globals!(@munch [] [] $($table)*);
    };
}

/// A stored key's canonical text by its table's `text`: `always`, or
/// `unless_default` (the same value as the default is left out).
macro_rules! canonical_text {
    (always, $value:expr, $default:expr) => {
        Some($value.global_text())
    };
    (unless_default, $value:expr, $default:expr) => {
        (!$value.same_global(&$default)).then(|| $value.global_text())
    };
}

/// A stored key's field in `rse.json` by its table's `record`: `always`,
/// or `unless_default` (left out at its default).
macro_rules! record_field {
    (always, $record:ident, $field:ident, $value:expr, $default:expr) => {
        $record.serialize_field(stringify!($field), &$value)?
    };
    (unless_default, $record:ident, $field:ident, $value:expr, $default:expr) => {
        if $value.same_global(&$default) {
            $record.skip_field(stringify!($field))?
        } else {
            $record.serialize_field(stringify!($field), &$value)?
        }
    };
}

for_each_global_key!(declare_globals);

impl Globals {
    /// The grid these parameters define (frame included).
    pub fn grid(&self) -> Grid {
        match self.pallets {
            None => Grid {
                nx: self.size[0],
                ny: self.size[1],
                frame_period: None,
            },
            Some(p) if p.boundary => Grid {
                nx: p.count[0]
                    .saturating_mul(p.size.saturating_add(1))
                    .saturating_add(1),
                ny: p.count[1]
                    .saturating_mul(p.size.saturating_add(1))
                    .saturating_add(1),
                frame_period: Some(p.size + 1),
            },
            Some(p) => Grid {
                nx: p.count[0].saturating_mul(p.size),
                ny: p.count[1].saturating_mul(p.size),
                frame_period: None,
            },
        }
    }

    /// Checks every value's range (its table entry's), the grid size and
    /// what the values must be together. The error's `field` names the
    /// global key.
    pub fn validate(&self) -> Result<(), SchemeError> {
        // Each key's range, as its table entry declares it.
        self.as_patch().check_ranges()?;
        // Frames and any cell of one step reach `base + step_height`.
        let lowest_top = self.base + self.step_height;
        if lowest_top > MAX_TOP_IN_BLOCKS * self.block_size {
            let key = if self.base > self.step_height {
                GlobalKey::Base
            } else {
                GlobalKey::StepHeight
            };
            let value = if key == GlobalKey::Base {
                self.base
            } else {
                self.step_height
            };
            // `{:?}` prints 1e308 as such, `{}` with 309 digits.
            return bad(
                key,
                format!("{value:?}"),
                &format!(
                    "base + step_height ({lowest_top:?} m) must be at most {MAX_TOP_IN_BLOCKS} block sizes ({} m): meshes of walls that slender are not exact in f32",
                    MAX_TOP_IN_BLOCKS * self.block_size
                ),
            );
        }
        let grid = self.grid();
        if u64::from(grid.nx) * u64::from(grid.ny) > MAX_CELLS
            || grid.nx == u32::MAX
            || grid.ny == u32::MAX
        {
            let key = if self.pallets.is_some() {
                GlobalKey::Pallets
            } else {
                GlobalKey::Size
            };
            return Err(SchemeError::new(SchemeErrorKind::GridTooLarge {
                nx: grid.nx,
                ny: grid.ny,
            })
            .with_field(key.name()));
        }
        let longest = f64::from(grid.nx.max(grid.ny)) * self.block_size;
        if longest > MAX_EXTENT {
            return bad(
                GlobalKey::BlockSize,
                format!("{:?}", self.block_size),
                &format!(
                    "the grid would be {longest:?} m long; at most {MAX_EXTENT} m is supported"
                ),
            );
        }
        // Past these an f32 mesh no longer tells neighbouring corners (or
        // steps) apart, and check could not map its vertices back.
        if u64::from(grid.nx.max(grid.ny)) > MAX_LATTICE_UNITS {
            let key = if self.pallets.is_some() {
                GlobalKey::Pallets
            } else {
                GlobalKey::Size
            };
            return bad(
                key,
                format!("{}x{}", grid.nx, grid.ny),
                &format!(
                    "more than {MAX_LATTICE_UNITS} cells along a side: an f32 mesh no longer tells neighbouring cell corners apart"
                ),
            );
        }
        if self.base / self.step_height + 1.0 > MAX_LATTICE_UNITS as f64 {
            return bad(
                GlobalKey::Base,
                format!("{:?}", self.base),
                &format!(
                    "is more than {MAX_LATTICE_UNITS} step heights: an f32 mesh no longer tells one step from the next above it"
                ),
            );
        }
        Ok(())
    }

    /// The highest top `height` steps can reach, metres.
    pub fn top(&self, height: u32) -> f64 {
        self.base + f64::from(height) * self.step_height
    }
}

/// The cell grid of an RSE: its size and where the pallet frames are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Grid {
    /// Cells along x.
    pub nx: u32,
    /// Cells along y.
    pub ny: u32,
    /// With pallet frames: every `frame_period`-th row and column, from 0, is frame.
    pub frame_period: Option<u32>,
}

impl Grid {
    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.nx as usize * self.ny as usize
    }

    /// `true` if cell `(x, y)` lies on a pallet frame line.
    pub fn is_frame(&self, x: u32, y: u32) -> bool {
        self.frame_period
            .is_some_and(|period| x.is_multiple_of(period) || y.is_multiple_of(period))
    }
}
