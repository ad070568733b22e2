//! Rust errors as Python exceptions: `rse.SchemeError` (a `ValueError`
//! carrying file, line, column and field) and `OSError`.

use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    rse,
    SchemeError,
    PyValueError,
    "A scheme that cannot be used: `file`, `line`, `column` and `field` say where (each may be None)."
);

/// `rse.SchemeError` for a core scheme error, with its place as attributes.
pub fn scheme_error(py: Python<'_>, e: &rse_core::SchemeError) -> PyErr {
    let err = SchemeError::new_err(e.to_string());
    let value = err.value(py);
    // Setting attributes on a fresh exception object cannot fail.
    let _ = value.setattr("file", e.file.clone());
    let _ = value.setattr("line", e.line);
    let _ = value.setattr("column", e.column);
    let _ = value.setattr("field", e.field.clone());
    err
}

/// `rse.SchemeError` for a bad keyword argument: the field, no file or line.
pub fn scheme_error_at(py: Python<'_>, field: &str, message: &str) -> PyErr {
    let err = SchemeError::new_err(format!("{field}: {message}"));
    let value = err.value(py);
    let _ = value.setattr("file", py.None());
    let _ = value.setattr("line", py.None());
    let _ = value.setattr("column", py.None());
    let _ = value.setattr("field", field);
    err
}

/// The Python exception for a core error.
pub fn core_error(py: Python<'_>, e: &rse_core::Error) -> PyErr {
    match e {
        rse_core::Error::Scheme(e) => scheme_error(py, e),
        rse_core::Error::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// The Python exception for a world-writing error.
pub fn world_error(py: Python<'_>, e: &rse_world::Error) -> PyErr {
    match e {
        rse_world::Error::Io { source, .. } => PyOSError::new_err(format!("{e}: {source}")),
        rse_world::Error::Core(e) => core_error(py, e),
        _ => PyValueError::new_err(e.to_string()),
    }
}
