//! Allocations sized by a caller's number, estimated and refused before
//! they are made: a `MemoryError` naming the argument, never an aborted
//! interpreter (`EnvTerrains(scheme, 10**8)` once asked for 15 GB and
//! aborted).

use pyo3::exceptions::PyMemoryError;
use pyo3::prelude::*;

/// Refuses `bytes` for `what` (sized by `argument`) when this machine has
/// less memory available (`MemAvailable`; nothing is refused where it
/// cannot be read).
pub fn fits(argument: &str, bytes: u64, what: impl std::fmt::Display) -> PyResult<()> {
    match rse_world::available_bytes() {
        Some(available) if bytes > available => Err(PyMemoryError::new_err(format!(
            "{argument}: {what} would take {} MiB, but {} MiB of memory are available; ask for less",
            bytes >> 20,
            available >> 20
        ))),
        _ => Ok(()),
    }
}

/// The bytes one terrain of `scheme` holds: its heights (16 bits a cell)
/// and its drawn obstacles, with the Python object around it.
pub fn terrain_bytes(scheme: &rse_core::Scheme) -> u64 {
    let cells = scheme.grid().cells() as u64;
    (std::mem::size_of::<rse_core::Terrain>() as u64 + 64)
        .saturating_add(cells.saturating_mul(2))
        .saturating_add((scheme.obstacles().len() as u64).saturating_mul(64))
}
