//! `rse.scheme_mix`: which scheme of a mix each environment draws
//! (rse-core's `SchemeMix`), for the framework adapters and `rse-gen
//! contact-sheet` alike.

use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The scheme (an index into `proportions`) that each of `num_envs`
/// environments draws, global ids `env_offset` on, base seed `seed`: each
/// scheme's share is its proportion of their sum; an environment's draw
/// depends on its global id and the seed alone (docs/envs.md).
#[pyfunction]
#[pyo3(signature = (proportions, num_envs, seed, env_offset=0))]
pub fn scheme_mix(
    py: Python<'_>,
    proportions: Vec<f64>,
    num_envs: usize,
    seed: u64,
    env_offset: u64,
) -> PyResult<Bound<'_, PyArray1<i64>>> {
    let mix =
        rse_core::SchemeMix::new(&proportions).map_err(|e| PyValueError::new_err(e.to_string()))?;
    if env_offset.checked_add(num_envs as u64).is_none() {
        return Err(PyValueError::new_err(
            "env_offset: past the last global env id",
        ));
    }
    let drawn: Vec<i64> = mix
        .schemes_of(seed, env_offset, num_envs)
        .into_iter()
        .map(|s| s as i64)
        .collect();
    Ok(PyArray1::from_vec(py, drawn))
}
