//! What a user asks of [`EnvTerrains`](super::EnvTerrains): every setting
//! but the number of environments optional, resolved and validated here,
//! once, against the scheme and the library's defaults. The Python class,
//! the framework adapters and any other front end pass what their user
//! gave and `None` for the rest, so a default lives in one place.

use std::str::FromStr;

use super::options::{EnvError, EnvLayout, EnvOptions, bad};
use crate::difficulty::Difficulty;
use crate::scheme::Scheme;
use crate::spawn::DEFAULT_SPAWN_RADIUS;

/// Height-field samples per cell along each axis of an environment's field
/// when the user names none. Lower than a world file's
/// [`DEFAULT_OVERSAMPLE`](crate::DEFAULT_OVERSAMPLE) (4): a pool holds
/// thousands of fields (4096 envs of 80×80 cells are 400 MiB at 2, 1.6 GiB
/// at 4) and is rewritten every reset, while a step edge is still within
/// a quarter block of where it is.
pub const DEFAULT_ENV_OVERSAMPLE: u32 = 2;

/// The two layouts by name, as a user picks one (`"slots"`, `"tiles"`);
/// [`EnvLayout`] is the resolved layout with its tile columns and border.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LayoutKind {
    /// One height field per environment.
    #[default]
    Slots,
    /// One shared field of tiles.
    Tiles,
}

impl LayoutKind {
    /// The name a user writes.
    pub fn name(self) -> &'static str {
        match self {
            LayoutKind::Slots => "slots",
            LayoutKind::Tiles => "tiles",
        }
    }
}

impl FromStr for LayoutKind {
    type Err = EnvError;

    fn from_str(text: &str) -> Result<Self, EnvError> {
        match text {
            "slots" => Ok(LayoutKind::Slots),
            "tiles" => Ok(LayoutKind::Tiles),
            other => Err(bad(
                "layout",
                format!("{other:?} is not \"slots\" or \"tiles\""),
            )),
        }
    }
}

impl From<EnvLayout> for LayoutKind {
    fn from(layout: EnvLayout) -> Self {
        match layout {
            EnvLayout::Slots => LayoutKind::Slots,
            EnvLayout::Tiles { .. } => LayoutKind::Tiles,
        }
    }
}

/// The per-environment options, declared once: each option's field in
/// [`EnvRequest`] and type, its range (a [`global_range`](crate::global_range)
/// value, checked by [`EnvRequest::check_ranges`] for every front end and
/// by [`EnvTerrains::mixed`](super::EnvTerrains::mixed) for options built
/// by hand), its default as text, an example other than the default, a
/// value outside its range (the tests walk both through every skin), and
/// what it needs beside it (the tile options: `layout=tiles`).
///
/// Hands the table to `$callback`: [`EnvRequest`], its `check_ranges` and
/// [`ENV_OPTIONS`] here; Python's `EnvTerrains` keywords, their signature
/// and their mapping in rse-py. An option of a type these know is added
/// here, resolved in [`EnvRequest::resolve`] and used where it acts
/// (docs/development.md, "Adding a per-env option").
#[macro_export]
macro_rules! for_each_env_option {
    ($callback:ident) => {
        $callback! {
            /// Samples per cell along each axis; default
            /// [`DEFAULT_ENV_OVERSAMPLE`](crate::DEFAULT_ENV_OVERSAMPLE).
            oversample: u32 {
                range: $crate::global_range::AtLeastOne("sample per cell"),
                default: "2",
                example: "3",
                outside: Some("0"),
                needs: "",
            }
            /// Base seed; default the scheme's `# seed:`.
            seed: u64 {
                range: $crate::global_range::AnyValue,
                default: "the scheme's",
                example: "7",
                outside: None,
                needs: "",
            }
            /// Global id of environment 0; default 0.
            env_offset: u64 {
                range: $crate::global_range::AnyValue,
                default: "0",
                example: "16",
                outside: None,
                needs: "",
            }
            /// Starting difficulty of every environment (checked where the
            /// user's number is read, by [`Difficulty`](crate::Difficulty)'s
            /// own constructor); default 1.
            difficulty: $crate::Difficulty {
                range: $crate::global_range::CheckedByType { describe: "0 to 1", outside: "1.5" },
                default: "1",
                example: "0.5",
                outside: Some("1.5"),
                needs: "",
            }
            /// Slots or tiles; default slots.
            layout: $crate::LayoutKind {
                range: $crate::global_range::CheckedByType { describe: "slots or tiles", outside: "rows" },
                default: "slots",
                example: "tiles",
                outside: Some("rows"),
                needs: "",
            }
            /// Tiles along x (tiles only); default `ceil(sqrt(num_envs))`.
            cols: u32 {
                range: $crate::global_range::AtLeastOne("tile along x"),
                default: "ceil(sqrt(num_envs))",
                example: "2",
                outside: Some("0"),
                needs: "layout=tiles",
            }
            /// Cells of height 0 between and around tiles (tiles only);
            /// default 0.
            border: u32 {
                range: $crate::global_range::AnyValue,
                default: "0",
                example: "1",
                outside: None,
                needs: "layout=tiles",
            }
            /// Radius of the disc under a spawn origin, metres; default
            /// [`DEFAULT_SPAWN_RADIUS`](crate::spawn::DEFAULT_SPAWN_RADIUS).
            spawn_radius: f64 {
                range: $crate::spawn::Radius,
                default: "0.3",
                example: "0.5",
                outside: Some("-1"),
                needs: "",
            }
        }
    };
}

/// One per-environment option as the front ends show it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EnvOptionInfo {
    /// The option's name: [`EnvRequest`]'s field, Python's keyword.
    pub name: &'static str,
    /// Its default, as text.
    pub default: &'static str,
    /// A value other than the default.
    pub example: &'static str,
    /// A value every front end refuses, where there is one.
    pub outside: Option<&'static str>,
    /// What it needs beside it (`layout=tiles`), or `""`.
    pub needs: &'static str,
}

/// [`EnvRequest`], its range check and [`ENV_OPTIONS`] from the table.
macro_rules! declare_env_request {
    ($(
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty {
            range: $range:expr,
            default: $default:literal,
            example: $example:literal,
            outside: $outside:expr,
            needs: $needs:literal,
        }
    )*) => {
        /// The environments a user asks for: `None` is "the default".
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        pub struct EnvRequest {
            /// How many environments.
            pub num_envs: usize,
            $($(#[doc = $what])* pub $field: Option<$ty>,)*
        }

        impl EnvRequest {
            /// Each option given in its range (the table's `range`), the
            /// first outside it an error naming it.
            pub fn check_ranges(&self) -> Result<(), EnvError> {
                use $crate::global_range::GlobalRange as _;
                $(if let Some(value) = &self.$field {
                    $range.check(value).map_err(|reason| bad(stringify!($field), reason))?;
                })*
                Ok(())
            }
        }

        /// Every per-environment option, in the table's order.
        pub const ENV_OPTIONS: &[EnvOptionInfo] = &[$(EnvOptionInfo {
            name: stringify!($field),
            default: $default,
            example: $example,
            outside: $outside,
            needs: $needs,
        }),*];
    };
}

for_each_env_option!(declare_env_request);

impl EnvRequest {
    /// The options of [`EnvTerrains::new`](super::EnvTerrains::new) for
    /// `scheme`, every unset field given its default. Refused, naming the
    /// argument: `cols` or `border` with slots.
    /// The rest (counts, sizes, the radius) is checked by `EnvTerrains::new`.
    pub fn resolve(&self, scheme: &Scheme) -> Result<EnvOptions, EnvError> {
        self.check_ranges()?;
        let layout = match self.layout.unwrap_or_default() {
            // A border of 0 is the slots' own (no border): as before,
            // only a real tile setting is refused.
            LayoutKind::Slots if self.cols.is_some() || self.border.is_some_and(|b| b > 0) => {
                return Err(bad("cols, border", "only with layout=\"tiles\""));
            }
            LayoutKind::Slots => EnvLayout::Slots,
            LayoutKind::Tiles => EnvLayout::Tiles {
                cols: self
                    .cols
                    .unwrap_or_else(|| (self.num_envs as f64).sqrt().ceil() as u32),
                border: self.border.unwrap_or(0),
            },
        };
        let difficulty = self.difficulty.unwrap_or(Difficulty::FULL);
        Ok(EnvOptions {
            num_envs: self.num_envs,
            oversample: self.oversample.unwrap_or(DEFAULT_ENV_OVERSAMPLE),
            seed: scheme.seed_or(self.seed),
            env_offset: self.env_offset.unwrap_or(0),
            layout,
            difficulty,
            spawn_radius: self.spawn_radius.unwrap_or(DEFAULT_SPAWN_RADIUS),
        })
    }
}

impl EnvRequest {
    /// Every option `options` resolved to, given: what
    /// [`EnvTerrains::mixed`](super::EnvTerrains::mixed) checks the ranges
    /// of, whoever built the options.
    pub fn given(options: &EnvOptions) -> EnvRequest {
        let EnvOptions {
            num_envs,
            oversample,
            seed,
            env_offset,
            layout,
            difficulty,
            spawn_radius,
        } = *options;
        let (cols, border) = match layout {
            EnvLayout::Slots => (None, None),
            EnvLayout::Tiles { cols, border } => (Some(cols), Some(border)),
        };
        EnvRequest {
            num_envs,
            oversample: Some(oversample),
            seed: Some(seed),
            env_offset: Some(env_offset),
            difficulty: Some(difficulty),
            layout: Some(layout.into()),
            cols,
            border,
            spawn_radius: Some(spawn_radius),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scheme(seed: u64) -> Scheme {
        Scheme::from_csv(
            &format!("# size: 8x6\n# seed: {seed}\ntype,height\nrandom,2\n"),
            None,
        )
        .unwrap()
    }

    #[test]
    fn unset_fields_take_the_library_defaults_and_the_scheme_seed() {
        let options = EnvRequest {
            num_envs: 10,
            ..EnvRequest::default()
        }
        .resolve(&scheme(77))
        .unwrap();
        assert_eq!(options.seed, 77, "the scheme's # seed: rules");
        assert_eq!(options.oversample, DEFAULT_ENV_OVERSAMPLE);
        assert_eq!(
            options.spawn_radius.to_bits(),
            DEFAULT_SPAWN_RADIUS.to_bits()
        );
        assert_eq!(options.layout, EnvLayout::Slots);
        assert_eq!(options.difficulty, Difficulty::FULL);
        assert_eq!(options.env_offset, 0);
    }

    #[test]
    fn given_fields_win_and_tiles_get_a_square_by_default() {
        let request = EnvRequest {
            num_envs: 10,
            seed: Some(3),
            difficulty: Some(Difficulty::new(0.25).unwrap()),
            layout: Some(LayoutKind::Tiles),
            ..EnvRequest::default()
        };
        let options = request.resolve(&scheme(77)).unwrap();
        assert_eq!(options.seed, 3);
        assert_eq!(options.difficulty, Difficulty::new(0.25).unwrap());
        assert_eq!(options.layout, EnvLayout::Tiles { cols: 4, border: 0 });
    }

    #[test]
    fn refusals_name_the_argument() {
        let refused = |request: EnvRequest| request.resolve(&scheme(0)).unwrap_err().to_string();
        let base = EnvRequest {
            num_envs: 4,
            ..EnvRequest::default()
        };
        assert!(
            refused(EnvRequest {
                border: Some(1),
                ..base
            })
            .starts_with("cols, border: ")
        );
        let no_border = EnvRequest {
            border: Some(0),
            ..base
        };
        assert_eq!(
            no_border.resolve(&scheme(0)).unwrap().layout,
            EnvLayout::Slots
        );
        let layout: Result<LayoutKind, _> = "grid".parse();
        assert_eq!(
            layout.unwrap_err().to_string(),
            "layout: \"grid\" is not \"slots\" or \"tiles\""
        );
    }
}
