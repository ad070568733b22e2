//! Keyword arguments as typed groups (as tokenizers' trainers take
//! theirs): a call's `**options` is read into one struct per group of
//! keywords, each declared once with its field's type and shared by every
//! function that takes it (the world options by `write_worlds`,
//! `write_world` and `Atlas.write`). A keyword no group of the call knows
//! is a `TypeError` naming the call's keywords, as Python's own.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A struct of optional keyword values and its reader: `take` moves the
/// keywords it names out of a call's `**options` (Python `None` is not
/// given), each read by its type's `FromPyObject`; an error names the
/// keyword.
macro_rules! keyword_group {
    (
        $(#[doc = $what:literal])*
        pub struct $group:ident {
            $($(#[doc = $field_doc:literal])* $field:ident: $ty:ty,)*
        }
    ) => {
        $(#[doc = $what])*
        #[derive(Default)]
        pub struct $group {
            $($(#[doc = $field_doc])* pub $field: Option<$ty>,)*
        }

        impl $group {
            /// The keywords, in the order signatures list them.
            pub const NAMES: &'static [&'static str] = &[$(stringify!($field)),*];

            /// The group's keywords in `options`, removed from it.
            pub fn take(options: &::pyo3::Bound<'_, ::pyo3::types::PyDict>) -> ::pyo3::PyResult<Self> {
                use ::pyo3::prelude::*;

                let mut group = $group::default();
                $(if let Some(value) = options.get_item(stringify!($field))? {
                    options.del_item(stringify!($field))?;
                    if !value.is_none() {
                        group.$field = Some(
                            value
                                .extract::<$ty>()
                                .map_err(|e| $crate::keywords::naming(options.py(), stringify!($field), e))?,
                        );
                    }
                })*
                Ok(group)
            }
        }
    };
}

pub(crate) use keyword_group;

/// A copy of a call's `**options` (empty when none were given), for
/// groups to `take` from.
pub fn given<'py>(
    py: Python<'py>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    match options {
        Some(options) => options.copy(),
        None => Ok(PyDict::new(py)),
    }
}

/// `Ok` once the groups have taken every keyword of `options`, else
/// Python's `TypeError` for an unexpected keyword, listing `function`'s.
pub fn none_left(function: &str, options: &Bound<'_, PyDict>, known: &[&[&str]]) -> PyResult<()> {
    let Some((key, _)) = options.iter().next() else {
        return Ok(());
    };
    let names: Vec<&str> = known
        .iter()
        .flat_map(|group| group.iter().copied())
        .collect();
    Err(PyTypeError::new_err(format!(
        "{function}() got an unexpected keyword argument {}: the keywords are {}",
        key.repr()?,
        names.join(", ")
    )))
}

/// `e` of reading keyword `name`: a `TypeError` of Python's own words
/// says which argument, as pyo3's do (`argument 'seed': …`); ours, which
/// start with the keyword, and any other error stay as they are.
pub fn naming(py: Python<'_>, name: &str, e: impl Into<PyErr>) -> PyErr {
    let e = e.into();
    let message = e.value(py).to_string();
    if e.is_instance_of::<PyTypeError>(py) && !message.starts_with(&format!("{name}:")) {
        PyTypeError::new_err(format!("argument '{name}': {message}"))
    } else {
        e
    }
}

/// `inspect.Signature` of a call taking `positional` (required, by
/// position or keyword) then every keyword of `groups` (keyword-only,
/// default `None`: the library's default): what `__signature__` gives a
/// class whose constructor reads `**options`.
pub fn signature(py: Python<'_>, positional: &[&str], groups: &[&[&str]]) -> PyResult<Py<PyAny>> {
    let inspect = py.import("inspect")?;
    let parameter = inspect.getattr("Parameter")?;
    let by_position = parameter.getattr("POSITIONAL_OR_KEYWORD")?;
    let keyword_only = parameter.getattr("KEYWORD_ONLY")?;
    let mut parameters = Vec::new();
    for name in positional {
        parameters.push(parameter.call1((*name, &by_position))?);
    }
    for name in groups.iter().flat_map(|group| group.iter()) {
        let default = PyDict::new(py);
        default.set_item("default", py.None())?;
        parameters.push(parameter.call((*name, &keyword_only), Some(&default))?);
    }
    Ok(inspect.getattr("Signature")?.call1((parameters,))?.unbind())
}
