//! The global keys of a scheme, declared once in one table
//! ([`global_key_table`]): each key's name (in a scheme file, the editor
//! and Python; `--block-size` on the command line), its field in the patch,
//! its unit, what its text must be, its range, its default and one line of
//! documentation. The enum, the globals and their patch are built from the
//! table; the CSV reader, the editor's schema, the command line and Python
//! read them instead of matching strings of their own.

/// The global keys, declared once: each key's variant, name (in a scheme
/// file, the editor and Python; `--block-size` on the command line), field
/// and type in the patch (whose type picks its parser, its canonical text
/// and its Python value), unit, what its text must be, its range (a
/// [`global_range`](crate::global_range) value: what the value must be
/// beyond its type, checked by every skin through
/// [`GlobalsPatch::check_ranges`](crate::GlobalsPatch::check_ranges)), an
/// example other than its default (the value the tests walk it through
/// every skin with), one line of documentation, how
/// [`Globals`](crate::Globals) stores it, and its command-line flag.
///
/// `stored: { default, text, record }` makes the key a field of `Globals`
/// of its own: its default, whether the canonical scheme file writes it
/// `always` or `unless_default`, and whether `rse.json` records it
/// `always` or `unless_default` (a key added after worlds were written is
/// `unless_default` there, so their bytes do not change). `stored:
/// by_hand` is for the grid's keys (`size` and the pallet keys, which
/// share one `Pallets`), whose rules `globals.rs` and `globals_patch.rs`
/// write out.
///
/// `flag: {}` is for no flag (`amount` and `seed` are the batch's own);
/// otherwise the flag's type, help line and clap `#[arg]` settings, as
/// tokens only rse-cli expands. Its value is read by the scheme file's
/// parser and range (rse-cli's `flag_value`).
///
/// Hands the whole table, entry by entry as written here, to
/// `$($callback)+` with `[$($pass)*]` before it. Only [`GlobalKey`] reads
/// it so: every other consumer takes the short form
/// [`for_each_global_key`] gives, and asks [`GlobalKey`] for the rest. A
/// key of a type these already know is added here and nowhere else
/// (docs/development.md, "Adding a global key of the scheme").
#[doc(hidden)]
#[macro_export]
macro_rules! global_key_table {
    ([$($callback:tt)+] [$($pass:tt)*]) => {
        $($callback)+! { [$($pass)*]
            /// `[nx, ny]` in cells.
            Size {
                name: "size",
                field: size: [u32; 2],
                unit: Some("cells"),
                expects: "NXxNY, whole numbers of cells",
                range: $crate::global_range::EachAtLeastOne("cell"),
                example: "13x11",
                doc: "`NXxNY` cells, used when pallets are off",
                stored: by_hand,
                flag: {
                    ty: [u32; 2],
                    help: "Grid size in cells, used when pallets are off.",
                    arg: (value_name = "NXxNY")
                },
            }
            /// Pallets along x and y, or off: `Some(None)` turns them off.
            Pallets {
                name: "pallets",
                field: pallets: Option<[u32; 2]>,
                unit: Some("pallets"),
                expects: "NXxNY pallets, or off",
                range: $crate::global_range::EachAtLeastOne("pallet"),
                example: "2x1",
                doc: "`PXxPY` pallets, or `off`",
                stored: by_hand,
                flag: {
                    ty: PalletsFlag,
                    help: "Pallets along x and y, or `off`.",
                    arg: (value_name = "PXxPY|off")
                },
            }
            /// Pallet side in cells; needs pallets.
            PalletSize {
                name: "pallet_size",
                field: pallet_size: u32,
                unit: Some("cells"),
                expects: "a whole number of cells",
                range: $crate::global_range::AtLeastOne("cell"),
                example: "7",
                doc: "pallet side in cells, inside the frame (needs `pallets`; a NIST pallet is 10)",
                stored: by_hand,
                flag: {
                    ty: u32,
                    help: "Pallet side in cells (needs pallets).",
                    arg: (value_name = "CELLS")
                },
            }
            /// Whether every pallet has a frame; `true` needs pallets.
            PalletBoundary {
                name: "pallet_boundary",
                field: pallet_boundary: bool,
                unit: None,
                expects: "true or false",
                range: $crate::global_range::AnyValue,
                example: "false",
                doc: "`true`/`false`: a 1-cell frame, 1 step high, around every pallet (needs `pallets`)",
                stored: by_hand,
                flag: {
                    ty: bool,
                    help: "A 1-cell, 1-step frame around every pallet (needs pallets).",
                    arg: (value_name = "true|false", action = clap::ArgAction::Set, hide_possible_values = true)
                },
            }
            /// Cell side, metres.
            BlockSize {
                name: "block_size",
                field: block_size: f64,
                unit: Some("m"),
                expects: "a length in metres",
                range: $crate::global_range::Length,
                example: "0.05",
                doc: "cell side `S` in metres",
                stored: { default: 0.1, text: always, record: always },
                flag: {
                    ty: f64,
                    help: "Cell side in metres.",
                    arg: (value_name = "M")
                },
            }
            /// One step, metres.
            StepHeight {
                name: "step_height",
                field: step_height: f64,
                unit: Some("m"),
                expects: "a length in metres",
                range: $crate::global_range::Length,
                example: "0.025",
                doc: "height of one step in metres",
                stored: { default: 0.1, text: always, record: always },
                flag: {
                    ty: f64,
                    help: "Height of one step in metres.",
                    arg: (value_name = "M")
                },
            }
            /// The slab under the grid, metres.
            Base {
                name: "base",
                field: base: f64,
                unit: Some("m"),
                expects: "a length in metres",
                range: $crate::global_range::LengthOrZero("no slab"),
                example: "0.02",
                doc: "slab under the whole grid, metres",
                stored: { default: 0.0, text: unless_default, record: always },
                flag: {
                    ty: f64,
                    help: "Slab under the whole grid in metres (0 for none).",
                    arg: (value_name = "M")
                },
            }
            /// The terrain's colour, red green blue from 0 to 1.
            Color {
                name: "color",
                field: color: $crate::Color,
                unit: None,
                expects: "red, green and blue, each 0 to 1",
                range: $crate::global_range::CheckedByType { describe: "each component 0 to 1", outside: "1.5 0 0" },
                example: "0.1 0.2 0.3",
                doc: "the terrain's colour: red green blue (light wood)",
                stored: { default: $crate::Color::WOOD, text: unless_default, record: unless_default },
                flag: {
                    ty: $crate::Color,
                    help: "The terrain's colour: red green blue, each 0 to 1.",
                    arg: (value_name = "R,G,B")
                },
            }
            /// The ground's colour around the terrain, red green blue from 0 to 1.
            GroundColor {
                name: "ground_color",
                field: ground_color: $crate::Color,
                unit: None,
                expects: "red, green and blue, each 0 to 1",
                range: $crate::global_range::CheckedByType { describe: "each component 0 to 1", outside: "0 0 -0.1" },
                example: "0.3 0.5 0.3",
                doc: "the ground's colour around the terrain: red green blue (light grey)",
                stored: { default: $crate::Color::LIGHT_GREY, text: unless_default, record: unless_default },
                flag: {
                    ty: $crate::Color,
                    help: "The ground's colour around the terrain: red green blue, each 0 to 1.",
                    arg: (value_name = "R,G,B")
                },
            }
            /// Worlds in a batch.
            Amount {
                name: "amount",
                field: amount: u64,
                unit: Some("worlds"),
                expects: "a whole number of worlds",
                range: $crate::global_range::AtLeastOne("world"),
                example: "3",
                doc: "worlds in a batch",
                stored: { default: 1, text: unless_default, record: always },
                flag: {},
            }
            /// The batch's base seed.
            Seed {
                name: "seed",
                field: seed: u64,
                unit: None,
                expects: "a whole number from 0 to 2^64 − 1",
                range: $crate::global_range::AnyValue,
                example: "17",
                doc: "base seed of a batch, a whole number from 0 to 2^64 − 1",
                stored: { default: 0, text: unless_default, record: always },
                flag: {},
            }
        }
    };
}

/// The table of [`global_key_table`] in the short form every consumer but
/// [`GlobalKey`] matches, one entry a key:
///
/// ```text
/// /// docs
/// Variant { field: Type, range: RANGE, stored: STORED, flag: FLAG }
/// ```
///
/// the parts that shape types and code (the patch's field and type, the
/// range checked, how `Globals` stores it, the command-line flag). The
/// rest (name, unit, doc, example) are [`GlobalKey`]'s methods:
/// `GlobalKey::Variant.name()`. Hands the entries to `$callback`, which
/// builds what it needs of them: `Globals` and its defaults, canonical text
/// and record in `globals.rs`; the patch and its `set_key`/`combine`/
/// `given`/`check_ranges` in `globals_patch.rs`; the command line's
/// `SchemeOverrides` in rse-cli; Python's keywords, values and signature in
/// rse-py.
#[macro_export]
macro_rules! for_each_global_key {
    ($callback:ident) => {
        $crate::global_key_table!([$crate::short_global_keys][$callback]);
    };
}

/// The short form of [`for_each_global_key`], made from the whole table.
#[doc(hidden)]
#[macro_export]
macro_rules! short_global_keys {
    ([$callback:ident] $(
        $(#[doc = $what:literal])*
        $variant:ident {
            name: $name:literal,
            field: $field:ident: $ty:ty,
            unit: $unit:expr,
            expects: $expects:literal,
            range: $range:expr,
            example: $example:literal,
            doc: $doc:literal,
            stored: $stored:tt,
            flag: $flag:tt,
        }
    )*) => {
        $callback! {
            $(
                $(#[doc = $what])*
                $variant { $field: $ty, range: $range, stored: $stored, flag: $flag }
            )*
        }
    };
}

/// [`GlobalKey`] from the whole table of [`global_key_table`].
macro_rules! declare_global_key {
    ([] $(
        $(#[doc = $what:literal])*
        $variant:ident {
            name: $name:literal,
            field: $field:ident: $ty:ty,
            unit: $unit:expr,
            expects: $expects:literal,
            range: $range:expr,
            example: $example:literal,
            doc: $doc:literal,
            stored: $stored:tt,
            flag: $flag:tt,
        }
    )*) => {
        /// A `# key: value` global of a scheme file (docs/schemes.md).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum GlobalKey {
            $($(#[doc = $what])* $variant,)*
        }

        impl GlobalKey {
            /// Every key, in the order a scheme file writes them.
            pub const ALL: [GlobalKey; [$(stringify!($variant)),*].len()] =
                [$(GlobalKey::$variant),*];

            /// The key as a scheme file, the editor and Python's keywords
            /// spell it.
            pub const fn name(self) -> &'static str {
                match self {
                    $(GlobalKey::$variant => $name,)*
                }
            }

            /// The unit of its value, where it has one the editor shows.
            pub const fn unit(self) -> Option<&'static str> {
                match self {
                    $(GlobalKey::$variant => $unit,)*
                }
            }

            /// What its text must be, as a parse error says it.
            pub const fn expects(self) -> &'static str {
                match self {
                    $(GlobalKey::$variant => $expects,)*
                }
            }

            /// A value other than the default, as a scheme file writes it
            /// (with pallets on, for the pallet keys): what the tests walk
            /// every key through every skin with.
            pub const fn example(self) -> &'static str {
                match self {
                    $(GlobalKey::$variant => $example,)*
                }
            }

            /// One line of documentation, markdown (backticks for what is
            /// typed), which [`GlobalKey::described`] follows with the
            /// range.
            pub const fn doc(self) -> &'static str {
                match self {
                    $(GlobalKey::$variant => $doc,)*
                }
            }

            /// What its value must be beyond its type, in words (its
            /// table entry's `range`), or `""` where any value of its type
            /// will do.
            pub fn range(self) -> &'static str {
                use $crate::global_range::RangeText as _;
                match self {
                    $(GlobalKey::$variant => $range.describe(),)*
                }
            }

            /// A value outside its range as a scheme file writes it (with
            /// pallets on, for the pallet keys), which every skin must
            /// refuse naming the key; `None` where any value of its type
            /// will do.
            pub fn outside_example(self) -> Option<&'static str> {
                use $crate::global_range::RangeText as _;
                match self {
                    $(GlobalKey::$variant => $range.outside(),)*
                }
            }
        }
    };
}

global_key_table!([declare_global_key] []);

impl GlobalKey {
    /// The key spelt `name` in any case.
    pub fn find(name: &str) -> Option<GlobalKey> {
        GlobalKey::ALL
            .into_iter()
            .find(|key| key.name().eq_ignore_ascii_case(name))
    }
}

impl GlobalKey {
    /// Its documentation line and its range: docs/schemes.md's "value"
    /// column, and without backticks the editor's tooltip.
    pub fn described(self) -> String {
        match self.range() {
            "" => self.doc().to_owned(),
            range => format!("{}; {range}", self.doc()),
        }
    }
}

impl std::fmt::Display for GlobalKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Every key's name, in [`GlobalKey::ALL`] order.
pub const GLOBAL_KEYS: [&str; GlobalKey::ALL.len()] = {
    let mut names = [""; GlobalKey::ALL.len()];
    let mut i = 0;
    while i < names.len() {
        names[i] = GlobalKey::ALL[i].name();
        i += 1;
    }
    names
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_found_in_any_case_and_each_is_one_key() {
        for key in GlobalKey::ALL {
            assert_eq!(GlobalKey::find(key.name()), Some(key));
            assert_eq!(GlobalKey::find(&key.name().to_ascii_uppercase()), Some(key));
        }
        assert_eq!(GlobalKey::find("step-height"), None);
        // Sorted first: `dedup` only drops neighbours.
        let mut names = GLOBAL_KEYS.to_vec();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), GlobalKey::ALL.len());
    }
}
