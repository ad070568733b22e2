//! World options as Python passes them: each keyword's value turned into
//! its text by the option's type (a list of targets joined, an int
//! written out; any other Python type a `TypeError` naming it), then read
//! by rse-world's own table (`WorldConfig::set`): the same parser and
//! range as the flags and the editor, so Python writes no option name,
//! parser or default of its own. `None` means the library's default.

use std::marker::PhantomData;

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyString;
use rse_core::Difficulty;
use rse_world::{ColliderName, MeshMode, Targets, WorldConfig, WorldOptions};

use crate::args::describe;
use crate::errors::world_error;
use crate::keywords::keyword_group;

/// The text of a world option of type `T` as Python gave it, for
/// [`WorldConfig::set`].
pub struct OptionText<T> {
    text: String,
    of: PhantomData<T>,
}

impl<T> OptionText<T> {
    fn new(text: String) -> Self {
        OptionText {
            text,
            of: PhantomData,
        }
    }
}

/// `targets=`: `"gazebo,mujoco"`, or a sequence of names
/// (`["gazebo", "mujoco"]`).
impl<'a, 'py> FromPyObject<'a, 'py> for OptionText<Targets> {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if obj.is_instance_of::<PyString>() {
            return obj.extract::<String>().map(OptionText::new);
        }
        let names: Vec<String> = obj.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "targets: expected a comma-separated string or a list of target names, got {}",
                describe(&obj)
            ))
        })?;
        Ok(OptionText::new(names.join(",")))
    }
}

/// `mesh=`: `"auto"`, `"single"` or `"blocks"`.
impl<'a, 'py> FromPyObject<'a, 'py> for OptionText<MeshMode> {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        string(obj, "mesh").map(OptionText::new)
    }
}

/// `mujoco_collider=`: `"boxes"` or `"hfield"` (its oversample is a
/// keyword of its own).
impl<'a, 'py> FromPyObject<'a, 'py> for OptionText<ColliderName> {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        string(obj, "mujoco_collider").map(OptionText::new)
    }
}

/// A whole number (`oversample=`): a Python int of any size, written out,
/// so the option's own parser names it when it is out of range.
impl<'a, 'py> FromPyObject<'a, 'py> for OptionText<u32> {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if !obj.is_instance_of::<pyo3::types::PyInt>()
            || obj.is_instance_of::<pyo3::types::PyBool>()
        {
            return Err(PyTypeError::new_err(format!(
                "expected an int, got {}",
                describe(&obj)
            )));
        }
        Ok(OptionText::new(obj.str()?.to_string()))
    }
}

/// `layout=` of `EnvTerrains`: `"slots"` or `"tiles"`, parsed by rse-core's
/// [`rse_core::LayoutKind`].
pub struct PyLayout(pub rse_core::LayoutKind);

impl<'a, 'py> FromPyObject<'a, 'py> for PyLayout {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let text = string(obj, "layout")?;
        text.parse()
            .map(PyLayout)
            .map_err(|e: rse_core::EnvError| pyo3::exceptions::PyValueError::new_err(e.to_string()))
    }
}

/// The text of a keyword that takes a name, or a `TypeError` naming it.
fn string(obj: Borrowed<'_, '_, PyAny>, keyword: &str) -> PyResult<String> {
    if !obj.is_instance_of::<PyString>() {
        return Err(PyTypeError::new_err(format!(
            "{keyword}: expected a string, got {}",
            describe(&obj)
        )));
    }
    obj.extract::<String>()
}

/// `WorldKeywords` (the world options of rse-world's table, then the
/// writer's own `template` and `force`) and its `config`.
macro_rules! world_keywords {
    ($(
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty { $($entry:tt)* }
    )*) => {
        keyword_group! {
            /// What every writer of world folders takes (`write_worlds`,
            /// `write_world`, `Atlas.write`): what the folder holds and how
            /// it is written. `None` is the library's default.
            pub struct WorldKeywords {
                $($(#[doc = $what])* $field: OptionText<$ty>,)*
                /// `template=`: a folder overlaying our templates.
                template: std::path::PathBuf,
                /// `force=`: replace a different folder.
                force: bool,
            }
        }

        impl WorldKeywords {
            /// What these give a world folder of `difficulty` (`None`: the
            /// batch's): what the user gave, each read by rse-world's table
            /// (`WorldConfig::set`: parser and range, an error naming the
            /// option), `None` for the rest.
            pub fn config(&self, py: Python<'_>, difficulty: Option<Difficulty>) -> PyResult<WorldConfig> {
                let WorldKeywords { $($field,)* template: _, force: _ } = self;
                let mut config = WorldConfig {
                    difficulty,
                    ..WorldConfig::default()
                };
                $(if let Some(given) = $field {
                    config
                        .set(stringify!($field), &given.text)
                        .map_err(|e| world_error(py, &e))?;
                })*
                Ok(config)
            }
        }
    };
}

rse_world::for_each_world_option!(world_keywords);

/// The keywords of `WorldKeywords` as a text signature writes them
/// (`targets=None, …, force=None`), a string literal from the table:
/// `rse_world::for_each_world_option!(world_keywords_text)` inside a
/// `concat!` of a docstring's signature.
macro_rules! world_keywords_text {
    ($(
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty { $($entry:tt)* }
    )*) => {
        concat!($(stringify!($field), "=None, ",)* "template=None, force=None")
    };
}

pub(crate) use world_keywords_text;

/// `[(name, type, example, outside), …]`: each world option's keyword, its
/// type as `_rse.pyi` writes it (for `scripts/python_stubs.py`), a value
/// other than its default and one every writer refuses (what
/// `tests/python/test_every_option.py` walks through every skin), from
/// rse-world's table.
#[pyfunction]
pub fn _world_keywords() -> Vec<(&'static str, &'static str, &'static str, &'static str)> {
    rse_world::WORLD_OPTIONS
        .iter()
        .map(|o| (o.name, o.py_type, o.example, o.outside))
        .collect()
}

impl WorldKeywords {
    /// The world options these give a folder of `difficulty`.
    pub fn options(&self, py: Python<'_>, difficulty: Difficulty) -> PyResult<WorldOptions> {
        self.config(py, Some(difficulty))?
            .resolve()
            .map_err(|e| world_error(py, &e))
    }
}
