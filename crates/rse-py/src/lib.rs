//! Python bindings of rse (`import rse`). A skeleton for now: the module
//! loads and reports its version; the Python issue adds the generator API.

use pyo3::prelude::*;

/// The native part of the `rse` package.
#[pymodule]
fn _rse(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", rse_core::VERSION)?;
    Ok(())
}
