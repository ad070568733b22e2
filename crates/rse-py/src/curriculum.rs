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
#[pyo3(signature = (scheme, levels, draws, seed=None, budget=None))]
pub fn _check_curriculum(
    py: Python<'_>,
    scheme: &Scheme,
    levels: u32,
    draws: u32,
    seed: Option<u64>,
    budget: Option<f64>,
) -> PyResult<(Vec<LevelTuple>, Vec<String>, u64)> {
    let budget = budget
        .map(rse_verify::Budget::new)
        .transpose()
        .map_err(|e| PyValueError::new_err(e.to_string()))?
        .unwrap_or_default()
        .factor();
    let scheme = &scheme.inner;
    let options = CurriculumOptions {
        levels,
        draws,
        seed: scheme.seed_or(seed),
    };
    let report = interruptible(py, |stop| {
        rse_core::check_curriculum_within(scheme, options, budget, stop)
    })?
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

/// Runs `work` without the GIL on another thread while this one waits for
/// it, checking Python's signals every 50 ms: Ctrl-C sets the stop flag
/// `work` polls, and its `KeyboardInterrupt` is raised once `work` has
/// stopped (a long check once ignored Ctrl-C to the end).
#[allow(clippy::redundant_closure_for_method_calls)] // the closure is generic over the GIL's lifetime; the method is not
fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&(dyn Fn() -> bool + Sync)) -> T + Send,
) -> PyResult<T> {
    use std::sync::atomic::{AtomicBool, Ordering};
    let stop = AtomicBool::new(false);
    let mut raised = None;
    let done = py.detach(|| {
        std::thread::scope(|scope| {
            let running = scope.spawn(|| work(&|| stop.load(Ordering::Relaxed)));
            while !running.is_finished() {
                std::thread::sleep(std::time::Duration::from_millis(50));
                if raised.is_none()
                    && let Err(e) = Python::attach(|py| py.check_signals())
                {
                    raised = Some(e);
                    stop.store(true, Ordering::Relaxed);
                }
            }
            running.join()
        })
    });
    if let Some(e) = raised {
        return Err(e);
    }
    done.map_err(|_| PyValueError::new_err("the check panicked"))
}
