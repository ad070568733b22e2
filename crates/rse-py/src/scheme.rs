//! `rse.Obstacle` and `rse.Scheme`: the obstacle table and global
//! parameters, built from keyword arguments or read from CSV.

use std::sync::Arc;

use pyo3::IntoPyObjectExt as _;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rse_core::{Field, GlobalKey, Globals, ObstacleFields, ObstacleKind, Param, SchemeErrorKind};

use crate::args;
use crate::errors::{core_error, scheme_error, scheme_error_at};
use crate::global_keywords;
use crate::keywords;
use crate::terrain::Terrain;

/// Python's view of a parameter: an int/float or a `(lo, hi)` tuple.
fn param_to_py<'py, T: IntoPyObject<'py> + Copy>(
    py: Python<'py>,
    p: Option<Param<T>>,
) -> PyResult<Py<PyAny>> {
    Ok(match p {
        None => py.None(),
        Some(Param::Fixed(v)) => v.into_py_any(py)?,
        Some(Param::Range(lo, hi)) => (lo, hi).into_py_any(py)?,
    })
}

/// One row of the obstacle table; keyword arguments are the CSV columns.
#[pyclass(module = "rse", frozen, eq)]
#[derive(Clone, PartialEq)]
pub struct Obstacle {
    pub inner: rse_core::Obstacle,
}

impl Obstacle {
    /// The fields but `type`, by name, in the table's order.
    fn keywords(&self, py: Python<'_>) -> PyResult<Vec<(&'static str, Py<PyAny>)>> {
        let f = self.inner.fields();
        let mut keywords = Vec::new();
        for field in Field::ALL {
            let value = match field {
                Field::Type => continue,
                Field::Height => param_to_py(py, f.height)?,
                Field::Angle => param_to_py(py, f.angle)?,
                Field::X1 => param_to_py(py, f.x1)?,
                Field::Y1 => param_to_py(py, f.y1)?,
                Field::X2 => param_to_py(py, f.x2)?,
                Field::Y2 => param_to_py(py, f.y2)?,
                Field::Sigma => param_to_py(py, f.sigma)?,
                Field::Tread => param_to_py(py, f.tread)?,
            };
            keywords.push((field.name(), value));
        }
        Ok(keywords)
    }
}

/// The obstacle's columns but `type` as keyword-only parameters.
fn column_keywords() -> Vec<&'static str> {
    Field::ALL
        .into_iter()
        .filter(|&f| f != Field::Type)
        .map(Field::name)
        .collect()
}

#[pymethods]
impl Obstacle {
    /// `Obstacle(type, *, height=None, …)`: the type, then each column of
    /// the obstacle table (docs/schemes.md) as a keyword, read by the
    /// column's own rules (whole or real; a value or a `(lo, hi)` range).
    #[new]
    #[pyo3(signature = (r#type, **columns))]
    fn new(py: Python<'_>, r#type: &str, columns: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let kind: ObstacleKind = r#type
            .parse()
            .map_err(|e| scheme_error_at(py, "type", &format!("{e}")))?;
        let mut fields = ObstacleFields::default();
        for (key, value) in columns.map(PyDictMethods::iter).into_iter().flatten() {
            let name = key.extract::<String>().unwrap_or_default();
            let column = Field::ALL
                .into_iter()
                .find(|f| *f != Field::Type && f.name() == name);
            let value = (!value.is_none()).then_some(&value);
            match column {
                Some(Field::Height) => fields.height = args::whole_param("height", value)?,
                Some(Field::Angle) => fields.angle = args::real_param("angle", value)?,
                Some(Field::X1) => fields.x1 = args::whole_param("x1", value)?,
                Some(Field::Y1) => fields.y1 = args::whole_param("y1", value)?,
                Some(Field::X2) => fields.x2 = args::whole_param("x2", value)?,
                Some(Field::Y2) => fields.y2 = args::whole_param("y2", value)?,
                Some(Field::Sigma) => fields.sigma = args::real_param("sigma", value)?,
                Some(Field::Tread) => fields.tread = args::whole_param("tread", value)?,
                Some(Field::Type) | None => {
                    return Err(keywords::unexpected(
                        "Obstacle",
                        &key,
                        column_keywords().into_iter(),
                    )?);
                }
            }
        }
        let inner = rse_core::Obstacle::new(kind, fields).map_err(|e| scheme_error(py, &e))?;
        Ok(Obstacle { inner })
    }

    /// The constructor's signature, from the obstacle table's columns.
    #[classattr]
    fn __signature__(py: Python<'_>) -> PyResult<Py<PyAny>> {
        keywords::signature(py, &["type"], &[&column_keywords()])
    }

    /// The type: `random`, `gaussian`, `peak`, `pit`, `wall`, `long_pit`,
    /// `stairs`, `pyramid`, `pyramid_pit`, `ramp` or `crossing_ramps`.
    #[getter]
    fn r#type(&self) -> &'static str {
        self.inner.kind().name()
    }

    /// Height in steps: a whole number, a `(lo, hi)` range, or None.
    #[getter]
    fn height(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().height)
    }

    /// Slope angle in degrees (0 to 90), a `(lo, hi)` range, or None.
    #[getter]
    fn angle(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().angle)
    }

    /// First point, x cell (a value, a `(lo, hi)` range, or None).
    #[getter]
    fn x1(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().x1)
    }

    /// First point, y cell (a value, a `(lo, hi)` range, or None).
    #[getter]
    fn y1(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().y1)
    }

    /// Second point, x cell (a value, a `(lo, hi)` range, or None).
    #[getter]
    fn x2(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().x2)
    }

    /// Second point, y cell (a value, a `(lo, hi)` range, or None).
    #[getter]
    fn y2(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().y2)
    }

    /// Standard deviation of a gaussian, in steps (a value, a range, or None).
    #[getter]
    fn sigma(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().sigma)
    }

    /// Cells from one step to the next of a pyramid or pyramid pit (a
    /// value, a `(lo, hi)` range, or None).
    #[getter]
    fn tread(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().tread)
    }

    /// `rse.Obstacle('wall', height=3, ...)`: the call that makes it.
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let mut parts = vec![self.r#type().into_pyobject(py)?.repr()?.to_string()];
        for (name, value) in self.keywords(py)? {
            if !value.is_none(py) {
                parts.push(format!("{name}={}", value.bind(py).repr()?));
            }
        }
        Ok(format!("rse.Obstacle({})", parts.join(", ")))
    }

    /// For pickle and `copy`: the constructor's arguments, the type and
    /// the columns as keywords.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<((&'static str,), Bound<'py, PyDict>)> {
        let columns = PyDict::new(py);
        for (name, value) in self.keywords(py)? {
            columns.set_item(name, value)?;
        }
        Ok(((self.r#type(),), columns))
    }
}

/// `onto` with the global keywords in `given` (core's rules, e.g. pallets
/// turned on get a frame; `pallets=None` turns them off, any other `None`
/// is not given).
fn apply_patch(py: Python<'_>, given: &Bound<'_, PyDict>, onto: &Globals) -> PyResult<Globals> {
    global_keywords::patch(given)?
        .apply(onto)
        .map_err(|e| match (&e.kind, e.field.as_deref()) {
            // The rule is core's; the words are Python's.
            (SchemeErrorKind::PalletsOff, Some(field)) => scheme_error_at(
                py,
                field,
                "is set but pallets are off; pass pallets too, e.g. pallets=(2, 3)",
            ),
            _ => scheme_error(py, &e),
        })
}

/// A scheme: global parameters and an ordered obstacle table (docs/schemes.md).
#[pyclass(module = "rse", frozen)]
pub struct Scheme {
    pub inner: Arc<rse_core::Scheme>,
}

#[pymethods]
impl Scheme {
    /// `Scheme(obstacles=[], *, size=(10, 10), …)`: each global key a
    /// keyword (`inspect.signature(rse.Scheme)` lists them with their
    /// defaults).
    #[new]
    #[pyo3(signature = (obstacles=Vec::new(), **globals))]
    fn new(
        py: Python<'_>,
        obstacles: Vec<Bound<'_, Obstacle>>,
        globals: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let globals = match globals {
            Some(given) => {
                keywords::only_known(
                    "Scheme",
                    given,
                    GlobalKey::ALL.into_iter().map(GlobalKey::name),
                )?;
                apply_patch(py, given, &Globals::default())?
            }
            None => Globals::default(),
        };
        let table = obstacles.iter().map(|o| o.get().inner.clone()).collect();
        let inner = rse_core::Scheme::new(globals, table).map_err(|e| scheme_error(py, &e))?;
        Ok(Scheme {
            inner: Arc::new(inner),
        })
    }

    /// The constructor's signature, built from rse-core's table of global
    /// keys (pyo3 would show `**globals`).
    #[classattr]
    fn __signature__(py: Python<'_>) -> PyResult<Py<PyAny>> {
        global_keywords::scheme_signature(py)
    }

    /// A copy with some fields changed, for curricula:
    /// `scheme.replace(size=(20, 20), step_height=0.05)`. Takes the
    /// constructor's keywords (`obstacles` too); validated as a new scheme.
    /// `pallets=None` turns pallets off with their size and boundary.
    #[pyo3(signature = (**fields))]
    fn replace<'py>(
        &self,
        py: Python<'py>,
        fields: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let mut table = None;
        let given = PyDict::new(py);
        if let Some(fields) = fields {
            let known = std::iter::once("obstacles").chain(GlobalKey::ALL.map(GlobalKey::name));
            keywords::only_known("replace", fields, known)?;
            for (key, value) in fields.iter() {
                if key.extract::<String>()? == "obstacles" {
                    table = Some(value.extract::<Vec<Bound<'py, Obstacle>>>()?);
                } else {
                    given.set_item(key, value)?;
                }
            }
        }
        let globals = apply_patch(py, &given, self.inner.globals())?;
        let obstacles = match table {
            Some(table) => table.iter().map(|o| o.get().inner.clone()).collect(),
            None => self.inner.obstacles().to_vec(),
        };
        let inner = rse_core::Scheme::new(globals, obstacles).map_err(|e| scheme_error(py, &e))?;
        Scheme {
            inner: Arc::new(inner),
        }
        .into_bound_py_any(py)
    }

    /// The constructor's keywords with this scheme's values.
    fn fields<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("obstacles", self.obstacles())?;
        global_keywords::values(self.inner.globals(), &dict)?;
        Ok(dict)
    }

    /// Reads a scheme CSV file.
    #[staticmethod]
    fn load(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let inner = rse_core::Scheme::load(&path).map_err(|e| core_error(py, &e))?;
        Ok(Scheme {
            inner: Arc::new(inner),
        })
    }

    /// Parses scheme CSV text.
    #[staticmethod]
    #[pyo3(signature = (text, file=None))]
    fn from_csv(py: Python<'_>, text: &str, file: Option<&str>) -> PyResult<Self> {
        let inner = rse_core::Scheme::from_csv(text, file).map_err(|e| scheme_error(py, &e))?;
        Ok(Scheme {
            inner: Arc::new(inner),
        })
    }

    /// The canonical CSV text.
    fn to_csv(&self) -> String {
        self.inner.to_csv()
    }

    /// The obstacle table.
    #[getter]
    fn obstacles(&self) -> Vec<Obstacle> {
        self.inner
            .obstacles()
            .iter()
            .map(|o| Obstacle { inner: o.clone() })
            .collect()
    }

    /// The highest top any world of this scheme can have, metres:
    /// `base + H·step_height`, `H` the largest obstacle height allowed (at
    /// least one step, for frames). A height field that reaches it holds
    /// every world (`rse.mujoco.hfield_mjcf`).
    #[getter]
    fn max_top(&self) -> f64 {
        self.inner.max_top()
    }

    /// `(nx, ny)`: the grid in cells, frames included.
    #[getter]
    fn grid(&self) -> (u32, u32) {
        let grid = self.inner.grid();
        (grid.nx, grid.ny)
    }

    /// Cell side in metres.
    #[getter]
    fn block_size(&self) -> f64 {
        self.inner.globals().block_size
    }

    /// Height of one step in metres.
    #[getter]
    fn step_height(&self) -> f64 {
        self.inner.globals().step_height
    }

    /// Slab under the whole grid in metres (0: none).
    #[getter]
    fn base(&self) -> f64 {
        self.inner.globals().base
    }

    /// Worlds in a batch of this scheme (`# amount:`, else 1).
    #[getter]
    fn amount(&self) -> u64 {
        self.inner.globals().amount
    }

    /// Base seed of a batch of this scheme (`# seed:`, else 0).
    #[getter]
    fn seed(&self) -> u64 {
        self.inner.globals().seed
    }

    /// World `index` of the batch with base seed `seed` (default: the
    /// scheme's `# seed:`, else 0, as on the command line), its obstacle
    /// heights scaled to `difficulty` (0 to 1: `h` becomes
    /// `floor(difficulty·h + u)` steps, `u` one draw per world, the highest
    /// cell kept at a step; frames stay 1 step; docs/schemes.md).
    #[pyo3(signature = (seed=None, index=0, difficulty=None))]
    fn generate(
        &self,
        py: Python<'_>,
        seed: Option<u64>,
        index: u64,
        difficulty: Option<PyDifficulty>,
    ) -> Terrain {
        let request = rse_core::WorldRequest {
            seed,
            index: Some(index),
            difficulty: difficulty.map(|d| d.0),
        };
        let scheme = &self.inner;
        let at = request.resolve(scheme);
        py.detach(|| Terrain::generate(scheme, at.seed, at.index, at.difficulty))
    }

    fn __eq__(&self, other: &Scheme) -> bool {
        self.inner.to_csv() == other.inner.to_csv()
    }

    /// `rse.Scheme([...], size=(10, 10), ...)`: the call that makes it
    /// (notes aside), fields at their defaults left out.
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let defaults = Scheme {
            inner: Arc::new(
                rse_core::Scheme::new(Globals::default(), Vec::new())
                    .expect("the default scheme is valid"),
            ),
        }
        .fields(py)?;
        // `obstacles` first, positional; then what differs from the default.
        let mut entries = self.fields(py)?.iter();
        let (_, obstacles) = entries.next().expect("fields start with obstacles");
        let mut parts = vec![obstacles.repr()?.to_string()];
        for (key, value) in entries {
            let default = defaults.get_item(&key)?.expect("same keys");
            if !value.eq(default)? {
                parts.push(format!("{key}={}", value.repr()?));
            }
        }
        Ok(format!("rse.Scheme({})", parts.join(", ")))
    }

    /// For pickle and `copy`: the canonical CSV (notes included), which
    /// reads back to an equal scheme.
    fn __reduce__(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let from_csv = py.get_type::<Scheme>().getattr("from_csv")?;
        let args = (self.inner.to_csv(), self.inner.file().map(str::to_owned));
        (from_csv, args).into_py_any(py)
    }
}

/// A `difficulty=` argument, refused with `ValueError` unless `0 ≤ d ≤ 1`.
pub fn difficulty_arg(d: f64) -> PyResult<rse_core::Difficulty> {
    rse_core::Difficulty::new(d).map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
}

/// A difficulty as Python passes it: a number in [0, 1] (an `int`, a
/// `float`, a numpy scalar), never `True`/`False` — to Python they are 1
/// and 0, but `difficulty=[True, False]` is a mask given in the wrong
/// place, not two difficulties. Every `difficulty` argument reads it.
pub struct PyDifficulty(pub rse_core::Difficulty);

impl<'a, 'py> FromPyObject<'a, 'py> for PyDifficulty {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let d = crate::args::real(&obj).ok_or_else(|| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "difficulty: expected a number from 0 to 1, got {}",
                crate::args::describe(&obj)
            ))
        })?;
        difficulty_arg(d).map(PyDifficulty)
    }
}
