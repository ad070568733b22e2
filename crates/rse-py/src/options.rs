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
use crate::keywords::keyword_group;

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

keyword_group! {
    /// What every writer of world folders takes (`write_worlds`,
    /// `write_world`, `Atlas.write`): what the folder holds and how it is
    /// written. `None` is the library's default.
    pub struct WorldKeywords {
        /// `targets=`.
        targets: PyTargets,
        /// `mesh=`.
        mesh: PyMeshMode,
        /// `template=`: a folder overlaying our templates.
        template: std::path::PathBuf,
        /// `force=`: replace a different folder.
        force: bool,
        /// `mujoco_collider=`.
        mujoco_collider: PyColliderName,
        /// `oversample=`: the hfield collider's.
        oversample: u32,
    }
}

impl WorldKeywords {
    /// What these give a world folder of `difficulty` (`None`: the
    /// batch's): what the user gave, `None` for the rest (rse-world's
    /// [`WorldConfig`] resolves them).
    pub fn config(&self, difficulty: Option<Difficulty>) -> WorldConfig {
        WorldConfig {
            difficulty,
            targets: self.targets.as_ref().map(|t| t.0.clone()),
            mesh: self.mesh.as_ref().map(|m| m.0),
            mujoco_collider: self.mujoco_collider.as_ref().map(|c| c.0.clone()),
            oversample: self.oversample,
        }
    }

    /// The world options these give a folder of `difficulty`.
    pub fn options(&self, py: Python<'_>, difficulty: Difficulty) -> PyResult<WorldOptions> {
        self.config(Some(difficulty))
            .resolve()
            .map_err(|e| world_error(py, &e))
    }
}
