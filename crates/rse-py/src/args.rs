//! Numbers from Python arguments as a Python user passes them: `int`,
//! `float`, numpy scalars, 0-d arrays, and `(lo, hi)` pairs as tuples,
//! lists or length-2 arrays. A wrong type is a `TypeError` naming the
//! field; a value out of range a `SchemeError` naming it.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyInt, PyString};
use rse_core::Param;

use crate::errors::scheme_error_at;

/// `type(obj).__name__` and `repr(obj)`, for messages.
pub(crate) fn describe(obj: &Bound<'_, PyAny>) -> String {
    let name = obj
        .get_type()
        .name()
        .map_or_else(|_| "?".to_owned(), |n| n.to_string());
    let repr = obj
        .repr()
        .map_or_else(|_| "?".to_owned(), |r| r.to_string());
    format!("{name} {repr}")
}

/// `operator.index(obj)`: the `int` of an integer-like object (Python
/// ints, numpy integers, 0-d integer arrays); `None` for anything else.
/// `bool` is refused: `height=True` is a mistake, not 1 step.
fn integer<'py>(obj: &Bound<'py, PyAny>) -> Option<Bound<'py, PyInt>> {
    if obj.is_instance_of::<PyBool>() {
        return None;
    }
    if let Ok(int) = obj.cast::<PyInt>() {
        return Some(int.clone());
    }
    let index = obj.py().import("operator").ok()?.getattr("index").ok()?;
    index.call1((obj,)).ok()?.cast_into::<PyInt>().ok()
}

/// A real number from anything with `__float__` (floats, ints, numpy
/// scalars, 0-d arrays) but text and `bool` (Python's or numpy's).
pub(crate) fn real(obj: &Bound<'_, PyAny>) -> Option<f64> {
    if is_bool(obj) || is_text(obj) {
        return None;
    }
    obj.extract::<f64>().ok()
}

/// `True`/`False`, as Python's `bool` or numpy's.
fn is_bool(obj: &Bound<'_, PyAny>) -> bool {
    if obj.is_instance_of::<PyBool>() {
        return true;
    }
    let ty = obj.get_type();
    let module = ty.module().map(|m| m.to_string()).unwrap_or_default();
    let name = ty.name().map(|n| n.to_string()).unwrap_or_default();
    module == "numpy" && (name == "bool" || name == "bool_")
}

/// Raw bytes: `bytes`, `bytearray`, or a `memoryview` (of bytes, or of
/// any buffer: its items are read as bytes unless it says otherwise, and
/// a view of `b"\x00\x03"` is not envs 0 and 3). One rule for every
/// buffer Python hands over as bytes.
pub(crate) fn is_raw_bytes(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<PyBytes>()
        || obj.is_instance_of::<pyo3::types::PyByteArray>()
        || obj.is_instance_of::<pyo3::types::PyMemoryView>()
}

fn is_text(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<PyString>() || obj.is_instance_of::<PyBytes>()
}

/// The `N` items of a tuple, list or array of length `N`.
fn items<'py, const N: usize>(obj: &Bound<'py, PyAny>) -> Option<[Bound<'py, PyAny>; N]> {
    if is_text(obj) {
        return None;
    }
    let items: Vec<Bound<'py, PyAny>> = obj.try_iter().ok()?.collect::<PyResult<_>>().ok()?;
    <[Bound<'py, PyAny>; N]>::try_from(items).ok()
}

/// The two items of a `(lo, hi)` pair.
fn pair<'py>(obj: &Bound<'py, PyAny>) -> Option<[Bound<'py, PyAny>; 2]> {
    items(obj)
}

/// `N` real numbers `field` (a tuple, list or array), e.g. an offset
/// `(x, y, z)`; `example` shows the shape in the message.
pub fn reals<const N: usize>(
    field: &str,
    obj: &Bound<'_, PyAny>,
    example: &str,
) -> PyResult<[f64; N]> {
    let wrong = || {
        PyTypeError::new_err(format!(
            "{field}: expected {N} numbers such as {example}, got {}",
            describe(obj)
        ))
    };
    let found = items::<N>(obj).ok_or_else(wrong)?;
    let mut out = [0.0; N];
    for (slot, item) in out.iter_mut().zip(&found) {
        *slot = real(item).ok_or_else(wrong)?;
    }
    Ok(out)
}

/// A whole number of type `T` for `field`, or a `SchemeError` saying the
/// range; `what` names the kind of value for a `TypeError`.
fn whole_value<T>(field: &str, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<T>
where
    T: for<'a, 'py> FromPyObject<'a, 'py> + num_bounds::Bounded,
{
    let Some(int) = integer(obj) else {
        return Err(PyTypeError::new_err(format!(
            "{field}: expected {what}, got {}",
            describe(obj)
        )));
    };
    int.extract::<T>().map_err(|_| {
        scheme_error_at(
            obj.py(),
            field,
            &format!("{int} is not a whole number from 0 to {}", T::MAX),
        )
    })
}

/// Upper bounds of the integer types used, for messages.
mod num_bounds {
    pub trait Bounded: std::fmt::Display {
        const MAX: Self;
    }
    impl Bounded for u16 {
        const MAX: Self = u16::MAX;
    }
    impl Bounded for u32 {
        const MAX: Self = u32::MAX;
    }
    impl Bounded for u64 {
        const MAX: Self = u64::MAX;
    }
}

/// A whole number `field` (`u32`, `u64`…).
pub fn whole<T>(field: &str, obj: &Bound<'_, PyAny>) -> PyResult<T>
where
    T: for<'a, 'py> FromPyObject<'a, 'py> + num_bounds::Bounded,
{
    whole_value(field, obj, "a whole number")
}

/// A real number `field`.
pub fn number(field: &str, obj: &Bound<'_, PyAny>) -> PyResult<f64> {
    real(obj).ok_or_else(|| {
        PyTypeError::new_err(format!("{field}: expected a number, got {}", describe(obj)))
    })
}

/// A `bool` `field`: `True`/`False` or a numpy bool, as pyo3 takes a
/// `bool` argument (not `1` or `"yes"`).
pub fn boolean(field: &str, obj: &Bound<'_, PyAny>) -> PyResult<bool> {
    obj.extract::<bool>().map_err(|_| {
        PyTypeError::new_err(format!(
            "{field}: expected True or False, got {}",
            describe(obj)
        ))
    })
}

/// A pair of whole numbers `field`, such as `size=(10, 10)`.
pub fn whole_pair(field: &str, obj: &Bound<'_, PyAny>) -> PyResult<(u32, u32)> {
    let Some([a, b]) = pair(obj) else {
        return Err(PyTypeError::new_err(format!(
            "{field}: expected a pair of whole numbers such as (10, 10), got {}",
            describe(obj)
        )));
    };
    Ok((whole(field, &a)?, whole(field, &b)?))
}

/// A whole-number obstacle field: a value or a `(lo, hi)` range.
pub fn whole_param(field: &str, obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Param<u32>>> {
    const WHAT: &str = "a whole number or a (lo, hi) pair of them";
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(None);
    };
    if integer(obj).is_some() {
        return Ok(Some(Param::Fixed(whole_value(field, obj, WHAT)?)));
    }
    match pair(obj) {
        Some([lo, hi]) => Ok(Some(Param::Range(
            whole_value(field, &lo, WHAT)?,
            whole_value(field, &hi, WHAT)?,
        ))),
        None => Err(PyTypeError::new_err(format!(
            "{field}: expected {WHAT}, got {}",
            describe(obj)
        ))),
    }
}

/// A real obstacle field: a value or a `(lo, hi)` range.
pub fn real_param(field: &str, obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Param<f64>>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(None);
    };
    let wrong = |o: &Bound<'_, PyAny>| {
        PyTypeError::new_err(format!(
            "{field}: expected a number or a (lo, hi) pair of them, got {}",
            describe(o)
        ))
    };
    if let Some(v) = real(obj) {
        return Ok(Some(Param::Fixed(v)));
    }
    let [lo, hi] = pair(obj).ok_or_else(|| wrong(obj))?;
    Ok(Some(Param::Range(
        real(&lo).ok_or_else(|| wrong(&lo))?,
        real(&hi).ok_or_else(|| wrong(&hi))?,
    )))
}
