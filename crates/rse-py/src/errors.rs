//! Rust errors as Python exceptions: `rse.SchemeError` (a `ValueError`
//! carrying file, line, column and field), `rse.ShardBusyError` and
//! `OSError`.

use pyo3::exceptions::{PyFileExistsError, PyOSError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    rse,
    SchemeError,
    PyValueError,
    "A scheme that cannot be used: `file`, `line`, `column` and `field` say where (each may be None)."
);

pyo3::create_exception!(
    rse,
    ShardBusyError,
    PyValueError,
    "Another live run holds this shard of this output folder (its lock): retry once it has ended, and the rerun skips every world it wrote."
);

/// `rse.SchemeError` with `message` and its place as attributes.
fn placed(
    py: Python<'_>,
    message: String,
    (file, line, column, field): (Option<&str>, Option<u64>, Option<u64>, Option<&str>),
) -> PyErr {
    let err = SchemeError::new_err(message);
    let value = err.value(py);
    // Setting attributes on a fresh exception object cannot fail.
    let _ = value.setattr("file", file);
    let _ = value.setattr("line", line);
    let _ = value.setattr("column", column);
    let _ = value.setattr("field", field);
    err
}

/// `rse.SchemeError` for a core scheme error, with its place.
pub fn scheme_error(py: Python<'_>, e: &rse_core::SchemeError) -> PyErr {
    let place = (e.file.as_deref(), e.line, e.column, e.field.as_deref());
    placed(py, e.to_string(), place)
}

/// `rse.SchemeError` for a bad keyword argument: the field, no file or line.
pub fn scheme_error_at(py: Python<'_>, field: &str, message: &str) -> PyErr {
    placed(
        py,
        format!("{field}: {message}"),
        (None, None, None, Some(field)),
    )
}

/// The Python exception for a core error.
pub fn core_error(py: Python<'_>, e: &rse_core::Error) -> PyErr {
    match e {
        rse_core::Error::Scheme(e) => scheme_error(py, e),
        rse_core::Error::Io { source, .. } => PyOSError::new_err(format!("{e}: {source}")),
        rse_core::Error::PreviewTooLarge { .. } => {
            PyValueError::new_err(format!("{e}: pass a smaller cell_pixels"))
        }
        rse_core::Error::SheetTooLarge { .. } => {
            PyValueError::new_err(format!("{e}: pass a smaller cols or cell_pixels"))
        }
        _ => PyValueError::new_err(error_chain(e)),
    }
}

/// `e` and its causes, `: `-separated, as the CLI prints them.
fn error_chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        text.push_str(": ");
        text.push_str(&c.to_string());
        cause = c.source();
    }
    text
}

/// The Python exception for an atlas that cannot be laid out: schemes
/// that cannot sit side by side are a `SchemeError` naming the field; a bad
/// argument a `ValueError` naming it.
pub fn atlas_error(py: Python<'_>, e: &rse_core::AtlasError) -> PyErr {
    match e {
        rse_core::AtlasError::Mismatch { field, .. } => {
            placed(py, e.to_string(), (None, None, None, Some(field)))
        }
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// The Python exception for a world-writing error, with the keyword that
/// fixes it where there is one.
pub fn world_error(py: Python<'_>, e: &rse_world::Error) -> PyErr {
    match e {
        rse_world::Error::Conflict { .. } => {
            PyFileExistsError::new_err(format!("{e}; pass force=True to replace it"))
        }
        rse_world::Error::Io { source, .. } => PyOSError::new_err(format!("{e}: {source}")),
        rse_world::Error::Busy { .. } => ShardBusyError::new_err(e.to_string()),
        rse_world::Error::Core(e) => core_error(py, e),
        rse_world::Error::Atlas(e) => atlas_error(py, e),
        rse_world::Error::AtlasMismatch { field, .. } => {
            placed(py, e.to_string(), (None, None, None, Some(field)))
        }
        _ => PyValueError::new_err(error_chain(e)),
    }
}
