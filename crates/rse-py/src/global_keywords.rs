//! Python's keywords for the scheme's global keys, built from rse-core's
//! table (`for_each_global_key!`): each keyword read into the patch and
//! each value given back by its type, and `Scheme`'s signature with the
//! defaults of `Globals::default`. A key added to the table is a keyword
//! here with no edit.

use pyo3::IntoPyObjectExt as _;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rse_core::{Color, GlobalKey, Globals, GlobalsPatch};

use crate::args;
use crate::errors::scheme_error_at;
use crate::keywords::{Parameter, signature_of};

/// A global's value as Python gives and gets it, picked by its type in the
/// table (as rse-core's parser is).
trait PyGlobal: Sized {
    /// The type as `_rse.pyi` writes it (its aliases).
    const PY_TYPE: &'static str;

    /// The patch's value of keyword `name`: `None` when not given (Python
    /// `None` is "not given" but for `pallets`, where it means off).
    fn from_py(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Self>>;

    /// The value as Python gets it.
    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>>;
}

/// `size`: a pair of whole numbers, `(10, 10)`.
impl PyGlobal for [u32; 2] {
    const PY_TYPE: &'static str = "_Pair";

    fn from_py(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Self>> {
        given(value, |v| args::whole_pair(name, v).map(Into::into))
    }

    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        (self[0], self[1]).into_bound_py_any(py)
    }
}

/// `pallets`: a pair, or `None` for off.
impl PyGlobal for Option<[u32; 2]> {
    const PY_TYPE: &'static str = "Optional[_Pair]";

    fn from_py(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Self>> {
        if value.is_none() {
            return Ok(Some(None));
        }
        <[u32; 2]>::from_py(name, value).map(|pair| pair.map(Some))
    }

    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match self {
            None => Ok(py.None().into_bound(py)),
            Some(pair) => pair.to_py(py),
        }
    }
}

impl PyGlobal for u32 {
    const PY_TYPE: &'static str = "_Int";

    fn from_py(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Self>> {
        given(value, |v| args::whole(name, v))
    }

    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.into_bound_py_any(py)
    }
}

impl PyGlobal for u64 {
    const PY_TYPE: &'static str = "_Int";

    fn from_py(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Self>> {
        given(value, |v| args::whole(name, v))
    }

    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.into_bound_py_any(py)
    }
}

impl PyGlobal for bool {
    const PY_TYPE: &'static str = "bool";

    fn from_py(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Self>> {
        given(value, |v| args::boolean(name, v))
    }

    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.into_bound_py_any(py)
    }
}

impl PyGlobal for f64 {
    const PY_TYPE: &'static str = "_Float";

    fn from_py(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Self>> {
        given(value, |v| args::number(name, v))
    }

    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.into_bound_py_any(py)
    }
}

/// `color`: `(r, g, b)`, each 0 to 1, or its scheme-file text
/// (`"0.72 0.58 0.42"`).
impl PyGlobal for Color {
    const PY_TYPE: &'static str = "Union[tuple[_Float, _Float, _Float], str]";

    fn from_py(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Self>> {
        given(value, |v| {
            let color = match v.extract::<String>() {
                Ok(text) => text.parse(),
                Err(_) => Color::new(args::reals::<3>(name, v, "(0.72, 0.58, 0.42)")?),
            };
            color.map_err(|reason| scheme_error_at(v.py(), name, &reason))
        })
    }

    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let [r, g, b] = self.rgb();
        (r, g, b).into_bound_py_any(py)
    }
}

/// `read(value)`, or not given for Python `None`.
fn given<T>(
    value: &Bound<'_, PyAny>,
    read: impl FnOnce(&Bound<'_, PyAny>) -> PyResult<T>,
) -> PyResult<Option<T>> {
    if value.is_none() {
        Ok(None)
    } else {
        read(value).map(Some)
    }
}

/// A patch field's value as Python gets it: `None` when not set.
fn patch_value<'py, T: PyGlobal>(
    py: Python<'py>,
    value: Option<&T>,
) -> PyResult<Bound<'py, PyAny>> {
    match value {
        None => Ok(py.None().into_bound(py)),
        Some(value) => value.to_py(py),
    }
}

/// [`patch`], [`values`] and [`KEYWORDS`] from the table.
macro_rules! declare_keywords {
    ($(
        $(#[doc = $what:literal])*
        $variant:ident { $field:ident: $ty:ty, range: $range:expr, stored: $stored:tt, flag: $flag:tt }
    )*) => {
        /// The global keywords in `given` as core's patch (keys absent or
        /// `None` not given; `pallets=None` is off).
        pub fn patch(given: &Bound<'_, PyDict>) -> PyResult<GlobalsPatch> {
            let mut patch = GlobalsPatch::default();
            $(if let Some(value) = given.get_item(GlobalKey::$variant.name())? {
                patch.$field = <$ty as PyGlobal>::from_py(GlobalKey::$variant.name(), &value)?;
            })*
            Ok(patch)
        }

        /// Each key of `globals` by its keyword, as Python gets it (the
        /// pallet keys `None` with pallets off).
        pub fn values(globals: &Globals, into: &Bound<'_, PyDict>) -> PyResult<()> {
            let py = into.py();
            let patch = globals.as_patch();
            $(into.set_item(GlobalKey::$variant.name(), patch_value(py, patch.$field.as_ref())?)?;)*
            Ok(())
        }

        /// Every keyword's key with its type as `_rse.pyi` writes it, in
        /// the table's order.
        pub const KEYWORDS: &[(GlobalKey, &str)] =
            &[$((GlobalKey::$variant, <$ty as PyGlobal>::PY_TYPE)),*];
    };
}

rse_core::for_each_global_key!(declare_keywords);

/// `Scheme(obstacles=[], *, size=(10, 10), …)`: the constructor's
/// `inspect.Signature`, each global a keyword-only parameter with its
/// default (`Globals::default`).
pub fn scheme_signature(py: Python<'_>) -> PyResult<Py<PyAny>> {
    let defaults = PyDict::new(py);
    values(&Globals::default(), &defaults)?;
    let mut parameters = vec![Parameter::Positional(
        "obstacles",
        Some(PyList::empty(py).into_any()),
    )];
    for &(key, _) in KEYWORDS {
        let name = key.name();
        let default = defaults
            .get_item(name)?
            .unwrap_or_else(|| py.None().into_bound(py));
        parameters.push(Parameter::Keyword(name, default));
    }
    signature_of(py, parameters.into_iter())
}

/// `[(name, type, example, outside), …]`: each global keyword, its type
/// as `_rse.pyi` writes it (for `scripts/python_stubs.py`), an example
/// other than its default and a value outside its range (`None` where any
/// value of its type will do), as a scheme file writes them (the values
/// `tests/python/test_every_option.py` walks it through every skin with).
#[pyfunction]
pub fn _global_keywords() -> Vec<(
    &'static str,
    &'static str,
    &'static str,
    Option<&'static str>,
)> {
    KEYWORDS
        .iter()
        .map(|&(key, py_type)| (key.name(), py_type, key.example(), key.outside_example()))
        .collect()
}
