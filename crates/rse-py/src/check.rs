//! `rse.check`: the worlds under some paths verified by `rse_verify`, with
//! the GIL released. The report crosses into Python as the same JSON that
//! `rse-gen check --json` prints; `rse/_check.py` makes it dataclasses.

use pyo3::exceptions::{PyNotADirectoryError, PyOSError, PyValueError};
use pyo3::prelude::*;
use rse_verify::{CheckConfig, CheckConfigError, DiscoverError, check_paths};

use crate::batch::pool;

/// The `check` report of the worlds under `paths`, as JSON text.
#[pyfunction]
#[pyo3(signature = (paths, physics=false, jobs=None, strict=false, template=None, budget=None))]
pub fn _check_json(
    py: Python<'_>,
    paths: Vec<std::path::PathBuf>,
    physics: bool,
    jobs: Option<usize>,
    strict: bool,
    template: Option<std::path::PathBuf>,
    budget: Option<f64>,
) -> PyResult<String> {
    let budget = budget
        .map(rse_verify::Budget::new)
        .transpose()
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let options = CheckConfig {
        physics: Some(physics),
        strict: Some(strict),
        template,
        budget,
    }
    .resolve()
    .map_err(|e| match e {
        CheckConfigError::NoPhysics(why) => PyValueError::new_err(format!("physics=True: {why}")),
        CheckConfigError::Template(e) => PyValueError::new_err(e.to_string()),
    })?;
    let pool = pool(py, jobs)?;
    let report = py
        .detach(|| pool.install(|| check_paths(&paths, &options, &|| {})))
        .map_err(|e| match e {
            DiscoverError::NotAFolder(_) => PyNotADirectoryError::new_err(e.to_string()),
            DiscoverError::Unreadable { .. } => PyOSError::new_err(e.to_string()),
            DiscoverError::PhysicsRefused { world, reason } => {
                PyValueError::new_err(format!("physics=True: {}: {reason}", world.display()))
            }
            _ => PyValueError::new_err(e.to_string()),
        })?;
    serde_json::to_string(&report).map_err(|e| PyValueError::new_err(e.to_string()))
}
