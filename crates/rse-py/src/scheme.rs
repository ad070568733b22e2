//! `rse.Obstacle` and `rse.Scheme`: the obstacle table and global
//! parameters, built from keyword arguments or read from CSV.

use pyo3::IntoPyObjectExt as _;
use pyo3::prelude::*;
use pyo3::types::PyInt;
use rse_core::{Globals, ObstacleFields, ObstacleKind, Pallets, Param};

use crate::errors::{core_error, scheme_error, scheme_error_at};
use crate::terrain::Terrain;

/// A value or an inclusive `(lo, hi)` range drawn per world.
#[derive(FromPyObject)]
pub enum ParamArg<T> {
    Range((T, T)),
    Fixed(T),
}

impl<T> From<ParamArg<T>> for Param<T> {
    fn from(arg: ParamArg<T>) -> Self {
        match arg {
            ParamArg::Fixed(v) => Param::Fixed(v),
            ParamArg::Range((lo, hi)) => Param::Range(lo, hi),
        }
    }
}

/// A whole-number field (height, points) from Python ints of any size, so
/// that a negative or huge value is a `SchemeError` naming the field rather
/// than Python's `OverflowError`.
fn whole<'py>(
    py: Python<'py>,
    field: &str,
    arg: Option<ParamArg<Bound<'py, PyInt>>>,
) -> PyResult<Option<Param<u32>>> {
    let convert = |v: &Bound<'py, PyInt>| {
        v.extract::<u32>().map_err(|_| {
            scheme_error_at(
                py,
                field,
                &format!("{v} is not a whole number from 0 to {}", u32::MAX),
            )
        })
    };
    Ok(match arg {
        None => None,
        Some(ParamArg::Fixed(v)) => Some(Param::Fixed(convert(&v)?)),
        Some(ParamArg::Range((lo, hi))) => Some(Param::Range(convert(&lo)?, convert(&hi)?)),
    })
}

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

#[pymethods]
impl Obstacle {
    #[new]
    #[pyo3(signature = (r#type, height=None, angle=None, x1=None, y1=None, x2=None, y2=None, sigma=None))]
    #[allow(clippy::too_many_arguments)]
    fn new<'py>(
        py: Python<'py>,
        r#type: &str,
        height: Option<ParamArg<Bound<'py, PyInt>>>,
        angle: Option<ParamArg<f64>>,
        x1: Option<ParamArg<Bound<'py, PyInt>>>,
        y1: Option<ParamArg<Bound<'py, PyInt>>>,
        x2: Option<ParamArg<Bound<'py, PyInt>>>,
        y2: Option<ParamArg<Bound<'py, PyInt>>>,
        sigma: Option<ParamArg<f64>>,
    ) -> PyResult<Self> {
        let kind: ObstacleKind = r#type
            .parse()
            .map_err(|e| scheme_error_at(py, "type", &format!("{e}")))?;
        let fields = ObstacleFields {
            height: whole(py, "height", height)?,
            angle: angle.map(Into::into),
            x1: whole(py, "x1", x1)?,
            y1: whole(py, "y1", y1)?,
            x2: whole(py, "x2", x2)?,
            y2: whole(py, "y2", y2)?,
            sigma: sigma.map(Into::into),
        };
        let inner = rse_core::Obstacle::new(kind, fields).map_err(|e| scheme_error(py, &e))?;
        Ok(Obstacle { inner })
    }

    /// The type: `random`, `gaussian`, `peak`, `pit`, `wall` or `long_pit`.
    #[getter]
    fn r#type(&self) -> &'static str {
        self.inner.kind().name()
    }

    #[getter]
    fn height(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().height)
    }

    #[getter]
    fn angle(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().angle)
    }

    #[getter]
    fn x1(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().x1)
    }

    #[getter]
    fn y1(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().y1)
    }

    #[getter]
    fn x2(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().x2)
    }

    #[getter]
    fn y2(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().y2)
    }

    #[getter]
    fn sigma(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        param_to_py(py, self.inner.fields().sigma)
    }

    fn __repr__(&self) -> String {
        format!(
            "rse.Obstacle({:?}, {:?})",
            self.inner.kind().name(),
            self.inner.fields()
        )
    }
}

/// A scheme: global parameters and an ordered obstacle table (SPEC §2–5).
#[pyclass(module = "rse", frozen)]
pub struct Scheme {
    pub inner: rse_core::Scheme,
}

#[pymethods]
impl Scheme {
    #[new]
    #[pyo3(signature = (obstacles=Vec::new(), *, size=(10, 10), pallets=None, pallet_size=None, pallet_boundary=true, block_size=0.1, step_height=0.1, base=0.0, amount=1, seed=0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        obstacles: Vec<Bound<'_, Obstacle>>,
        size: (u32, u32),
        pallets: Option<(u32, u32)>,
        pallet_size: Option<u32>,
        pallet_boundary: bool,
        block_size: f64,
        step_height: f64,
        base: f64,
        amount: u64,
        seed: u64,
    ) -> PyResult<Self> {
        let globals = Globals {
            size: [size.0, size.1],
            pallets: pallets.map(|(px, py)| Pallets {
                size: pallet_size.unwrap_or(rse_core::DEFAULT_PALLET_SIZE),
                count: [px, py],
                boundary: pallet_boundary,
            }),
            block_size,
            step_height,
            base,
            amount,
            seed,
        };
        let table = obstacles.iter().map(|o| o.get().inner.clone()).collect();
        let inner = rse_core::Scheme::new(globals, table).map_err(|e| scheme_error(py, &e))?;
        Ok(Scheme { inner })
    }

    /// Reads a scheme CSV file.
    #[staticmethod]
    fn load(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let inner = rse_core::Scheme::load(&path).map_err(|e| core_error(py, &e))?;
        Ok(Scheme { inner })
    }

    /// Parses scheme CSV text.
    #[staticmethod]
    #[pyo3(signature = (text, file=None))]
    fn from_csv(py: Python<'_>, text: &str, file: Option<&str>) -> PyResult<Self> {
        let inner = rse_core::Scheme::from_csv(text, file).map_err(|e| scheme_error(py, &e))?;
        Ok(Scheme { inner })
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

    /// `(nx, ny)`: the grid in cells, frames included.
    #[getter]
    fn grid(&self) -> (u32, u32) {
        let grid = self.inner.grid();
        (grid.nx, grid.ny)
    }

    #[getter]
    fn block_size(&self) -> f64 {
        self.inner.globals().block_size
    }

    #[getter]
    fn step_height(&self) -> f64 {
        self.inner.globals().step_height
    }

    #[getter]
    fn base(&self) -> f64 {
        self.inner.globals().base
    }

    #[getter]
    fn amount(&self) -> u64 {
        self.inner.globals().amount
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.inner.globals().seed
    }

    /// World `index` of the batch with base seed `seed` (default: the
    /// scheme's `# seed:`, else 0, as on the command line), its obstacle
    /// heights scaled to `difficulty` (0 to 1: `h` becomes
    /// `floor(difficulty·h + 0.5)` steps, frames stay 1 step).
    #[pyo3(signature = (seed=None, index=0, difficulty=1.0))]
    fn generate(
        &self,
        py: Python<'_>,
        seed: Option<u64>,
        index: u64,
        difficulty: f64,
    ) -> PyResult<Terrain> {
        let difficulty = difficulty_arg(difficulty)?;
        let scheme = &self.inner;
        let seed = seed.unwrap_or(scheme.globals().seed);
        Ok(Terrain {
            inner: py.detach(|| rse_core::generate_at(scheme, seed, index, difficulty)),
        })
    }

    fn __eq__(&self, other: &Scheme) -> bool {
        self.inner.to_csv() == other.inner.to_csv()
    }

    fn __repr__(&self) -> String {
        let (nx, ny) = self.grid();
        format!(
            "<rse.Scheme {nx}x{ny}, {} obstacles>",
            self.inner.obstacles().len()
        )
    }
}

/// A `difficulty=` argument, refused with `ValueError` unless `0 ≤ d ≤ 1`.
pub fn difficulty_arg(d: f64) -> PyResult<rse_core::Difficulty> {
    rse_core::Difficulty::new(d).map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
}
