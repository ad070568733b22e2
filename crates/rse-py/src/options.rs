//! World options as Python passes them, each a newtype over rse-world's
//! typed option (as tokenizers does for its enums): parsed by the option's
//! own `FromStr`, defaulted by its own `Default`, so Python writes no
//! option name or default of its own. `None` means the library's default.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyString;
use rse_core::Difficulty;
use rse_world::{MeshMode, Targets, WorldConfig, WorldOptions};

use crate::args::describe;
use crate::errors::world_error;

/// `targets=`: `"gazebo,mujoco"`, or a sequence of names
/// (`["gazebo", "mujoco"]`).
pub struct PyTargets(Targets);

impl<'a, 'py> FromPyObject<'a, 'py> for PyTargets {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let text = if obj.is_instance_of::<PyString>() {
            obj.extract::<String>()?
        } else {
            let names: Vec<String> = obj.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "targets: expected a comma-separated string or a list of target names, got {}",
                    describe(&obj)
                ))
            })?;
            names.join(",")
        };
        text.parse()
            .map(PyTargets)
            .map_err(|e| world_error(obj.py(), &e))
    }
}

/// `mesh=`: `"auto"`, `"single"` or `"blocks"`.
pub struct PyMeshMode(MeshMode);

impl<'a, 'py> FromPyObject<'a, 'py> for PyMeshMode {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let text = string(obj, "mesh")?;
        text.parse()
            .map(PyMeshMode)
            .map_err(|e| world_error(obj.py(), &e))
    }
}

/// `layout=` of `EnvTerrains`: `"slots"` or `"tiles"`, parsed by rse-core's
/// [`rse_core::LayoutKind`].
pub struct PyLayout(pub rse_core::LayoutKind);

impl<'a, 'py> FromPyObject<'a, 'py> for PyLayout {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let text = string(obj, "layout")?;
        text.parse()
            .map(PyLayout)
            .map_err(|e: rse_core::EnvError| pyo3::exceptions::PyValueError::new_err(e.to_string()))
    }
}

/// `mujoco_collider=`: `"boxes"` or `"hfield"` (its oversample is a
/// keyword of its own).
pub struct PyColliderName(String);

impl<'a, 'py> FromPyObject<'a, 'py> for PyColliderName {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        string(obj, "mujoco_collider").map(PyColliderName)
    }
}

/// The text of a keyword that takes a name, or a `TypeError` naming it.
fn string(obj: Borrowed<'_, '_, PyAny>, keyword: &str) -> PyResult<String> {
    if !obj.is_instance_of::<PyString>() {
        return Err(PyTypeError::new_err(format!(
            "{keyword}: expected a string, got {}",
            describe(&obj)
        )));
    }
    obj.extract::<String>()
}

/// What the keywords every writer takes give a world folder: what the user
/// gave, `None` for the rest (rse-world's [`WorldConfig`] resolves them).
pub fn world_config(
    targets: Option<PyTargets>,
    mesh: Option<PyMeshMode>,
    difficulty: Option<Difficulty>,
    mujoco_collider: Option<PyColliderName>,
    oversample: Option<u32>,
) -> WorldConfig {
    WorldConfig {
        difficulty,
        targets: targets.map(|t| t.0),
        mesh: mesh.map(|m| m.0),
        mujoco_collider: mujoco_collider.map(|c| c.0),
        oversample,
    }
}

/// The world options of the keywords every writer takes; `None` for any
/// of them is [`WorldOptions::default`]'s.
pub fn world_options(
    py: Python<'_>,
    targets: Option<PyTargets>,
    mesh: Option<PyMeshMode>,
    difficulty: Difficulty,
    mujoco_collider: Option<PyColliderName>,
    oversample: Option<u32>,
) -> PyResult<WorldOptions> {
    world_config(targets, mesh, Some(difficulty), mujoco_collider, oversample)
        .resolve()
        .map_err(|e| world_error(py, &e))
}
