//! `rse.check_curriculum`: `rse_core::check_curriculum` with the GIL
//! released; `rse/_curriculum.py` makes its tuples dataclasses.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rse_core::CurriculumOptions;

use crate::scheme::Scheme;

/// One level's figures: level, difficulty, flat share, mean height, mean
/// step, max step (metres), max slope (degrees), distinct worlds.
type LevelTuple = (u32, f64, f64, f64, f64, f64, f64, u32);

/// The per-level figures, the problems in words and the seed used
/// (`rse.check_curriculum` gives the defaults).
#[pyfunction]
#[pyo3(signature = (scheme, levels, draws, seed=None))]
pub fn _check_curriculum(
    py: Python<'_>,
    scheme: &Scheme,
    levels: u32,
    draws: u32,
    seed: Option<u64>,
) -> PyResult<(Vec<LevelTuple>, Vec<String>, u64)> {
    let scheme = &scheme.inner;
    let options = CurriculumOptions {
        levels,
        draws,
        seed: seed.unwrap_or(scheme.globals().seed),
    };
    let report = py
        .detach(|| rse_core::check_curriculum(scheme, options))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let levels = report
        .levels
        .iter()
        .map(|l| {
            (
                l.level,
                l.difficulty.get(),
                l.flat_share,
                l.mean_height,
                l.mean_step,
                l.max_step,
                l.max_slope_deg,
                l.distinct,
            )
        })
        .collect();
    let problems = report.problems.iter().map(ToString::to_string).collect();
    Ok((levels, problems, options.seed))
}
