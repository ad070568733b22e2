//! Keyword arguments as typed groups (as tokenizers' trainers take
//! theirs): a call's `**options` is read into one struct per group of
//! keywords, each declared once with its field's type and shared by every
//! function that takes it (the world options by `write_worlds`,
//! `write_world` and `Atlas.write`). A keyword no group of the call knows
//! is a `TypeError` naming the call's keywords, as Python's own.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A struct of optional keyword values and its [`KeywordGroup`] reader:
/// `take` moves the keywords it names out of a call's `**options` (Python
/// `None` is not given), each read by its type's `FromPyObject`; an error
/// names the keyword.
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

        impl $crate::keywords::KeywordGroup for $group {
            const NAMES: &'static [&'static str] = &[$(stringify!($field)),*];

            fn take(options: &::pyo3::Bound<'_, ::pyo3::types::PyDict>) -> ::pyo3::PyResult<Self> {
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

/// What `keyword_group!` declares: the group's keywords and its reader.
pub trait KeywordGroup: Sized {
    /// The keywords, in the order signatures list them.
    const NAMES: &'static [&'static str];

    /// The group's keywords in `options`, removed from it.
    fn take(options: &Bound<'_, PyDict>) -> PyResult<Self>;
}

/// Group `G` from a call `function` whose keywords are `G`'s alone; any
/// other keyword is Python's `TypeError`.
pub fn read<G: KeywordGroup>(
    py: Python<'_>,
    function: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<G> {
    let given = given(py, options)?;
    let group = G::take(&given)?;
    none_left(function, &given, &[G::NAMES])?;
    Ok(group)
}

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
    match options.iter().next() {
        None => Ok(()),
        Some((key, _)) => Err(unexpected(
            function,
            &key,
            known.iter().flat_map(|group| group.iter().copied()),
        )?),
    }
}

/// `Ok` when every key of `given` is one of `known`, else Python's
/// `TypeError` for an unexpected keyword, listing `function`'s.
pub fn only_known<'a>(
    function: &str,
    given: &Bound<'_, PyDict>,
    known: impl Iterator<Item = &'a str> + Clone,
) -> PyResult<()> {
    for key in given.keys() {
        let name = key.extract::<String>().unwrap_or_default();
        if !known.clone().any(|k| k == name) {
            return Err(unexpected(function, &key, known)?);
        }
    }
    Ok(())
}

/// Python's `TypeError` for keyword `key` in a call of `function`, which
/// takes `names`: the one message every call of the extension gives.
pub fn unexpected<'a>(
    function: &str,
    key: &Bound<'_, PyAny>,
    names: impl Iterator<Item = &'a str>,
) -> PyResult<PyErr> {
    let names: Vec<&str> = names.collect();
    Ok(PyTypeError::new_err(format!(
        "{function}() got an unexpected keyword argument {}: the keywords are {}",
        key.repr()?,
        names.join(", ")
    )))
}

/// `e` of reading keyword `name`: a `TypeError` of Python's own words
/// says which argument, as pyo3's do (`argument 'seed': …`); an int out of
/// a whole number's range (`OverflowError`) is a `ValueError` naming it;
/// ours, which start with the keyword, and any other error stay as they
/// are.
pub fn naming(py: Python<'_>, name: &str, e: impl Into<PyErr>) -> PyErr {
    let e = e.into();
    let message = e.value(py).to_string();
    if message.starts_with(&format!("{name}:")) {
        e
    } else if e.is_instance_of::<PyTypeError>(py) {
        PyTypeError::new_err(format!("argument '{name}': {message}"))
    } else if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(py) {
        // A negative or huge int for a whole number: said as a value.
        pyo3::exceptions::PyValueError::new_err(format!("{name}: {message}"))
    } else {
        e
    }
}

/// `inspect.Signature` of a call taking `positional` (required, by
/// position or keyword) then every keyword of `groups` (keyword-only,
/// default `None`: the library's default): what `__signature__` gives a
/// class whose constructor reads `**options`.
pub fn signature(py: Python<'_>, positional: &[&str], groups: &[&[&str]]) -> PyResult<Py<PyAny>> {
    let required = positional
        .iter()
        .map(|&name| Parameter::Positional(name, None));
    let keywords = groups
        .iter()
        .flat_map(|group| group.iter())
        .map(|&name| Parameter::Keyword(name, py.None().into_bound(py)));
    signature_of(py, required.chain(keywords))
}

/// One parameter of a signature: by position or keyword (with its default,
/// or required), or keyword-only with its default.
pub enum Parameter<'a, 'py> {
    /// By position or keyword; `None`: required.
    Positional(&'a str, Option<Bound<'py, PyAny>>),
    /// Keyword-only, with its default.
    Keyword(&'a str, Bound<'py, PyAny>),
}

/// `inspect.Signature` of `parameters`, in order.
pub fn signature_of<'a, 'py>(
    py: Python<'py>,
    parameters: impl Iterator<Item = Parameter<'a, 'py>>,
) -> PyResult<Py<PyAny>> {
    let inspect = py.import("inspect")?;
    let parameter = inspect.getattr("Parameter")?;
    let mut built = Vec::new();
    for p in parameters {
        let (name, kind, default) = match p {
            Parameter::Positional(name, default) => (name, "POSITIONAL_OR_KEYWORD", default),
            Parameter::Keyword(name, default) => (name, "KEYWORD_ONLY", Some(default)),
        };
        let options = PyDict::new(py);
        if let Some(default) = default {
            options.set_item("default", default)?;
        }
        built.push(parameter.call((name, parameter.getattr(kind)?), Some(&options))?);
    }
    Ok(inspect.getattr("Signature")?.call1((built,))?.unbind())
}
