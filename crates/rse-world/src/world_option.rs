//! The world options a user gives (what a world folder holds: the
//! simulators, the terrain model, the `MuJoCo` collider and its
//! oversample), declared once in one table ([`for_each_world_option`]):
//! [`WorldConfig`](crate::WorldConfig)'s fields, their text and range
//! here; the command line's flags (rse-cli), Python's keywords, their
//! signature and stubs (rse-py), the editor's fields (rse-edit) and
//! docs/worlds.md's table are built from it.

use crate::error::Error;
use crate::record::options::{MeshMode, MujocoCollider, Targets};

/// The world options, declared once: each option's field in
/// [`WorldConfig`](crate::WorldConfig) and type (whose [`OptionValue`]
/// reads its text), range (an `rse_core::global_range` value, checked by
/// [`WorldConfig::resolve`](crate::WorldConfig::resolve) for every front
/// end), the command line's flag (`--flag`, its value's name and help
/// line), its Python type as the stubs write it, its default as text
/// (a test holds it to [`WorldOptions`](crate::WorldOptions)'s default),
/// an example other than the default and a value every front end refuses
/// (the tests walk both through every skin); first, how
/// [`WorldOptions`](crate::WorldOptions) records it in `rse.json`:
/// `record: { field, resolve, serde }` is a field of its own (after the
/// difficulty, in table order), resolved by `given` (the value given, else
/// the default) or by a method of `WorldConfig` in `config.rs`, with its
/// serde attributes (a new option: `default, skip_serializing_if` its
/// default, so worlds written before it keep their bytes); `record: none`
/// is recorded by another's (the oversample, in the collider's).
///
/// Hands the table to `$callback`: `WorldConfig`, its `set`, `check_ranges`
/// and [`WORLD_OPTIONS`] here; `WorldOptions` in `record/options.rs` and
/// `WorldConfig::resolve` in `config.rs`; `WorldFilesArgs` in rse-cli;
/// `WorldKeywords` and the signatures in rse-py. Each consumer matches the
/// attributes it reads, in this order, and skips the rest
/// (`$($rest:tt)*`), so an attribute added last edits only its readers;
/// `record` comes first, so its readers skip all the others. An
/// option of a type these know is added here, used where it acts (the
/// writer, a template) and in the CHANGELOG, and nowhere else
/// (docs/development.md, "Adding a world option").
#[macro_export]
macro_rules! for_each_world_option {
    ($callback:ident) => {
        $callback! {
            /// The simulators; default gazebo.
            targets: $crate::Targets {
                record: { field: targets: $crate::Targets, resolve: given, serde: () },
                range: ::rse_core::global_range::AnyValue,
                flag: "target",
                value_name: "LIST",
                help: "Simulators to write, comma-separated: obj, gazebo, gazebo-classic, webots, mujoco, urdf, usd",
                py_type: "_Targets",
                default: "gazebo",
                example: "obj,mujoco",
                outside: "quake",
            }
            /// The terrain model; default auto.
            mesh: $crate::MeshMode {
                record: { field: mesh: $crate::MeshMode, resolve: given, serde: () },
                range: ::rse_core::global_range::AnyValue,
                flag: "mesh",
                value_name: "auto|single|blocks",
                help: "Terrain model in the simulator files: each target's fastest exact one that holds (auto: boxes for URDF and Gazebo classic, the mesh elsewhere), the single mesh everywhere, or boxes everywhere",
                py_type: "_MeshMode",
                default: "auto",
                example: "blocks",
                outside: "voxels",
            }
            /// The `MuJoCo` collider by name (`boxes`, `hfield`); default
            /// boxes.
            mujoco_collider: $crate::ColliderName {
                // One record with the oversample: absent for boxes, so
                // worlds made before height fields keep their bytes.
                record: {
                    field: mujoco_collider: $crate::MujocoCollider,
                    resolve: resolve_mujoco_collider,
                    serde: (default, skip_serializing_if = "is_default")
                },
                range: ::rse_core::global_range::AnyValue,
                flag: "mujoco-collider",
                value_name: "boxes|hfield",
                help: "MuJoCo collision: the box set (exact), or a height field (mujoco/terrain.bin)",
                py_type: "_MujocoCollider",
                default: "boxes",
                example: "hfield",
                outside: "spheres",
            }
            /// The height field's samples per cell along each axis; only
            /// with `hfield` (default 4 there).
            oversample: u32 {
                // Recorded in `mujoco_collider`.
                record: none,
                range: ::rse_core::global_range::AtLeastOne("sample per cell"),
                flag: "oversample",
                value_name: "K",
                help: "Height field samples per cell along each axis; needs --mujoco-collider hfield",
                py_type: "int",
                default: "4 with hfield",
                example: "2",
                outside: "0",
            }
        }
    };
}

/// A world option's value read from its text (a flag, the editor's field),
/// by its type.
pub trait OptionValue: Sized {
    /// The value of `text`, or why not.
    fn parse_option(text: &str) -> Result<Self, String>;
}

impl OptionValue for Targets {
    fn parse_option(text: &str) -> Result<Self, String> {
        Targets::parse(text).map_err(|e| e.to_string())
    }
}

impl OptionValue for MeshMode {
    fn parse_option(text: &str) -> Result<Self, String> {
        text.trim().parse().map_err(|e: Error| e.to_string())
    }
}

/// A `MuJoCo` collider as a user names it, one of [`MujocoCollider::NAMES`]
/// (its oversample is an option of its own; [`WorldConfig::resolve`]
/// makes the two one [`MujocoCollider`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ColliderName(String);

impl ColliderName {
    /// The name.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl OptionValue for ColliderName {
    fn parse_option(text: &str) -> Result<Self, String> {
        let name = text.trim();
        if MujocoCollider::NAMES.contains(&name) {
            Ok(ColliderName(name.to_owned()))
        } else {
            Err(format!(
                "unknown MuJoCo collider {name:?}: expected {}",
                MujocoCollider::NAMES.join(" or ")
            ))
        }
    }
}

impl OptionValue for u32 {
    fn parse_option(text: &str) -> Result<Self, String> {
        text.trim()
            .parse()
            .map_err(|_| format!("expected a whole number, not {:?}", text.trim()))
    }
}

/// One world option as the front ends show it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WorldOptionInfo {
    /// The option's name: `WorldConfig`'s field, Python's keyword, the
    /// editor's field and `rse.json`'s.
    pub name: &'static str,
    /// The command line's flag, without its `--`.
    pub flag: &'static str,
    /// What the flag's value is called in the help.
    pub value_name: &'static str,
    /// One line of help (the flag's, the editor's tooltip, the docs').
    pub help: &'static str,
    /// Its type as `_rse.pyi` writes it.
    pub py_type: &'static str,
    /// Its default, as text.
    pub default: &'static str,
    /// A value other than the default.
    pub example: &'static str,
    /// A value every front end refuses.
    pub outside: &'static str,
}

/// The text a range refuses, or why not.
fn in_range<T>(
    option: &'static str,
    value: &T,
    range: &impl rse_core::global_range::GlobalRange<T>,
) -> Result<(), Error> {
    range.check(value).map_err(|reason| Error::BadOption {
        option,
        message: format!("{option} {reason}"),
    })
}

/// `WorldConfig` (but its difficulty, which [`crate::config`] adds) and
/// [`WORLD_OPTIONS`] from the table.
macro_rules! declare_world_config {
    ($(
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty {
            record: $record:tt,
            range: $range:expr,
            flag: $flag:literal,
            value_name: $value_name:literal,
            help: $help:literal,
            py_type: $py_type:literal,
            default: $default:literal,
            example: $example:literal,
            outside: $outside:literal,
            $($rest:tt)*
        }
    )*) => {
        /// What a world folder holds, as given: `None` is the default.
        #[derive(Debug, Clone, Default, PartialEq)]
        pub struct WorldConfig {
            /// The difficulty (validated where the user's number is read,
            /// by [`Difficulty`](rse_core::Difficulty)'s own parser);
            /// default [`Difficulty::FULL`](rse_core::Difficulty::FULL).
            pub difficulty: Option<rse_core::Difficulty>,
            $($(#[doc = $what])* pub $field: Option<$ty>,)*
        }

        impl WorldConfig {
            /// Sets the option `name` from its text (the editor's fields);
            /// an unknown name or a bad text is an error naming it.
            pub fn set(&mut self, name: &str, text: &str) -> Result<(), Error> {
                match name {
                    $(stringify!($field) => {
                        let value = <$ty as OptionValue>::parse_option(text).map_err(|message| Error::BadOption {
                            option: stringify!($field),
                            message: format!("{}: {message}", stringify!($field)),
                        })?;
                        in_range(stringify!($field), &value, &$range)?;
                        self.$field = Some(value);
                        Ok(())
                    })*
                    _ => Err(Error::BadOption {
                        option: "world option",
                        message: format!("unknown world option {name:?}: expected one of {}", [$(stringify!($field)),*].join(", ")),
                    }),
                }
            }

            /// Each option given in its range (the table's `range`): what
            /// every front end's values pass through in
            /// [`resolve`](WorldConfig::resolve).
            pub(crate) fn check_ranges(&self) -> Result<(), Error> {
                $(if let Some(value) = &self.$field {
                    in_range(stringify!($field), value, &$range)?;
                })*
                Ok(())
            }
        }

        /// Every world option, in the table's order.
        pub const WORLD_OPTIONS: &[WorldOptionInfo] = &[$(WorldOptionInfo {
            name: stringify!($field),
            flag: $flag,
            value_name: $value_name,
            help: $help,
            py_type: $py_type,
            default: $default,
            example: $example,
            outside: $outside,
        }),*];
    };
}

for_each_world_option!(declare_world_config);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::WorldOptions;

    fn default_of(name: &str) -> &'static str {
        WORLD_OPTIONS
            .iter()
            .find(|o| o.name == name)
            .map_or("", |o| o.default)
    }

    /// Each default the table says is the library's, each example is read
    /// and differs from it, and each outside value is refused by `set`
    /// (or, for an oversample, by `resolve`), naming the option.
    #[test]
    fn the_tables_defaults_examples_and_outside_values_hold() {
        let defaults = WorldOptions::default();
        assert_eq!(default_of("targets"), defaults.targets.to_string());
        assert_eq!(default_of("mesh"), defaults.mesh.name());
        assert_eq!(
            default_of("mujoco_collider"),
            defaults.mujoco_collider.name()
        );
        assert_eq!(
            default_of("oversample"),
            format!("{} with hfield", rse_core::DEFAULT_OVERSAMPLE)
        );
        for option in WORLD_OPTIONS {
            let mut config = WorldConfig::default();
            config.set(option.name, option.example).unwrap();
            assert_ne!(config, WorldConfig::default(), "{}", option.name);
            let refused = WorldConfig::default()
                .set(option.name, option.outside)
                .unwrap_err();
            assert!(refused.to_string().contains(option.name), "{refused}");
        }
        assert!(WorldConfig::default().set("colour", "red").is_err());
    }

    /// docs/worlds.md's table of world options is this table's
    /// (`RSE_UPDATE_DOCS=1` rewrites it).
    #[test]
    fn the_docs_table_of_world_options_is_the_tables() {
        use std::fmt::Write as _;

        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/worlds.md");
        let docs = std::fs::read_to_string(path).unwrap();
        let header = "| option | flag | value | default |\n|---|---|---|---|\n";
        let start = docs
            .find(header)
            .expect("docs/worlds.md has its table of world options")
            + header.len();
        let end = start + docs[start..].find("\n\n").unwrap_or(0) + 1;
        let end = end.min(docs.len()).max(start);
        let mut rows = String::new();
        for o in WORLD_OPTIONS {
            writeln!(
                rows,
                "| `{}` | `--{} {}` | {} | `{}` |",
                // A `|` would end the cell.
                o.name,
                o.flag,
                o.value_name.replace('|', "\\|"),
                o.help,
                o.default
            )
            .unwrap();
        }
        if docs[start..end] != rows {
            if std::env::var_os("RSE_UPDATE_DOCS").is_some() {
                std::fs::write(path, format!("{}{rows}{}", &docs[..start], &docs[end..])).unwrap();
            } else {
                panic!(
                    "docs/worlds.md's table of world options is not rse-world's: rerun with RSE_UPDATE_DOCS=1\n{rows}"
                );
            }
        }
    }
}
