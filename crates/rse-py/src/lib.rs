//! Python bindings of rse (`import rse`): schemes, terrains as numpy arrays,
//! meshes, box sets, MJCF, batches. Thin over rse-core and rse-world: no
//! generator logic here.

// pyo3 hands every argument over by value (it converts it from Python):
// taking some of them by reference is not an option.
#![allow(clippy::needless_pass_by_value)]

use pyo3::prelude::*;
use pyo3::types::PyTuple;

mod args;
mod atlas;
mod batch;
mod check;
mod curriculum;
mod envs;
mod errors;
mod global_keywords;
mod keywords;
mod memory;
mod mix;
mod options;
mod scheme;
mod terrain;

/// The native part of the `rse` package.
#[pymodule]
fn _rse(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", rse_core::VERSION)?;
    // The option values and defaults of rse-world and rse-core, for the
    // Python modules and the stub's `Literal`s (a test keeps them equal).
    let py = m.py();
    let names = |names: &[&str]| PyTuple::new(py, names);
    m.add(
        "TARGETS",
        names(&rse_world::Target::ALL.map(rse_world::Target::name))?,
    )?;
    m.add(
        "MESH_MODES",
        names(&rse_world::MeshMode::ALL.map(rse_world::MeshMode::name))?,
    )?;
    m.add(
        "MUJOCO_COLLIDERS",
        names(&rse_world::MujocoCollider::NAMES)?,
    )?;
    // The library's defaults, for Python code that must name one (a
    // dataclass field, a docstring); a keyword left `None` gets the same.
    m.add("DEFAULT_OVERSAMPLE", rse_core::DEFAULT_OVERSAMPLE)?;
    // The rule that scales heights by difficulty in every terrain made
    // today (`rse.json`'s `difficulty_rule`), for a run's record.
    m.add("DIFFICULTY_RULE", rse_core::DifficultyRule::CURRENT.name())?;
    m.add("DEFAULT_ENV_OVERSAMPLE", rse_core::DEFAULT_ENV_OVERSAMPLE)?;
    m.add(
        "DEFAULT_SPAWN_RADIUS",
        rse_core::spawn::DEFAULT_SPAWN_RADIUS,
    )?;
    m.add(
        "DEFAULT_PATCH_RADIUS",
        rse_core::spawn::DEFAULT_PATCH_RADIUS,
    )?;
    m.add("SchemeError", m.py().get_type::<errors::SchemeError>())?;
    m.add(
        "ShardBusyError",
        m.py().get_type::<errors::ShardBusyError>(),
    )?;
    m.add_class::<scheme::Obstacle>()?;
    m.add_class::<scheme::Scheme>()?;
    m.add_class::<terrain::Terrain>()?;
    m.add_class::<atlas::Atlas>()?;
    m.add_class::<envs::EnvTerrains>()?;
    m.add_function(wrap_pyfunction!(batch::generate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(batch::write_worlds, m)?)?;
    m.add_function(wrap_pyfunction!(global_keywords::_global_keywords, m)?)?;
    m.add_function(wrap_pyfunction!(options::_world_keywords, m)?)?;
    m.add_function(wrap_pyfunction!(envs::_env_keywords, m)?)?;
    m.add_function(wrap_pyfunction!(batch::write_world, m)?)?;
    m.add_function(wrap_pyfunction!(batch::_time_generate, m)?)?;
    m.add_function(wrap_pyfunction!(check::_check_json, m)?)?;
    m.add_function(wrap_pyfunction!(curriculum::_check_curriculum, m)?)?;
    m.add_function(wrap_pyfunction!(mix::scheme_mix, m)?)?;
    Ok(())
}
