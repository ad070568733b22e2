//! `rse.EnvTerrains`: every parallel environment its own terrain, new every
//! episode (docs/envs.md). The state lives in rse-core; this class owns the
//! numpy arrays Python sees (`samples`, `episode`, `difficulty`, `origins`)
//! and fills them with the GIL released.
//!
//! Threads: the object may be shared. `heights_at`, `terrain` and `write`
//! run side by side; `reset` runs alone, and a call that meets another
//! thread's `reset` (or a `reset` that meets any other call) raises a
//! `RuntimeError` saying so, instead of waiting (docs/envs.md, "Threads").

use std::sync::{Arc, RwLock, RwLockReadGuard, RwLockWriteGuard};

use numpy::{
    Element, PyArray, PyArray1, PyArray2, PyArray3, PyArrayDescrMethods, PyArrayDyn,
    PyArrayMethods, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyMemoryError, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::world_error;
use crate::keywords::{self, KeywordGroup as _, keyword_group};
use crate::options::PyLayout;
use crate::scheme::{PyDifficulty, Scheme, difficulty_arg};
use crate::terrain::{Terrain, writable_samples};
use rse_core::FieldSamples;

/// The terrains of `num_envs` environments, each new at every reset.
///
/// `scheme` is one `rse.Scheme`, or a sequence of them to mix: each env
/// then draws its scheme by `proportions` (default equal) from its global
/// id and the seed, and keeps it (docs/envs.md, "A mix of schemes").
#[pyclass(module = "rse", frozen)]
pub struct EnvTerrains {
    /// The state; `reset` takes it whole (see the module's note on threads).
    inner: RwLock<rse_core::EnvTerrains>,
    /// What never changes after construction, read without the lock.
    fixed: Fixed,
    /// Every scheme (one, or a mix's in order), as the terrains name them.
    schemes: Vec<Arc<rse_core::Scheme>>,
    samples: Py<PyArray3<f32>>,
    episode: Py<PyArray1<i64>>,
    difficulty: Py<PyArray1<f64>>,
    origins: Py<PyArray2<f64>>,
}

/// The shape and placement of the pool: fixed when it is made.
struct Fixed {
    num_envs: usize,
    layout: &'static str,
    field_shape: (usize, usize),
    oversample: u32,
    buffer_shape: (usize, usize, usize),
    hfield_size: [f64; 4],
    hfield_pos: [f64; 3],
}

/// The error of a call that met another thread's `reset`, or of a `reset`
/// that met another thread's call.
fn busy() -> PyErr {
    PyRuntimeError::new_err(
        "EnvTerrains: another thread is using this object (reset runs alone; heights_at, \
         terrain and write run side by side): call reset from the thread that steps, or guard \
         the object with a lock",
    )
}

/// `array` as this object made it: its dtype and length unchanged. A
/// user can set `a.dtype` or `a.shape` of the very array in place; read
/// then as its old type, it would be read past its end.
fn intact<T: Element, D: numpy::ndarray::Dimension>(
    array: &Bound<'_, PyArray<T, D>>,
    name: &str,
    len: usize,
) -> PyResult<()> {
    let py = array.py();
    let dtype = array.dtype();
    if !dtype.is_equiv_to(&numpy::dtype::<T>(py)) || array.len() != len || !array.is_contiguous() {
        return Err(PyValueError::new_err(format!(
            "{name}: the array was changed in place (dtype {}, {} values; it must stay {} with \
             {len}): assign new values with `envs.{name} = values` or `envs.{name}[:] = values`",
            dtype.str()?,
            array.len(),
            numpy::dtype::<T>(py).str()?,
        )));
    }
    Ok(())
}

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// `env_ids` as indices below `n`, or a `ValueError` naming it: numbers
/// (a list, an array, a tensor on the CPU), or a boolean mask of `n` (a
/// numpy bool array, a list of bools), meaning the envs where it is true —
/// the rule of `rse._adapters.ids.env_ids`, which every adapter uses.
fn env_ids(ids: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<usize>> {
    // Bytes are a sequence of small integers to Python: `b"\x01\x02"` would
    // read as envs 1 and 2. Text and raw bytes (bytes, bytearray, a
    // memoryview of either) are never environment numbers.
    if crate::args::is_raw_bytes(ids) || ids.is_instance_of::<pyo3::types::PyString>() {
        return Err(PyValueError::new_err(
            "env_ids: expected a sequence of environment numbers, not bytes or text",
        ));
    }
    // True and False are 1 and 0 to Python: read as numbers, the mask
    // [True, False, True, False] reset envs 1, 0, 1, 0 and left env 2 alone.
    // numpy says whether what was given is booleans (a list, a tuple, an
    // array or a tensor it can read).
    let numpy = ids.py().import("numpy")?;
    if let Ok(array) = numpy.call_method1("asarray", (ids,)) {
        let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
        if kind == "b" {
            let mask: Vec<bool> = array
                .call_method0("ravel")?
                .call_method0("tolist")?
                .extract()?;
            let shape: Vec<usize> = array.getattr("shape")?.extract()?;
            if shape != [n] {
                return Err(PyValueError::new_err(format!(
                    "env_ids: a boolean mask of shape {shape:?} for {n} envs (it must be ({n},))"
                )));
            }
            return Ok(mask
                .iter()
                .enumerate()
                .filter_map(|(i, &on)| on.then_some(i))
                .collect());
        }
    }
    // An int64 numpy array is read in place; anything else (lists, other
    // dtypes, tensors) item by item.
    let ids: Vec<i64> = match ids.extract::<numpy::PyReadonlyArray1<'_, i64>>() {
        Ok(array) => array.as_array().to_vec(),
        Err(_) => ids.extract().map_err(|_| {
            PyValueError::new_err("env_ids: expected a sequence of environment numbers")
        })?,
    };
    ids.into_iter()
        .map(|e| {
            usize::try_from(e).ok().filter(|&e| e < n).ok_or_else(|| {
                PyValueError::new_err(format!(
                    "env_ids: {e} is not an environment (0 to {})",
                    n - 1
                ))
            })
        })
        .collect()
}

/// `samples` borrowed for writing, or a `ValueError` naming it (when
/// Python holds it borrowed elsewhere).
fn writable<'py>(
    samples: &Bound<'py, PyArray3<f32>>,
) -> PyResult<numpy::PyReadwriteArray3<'py, f32>> {
    samples
        .try_readwrite()
        .map_err(|e| PyValueError::new_err(format!("samples: {e}")))
}

impl EnvTerrains {
    /// The state for a call that reads it.
    fn reading(&self) -> PyResult<RwLockReadGuard<'_, rse_core::EnvTerrains>> {
        self.inner.try_read().map_err(|_| busy())
    }

    /// The state for `reset`.
    fn writing(&self) -> PyResult<RwLockWriteGuard<'_, rse_core::EnvTerrains>> {
        self.inner.try_write().map_err(|_| busy())
    }

    /// Every array of the pool as it was made: checked once, before a
    /// reset changes anything, so a refused reset changes nothing.
    fn arrays_intact(&self, py: Python<'_>) -> PyResult<()> {
        let n = self.fixed.num_envs;
        let (slots, rows, cols) = self.fixed.buffer_shape;
        intact(self.samples.bind(py), "samples", slots * rows * cols)?;
        intact(self.difficulty.bind(py), "difficulty", n)?;
        intact(self.origins.bind(py), "origins", 3 * n)?;
        intact(self.episode.bind(py), "episode", n)
    }

    /// Writes the samples of `envs` into `samples` (GIL released).
    fn write_samples(
        &self,
        py: Python<'_>,
        inner: &rse_core::EnvTerrains,
        envs: &[usize],
    ) -> PyResult<()> {
        let mut view = writable(self.samples.bind(py))?;
        let slice = view.as_slice_mut().map_err(value_error)?;
        py.detach(|| inner.write(envs, slice)).map_err(value_error)
    }

    /// Copies the origins and episodes of `envs` into the Python arrays
    /// (as made, or checked by [`Self::arrays_intact`]).
    fn publish(
        &self,
        py: Python<'_>,
        inner: &rse_core::EnvTerrains,
        envs: &[usize],
    ) -> PyResult<()> {
        let mut origins = self.origins.bind(py).try_readwrite().map_err(value_error)?;
        let mut episode = self.episode.bind(py).try_readwrite().map_err(value_error)?;
        let (origins, episode) = (
            origins.as_slice_mut().map_err(value_error)?,
            episode.as_slice_mut().map_err(value_error)?,
        );
        for &e in envs {
            origins[3 * e..3 * e + 3].copy_from_slice(&inner.origin(e));
            episode[e] = inner.episode(e) as i64;
        }
        Ok(())
    }
}

/// A per-env option's value as Python gives it, by its type in rse-core's
/// table (`for_each_env_option!`): what it is extracted as.
pub trait PyEnvOption: Sized {
    /// What Python's value is extracted as.
    type Py: for<'a, 'py> FromPyObject<'a, 'py, Error = PyErr>;

    /// The type as `_rse.pyi` writes it.
    const PY_TYPE: &'static str;

    /// The option's value.
    fn from_py(py: Self::Py) -> Self;
}

/// Numbers, as they are.
macro_rules! py_env_option_as_is {
    ($($ty:ty: $py_type:literal),*) => {
        $(impl PyEnvOption for $ty {
            type Py = $ty;

            const PY_TYPE: &'static str = $py_type;

            fn from_py(py: $ty) -> Self {
                py
            }
        })*
    };
}

py_env_option_as_is!(u32: "int", u64: "int", f64: "float");

impl PyEnvOption for rse_core::Difficulty {
    type Py = PyDifficulty;

    const PY_TYPE: &'static str = "float";

    fn from_py(py: PyDifficulty) -> Self {
        py.0
    }
}

impl PyEnvOption for rse_core::LayoutKind {
    type Py = PyLayout;

    const PY_TYPE: &'static str = "Literal[\"slots\", \"tiles\"]";

    fn from_py(py: PyLayout) -> Self {
        py.0
    }
}

/// `EnvKeywords` (the options of rse-core's table, then a mix's
/// proportions) and `request`, rse-core's `EnvRequest` of them.
macro_rules! env_keywords {
    ($(
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty {
            range: $range:expr,
            default: $default:literal,
            example: $example:literal,
            outside: $outside:expr,
            needs: $needs:literal,
        }
    )*) => {
        keyword_group! {
            /// What `EnvTerrains(scheme, num_envs, ...)` takes: rse-core's
            /// `EnvRequest` as the user gives it, and a mix's proportions.
            pub struct EnvKeywords {
                $($(#[doc = $what])* $field: <$ty as PyEnvOption>::Py,)*
                /// `proportions=`: a mix's shares.
                proportions: Vec<f64>,
            }
        }

        /// Each option's type as `_rse.pyi` writes it, in the table's order.
        const PY_TYPES: &[&str] = &[$(<$ty as PyEnvOption>::PY_TYPE),*];

        impl EnvKeywords {
            /// What the user gave for `num_envs` environments, `None` for
            /// the rest: rse-core resolves it.
            fn request(&mut self, num_envs: usize) -> rse_core::EnvRequest {
                rse_core::EnvRequest {
                    num_envs,
                    $($field: self.$field.take().map(PyEnvOption::from_py),)*
                }
            }
        }
    };
}

rse_core::for_each_env_option!(env_keywords);

/// One row of [`_env_keywords`]: name, type, default, example, outside,
/// needs.
pub type EnvKeywordRow = (
    &'static str,
    &'static str,
    &'static str,
    &'static str,
    Option<&'static str>,
    &'static str,
);

/// `[(name, type, default, example, outside, needs), …]`: each per-env
/// option of rse-core's table, its type as `_rse.pyi` writes it (for
/// `scripts/python_stubs.py`), and what `tests/python/test_every_option.py`
/// walks through every skin.
#[pyfunction]
pub fn _env_keywords() -> Vec<EnvKeywordRow> {
    rse_core::ENV_OPTIONS
        .iter()
        .zip(PY_TYPES)
        .map(|(o, py_type)| (o.name, *py_type, o.default, o.example, o.outside, o.needs))
        .collect()
}

keyword_group! {
    /// What `EnvTerrains.contact_sheet` takes beside its `path`.
    pub struct SheetKeywords {
        /// `env_ids=`: the envs drawn, in order (default every env).
        env_ids: Py<PyAny>,
        /// `cols=`: tiles per row.
        cols: u32,
        /// `cell_pixels=`: pixels per cell.
        cell_pixels: u32,
        /// `names=`: a mix's scheme names.
        names: Vec<String>,
        /// `one_scale=`: one colour scale for every scheme.
        one_scale: bool,
    }
}

#[pymethods]
impl EnvTerrains {
    /// `EnvTerrains(scheme, num_envs, *, oversample=None, …)`: the
    /// constructor's signature, from its keyword group.
    #[classattr]
    fn __signature__(py: Python<'_>) -> PyResult<Py<PyAny>> {
        keywords::signature(py, &["scheme", "num_envs"], &[EnvKeywords::NAMES])
    }

    #[new]
    #[pyo3(signature = (scheme, num_envs, **options))]
    fn new(
        py: Python<'_>,
        scheme: &Bound<'_, PyAny>,
        num_envs: usize,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut given = keywords::read::<EnvKeywords>(py, "EnvTerrains", options)?;
        let request = given.request(num_envs);
        let proportions = given.proportions;
        // One scheme, or several mixed by proportion (equal by default).
        let schemes: Vec<Arc<rse_core::Scheme>> = match scheme.cast::<Scheme>() {
            Ok(one) => vec![Arc::clone(&one.get().inner)],
            Err(_) => scheme
                .try_iter()
                .and_then(|items| {
                    items
                        .map(|item| Ok(Arc::clone(&item?.cast::<Scheme>()?.get().inner)))
                        .collect::<PyResult<Vec<_>>>()
                })
                .map_err(|_| {
                    PyTypeError::new_err(
                        "scheme: expected an rse.Scheme, or a sequence of them to mix",
                    )
                })?,
        };
        if schemes.is_empty() {
            return Err(PyValueError::new_err(
                "scheme: no scheme to draw terrains from",
            ));
        }
        let proportions = proportions.unwrap_or_else(|| vec![1.0; schemes.len()]);
        let scheme = Arc::clone(&schemes[0]);
        let options = request.resolve(&scheme).map_err(value_error)?;
        // Python's episode, difficulty and origin arrays: 40 bytes an env.
        let all: Vec<rse_core::Scheme> = schemes.iter().map(|s| (**s).clone()).collect();
        let bytes = rse_core::mix_pool_bytes(&all, options, 40).map_err(value_error)?;
        crate::memory::fits(
            "num_envs",
            bytes,
            format_args!(
                "a pool of {num_envs} environments at oversample {}",
                options.oversample
            ),
        )?;
        let owned: Vec<rse_core::Scheme> = schemes.iter().map(|s| (**s).clone()).collect();
        let inner = py
            .detach(|| rse_core::EnvTerrains::mixed(owned, &proportions, options))
            .map_err(value_error)?;
        let (n, rows, cols) = inner.buffer_shape();
        // Allocated by numpy, not Rust: numpy asks the kernel for huge
        // pages for large arrays, which makes the writes of a reset ~10%
        // faster (fewer TLB misses across a pool of hundreds of MiB).
        let samples = pool_samples(py, [n, rows, cols], num_envs, options.oversample)?;
        if matches!(inner.options().layout, rse_core::EnvLayout::Tiles { .. }) {
            // Tile borders are cells of height 0: the slab's top, as in an
            // atlas. (Slots are all written below.)
            let mut view = writable(&samples)?;
            let slice = view.as_slice_mut().map_err(value_error)?;
            let ground = inner.ground_sample();
            py.detach(|| slice.fill(ground));
        }
        let fixed = Fixed {
            num_envs,
            layout: rse_core::LayoutKind::from(inner.options().layout).name(),
            field_shape: inner.field_shape(),
            oversample: inner.options().oversample,
            buffer_shape: inner.buffer_shape(),
            hfield_size: inner.hfield_size(),
            hfield_pos: inner.hfield_pos(),
        };
        let envs = EnvTerrains {
            samples: samples.unbind(),
            episode: PyArray1::zeros(py, num_envs, false).unbind(),
            difficulty: PyArray1::from_vec(py, vec![options.difficulty.get(); num_envs]).unbind(),
            origins: PyArray2::zeros(py, [num_envs, 3], false).unbind(),
            inner: RwLock::new(inner),
            fixed,
            schemes,
        };
        let all: Vec<usize> = (0..num_envs).collect();
        {
            let inner = envs.reading()?;
            envs.write_samples(py, &inner, &all)?;
            envs.publish(py, &inner, &all)?;
        }
        Ok(envs)
    }

    /// Each env's scheme: its index in `schemes` (all 0 for one scheme),
    /// drawn from the proportions by its global id and the seed
    /// (`rse.scheme_mix`).
    #[getter]
    fn scheme_ids<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let inner = self.reading()?;
        let ids = (0..self.fixed.num_envs)
            .map(|e| inner.scheme_index(e) as i64)
            .collect();
        Ok(PyArray1::from_vec(py, ids))
    }

    /// Every scheme of the pool: the one, or a mix's in their order.
    #[getter]
    fn schemes(&self) -> Vec<Scheme> {
        self.schemes
            .iter()
            .map(|inner| Scheme {
                inner: Arc::clone(inner),
            })
            .collect()
    }

    /// How many environments (ids `0..num_envs` in this process).
    #[getter]
    fn num_envs(&self) -> usize {
        self.fixed.num_envs
    }

    /// The height-field samples, float32 in [0, 1]: `(num_envs, nrow, ncol)`
    /// for slots, `(1, rows, columns)` of the whole map for tiles. The same
    /// array every time; `reset` rewrites the reset environments' parts.
    #[getter]
    fn samples<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f32>> {
        self.samples.bind(py).clone()
    }

    /// Each environment's episode (int64; 0 until its first reset).
    #[getter]
    fn episode<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        self.episode.bind(py).clone()
    }

    /// Each environment's difficulty (float64 in [0, 1]), used at its next
    /// reset: the curriculum's knob. Set it whole, or write into it.
    #[getter]
    fn difficulty<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.difficulty.bind(py).clone()
    }

    #[setter(difficulty)]
    fn set_difficulty(&self, py: Python<'_>, values: Vec<PyDifficulty>) -> PyResult<()> {
        if values.len() != self.fixed.num_envs {
            return Err(PyValueError::new_err(format!(
                "difficulty: {} values for {} environments",
                values.len(),
                self.fixed.num_envs
            )));
        }
        let values: Vec<f64> = values.iter().map(|d| d.0.get()).collect();
        let array = self.difficulty.bind(py);
        intact(array, "difficulty", self.fixed.num_envs)?;
        let mut view = array.try_readwrite().map_err(value_error)?;
        view.as_slice_mut()
            .map_err(value_error)?
            .copy_from_slice(&values);
        Ok(())
    }

    /// Each environment's spawn point `(num_envs, 3)`, metres: its terrain's
    /// centre on the highest top within `spawn_radius`, in its slot's frame
    /// (slots: the terrain's corner at the origin) or the map's (tiles).
    #[getter]
    fn origins<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.origins.bind(py).clone()
    }

    /// `"slots"` or `"tiles"`.
    #[getter]
    fn layout(&self) -> &'static str {
        self.fixed.layout
    }

    /// One environment's field, `(nrow, ncol)`: its slot's (or tile's)
    /// cells, the largest grid of a mix, times `oversample`.
    #[getter]
    fn field_shape(&self) -> (usize, usize) {
        self.fixed.field_shape
    }

    /// Each environment's field's first sample in `samples`, int64
    /// `(num_envs, 2)` of `(row, column)`: its tile's corner in the map
    /// (tiles; the tile is `field_shape` from there), `(0, 0)` in its own
    /// slot (slots). What an adapter rewrites of a shared map after a reset.
    #[getter]
    fn field_corners<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let inner = self.reading()?;
        let corners: Vec<i64> = (0..self.fixed.num_envs)
            .flat_map(|e| {
                let (row, col) = inner.field_corner(e);
                [row as i64, col as i64]
            })
            .collect();
        PyArray1::from_vec(py, corners).reshape([self.fixed.num_envs, 2])
    }

    /// Samples per cell along each axis of the fields.
    #[getter]
    fn oversample(&self) -> u32 {
        self.fixed.oversample
    }

    /// MuJoCo's `size` of one slot's field (slots) or of the map (tiles):
    /// `(radius_x, radius_y, elevation, base)`, metres; sample 1 is the
    /// scheme's highest possible top above the geom, which goes at `hfield_pos`.
    #[getter]
    fn hfield_size(&self) -> (f64, f64, f64, f64) {
        let [a, b, c, d] = self.fixed.hfield_size;
        (a, b, c, d)
    }

    /// Where the field's geom goes in its slot's (or the map's) frame, metres.
    #[getter]
    fn hfield_pos(&self) -> (f64, f64, f64) {
        let [x, y, z] = self.fixed.hfield_pos;
        (x, y, z)
    }

    /// Moves each of `env_ids` to its next episode with a new terrain,
    /// written into its slot or tile only; `difficulty` (one value, or one
    /// per id) is stored for those envs first, else each keeps its own.
    /// Env e's terrain at episode k is world `k·2³² + (env_offset + e)` of
    /// the scheme at the base seed, at its difficulty.
    #[pyo3(signature = (env_ids, difficulty=None))]
    fn reset(
        &self,
        py: Python<'_>,
        env_ids: &Bound<'_, PyAny>,
        difficulty: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let mut inner = self.writing()?;
        let envs = self::env_ids(env_ids, self.fixed.num_envs)?;
        self.arrays_intact(py)?;
        let array = self.difficulty.bind(py).clone();
        if let Some(given) = difficulty {
            let values: Vec<f64> = match given.extract::<PyDifficulty>() {
                Ok(one) => vec![one.0.get(); envs.len()],
                // One value that is no difficulty (a bool, text, a number
                // out of range): its own error.
                Err(e)
                    if given.try_iter().is_err()
                        || given.is_instance_of::<pyo3::types::PyString>() =>
                {
                    return Err(e);
                }
                Err(_) => given
                    .extract::<Vec<PyDifficulty>>()?
                    .iter()
                    .map(|d| d.0.get())
                    .collect(),
            };
            if values.len() != envs.len() {
                return Err(PyValueError::new_err(format!(
                    "difficulty: {} values for {} env ids",
                    values.len(),
                    envs.len()
                )));
            }
            let mut view = array.try_readwrite().map_err(value_error)?;
            let slice = view.as_slice_mut().map_err(value_error)?;
            for (&e, &d) in envs.iter().zip(&values) {
                slice[e] = d;
            }
        }
        let levels: Vec<rse_core::Difficulty> = {
            let view = array.try_readonly().map_err(value_error)?;
            let slice = view.as_slice().map_err(value_error)?;
            envs.iter()
                .map(|&e| difficulty_arg(slice[e]))
                .collect::<PyResult<_>>()?
        };
        // New terrains made and written into `samples` in one pass, each by
        // the thread that made it (rse-core's `reset_into`).
        let mut view = writable(self.samples.bind(py))?;
        let slice = view.as_slice_mut().map_err(value_error)?;
        let state: &mut rse_core::EnvTerrains = &mut inner;
        py.detach(|| state.reset_into(&envs, &levels, slice))
            .map_err(value_error)?;
        self.publish(py, &inner, &envs)
    }

    /// Environment `env`'s current terrain.
    fn terrain(&self, env: usize) -> PyResult<Terrain> {
        if env >= self.fixed.num_envs {
            return Err(PyValueError::new_err(format!(
                "env: {env} is not an environment (0 to {})",
                self.fixed.num_envs - 1
            )));
        }
        let inner = self.reading()?;
        Ok(Terrain {
            inner: inner.terrain(env).clone(),
            scheme: Some(Arc::clone(&self.schemes[inner.scheme_index(env)])),
        })
    }

    /// A contact sheet of the current terrains as PNG bytes: one top-down
    /// preview per env (`env_ids`, default every env, in the order given),
    /// each labelled with its env id, episode and difficulty, a legend of
    /// the colour scale below; written to `path` too when given. `cols`
    /// tiles per row (default about square), `cell_pixels` pixels per cell
    /// (default: tiles about 120 pixels wide). A mix's tiles name their
    /// scheme (`names[j]` for scheme `j`, default `scheme j+1`) and each
    /// scheme has a colour scale of its own (from 0 to its highest cell
    /// shown; a legend bar each), unless `one_scale`.
    #[pyo3(signature = (path=None, **options),
           text_signature = "($self, path=None, *, env_ids=None, cols=None, cell_pixels=None, names=None, one_scale=None)")]
    fn contact_sheet<'py>(
        &self,
        py: Python<'py>,
        path: Option<std::path::PathBuf>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, pyo3::types::PyBytes>> {
        let SheetKeywords {
            env_ids,
            cols,
            cell_pixels,
            names,
            one_scale,
        } = keywords::read::<SheetKeywords>(py, "contact_sheet", options)?;
        let envs = match &env_ids {
            Some(ids) => self::env_ids(ids.bind(py), self.fixed.num_envs)?,
            None => Vec::new(),
        };
        if env_ids.is_some() && envs.is_empty() {
            return Err(PyValueError::new_err("env_ids: no environment to draw"));
        }
        if cols == Some(0) || cell_pixels == Some(0) {
            return Err(PyValueError::new_err(
                "cols and cell_pixels: expected a number above 0",
            ));
        }
        let options = rse_core::SheetOptions {
            cols,
            cell_pixels,
            one_scale: one_scale.unwrap_or(false),
        };
        let guard = self.reading()?;
        let inner: &rse_core::EnvTerrains = &guard;
        let png = py
            .detach(|| {
                rse_core::contact_sheet_named(
                    inner,
                    &envs,
                    options,
                    names.as_deref().unwrap_or(&[]),
                )
                .and_then(|sheet| rse_core::preview::encode_png(&sheet))
            })
            .map_err(value_error)?;
        drop(guard);
        if let Some(path) = path {
            // Whole or not at all, as every file rse writes.
            rse_world::write_atomically(&path, &png).map_err(|e| world_error(py, &e))?;
        }
        Ok(pyo3::types::PyBytes::new(py, &png))
    }

    /// The exact tops under `points` (`(len(env_ids), P, 2)`, metres, each
    /// env's slot frame or the map's for tiles): float64 `(len(env_ids), P)`,
    /// NaN off an env's terrain. The height scan a policy observes.
    fn heights_at<'py>(
        &self,
        py: Python<'py>,
        env_ids: &Bound<'py, PyAny>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let envs = self::env_ids(env_ids, self.fixed.num_envs)?;
        let points = py
            .import("numpy")?
            .call_method1("ascontiguousarray", (points, "float64"))?;
        let points = points
            .cast::<PyArrayDyn<f64>>()
            .map_err(|_| PyValueError::new_err("points: expected an array of float"))?;
        let shape = points.shape().to_vec();
        if shape.len() != 3 || shape[0] != envs.len() || shape[2] != 2 {
            return Err(PyValueError::new_err(format!(
                "points: shape {shape:?}, expected ({}, P, 2)",
                envs.len()
            )));
        }
        let view = points.try_readonly().map_err(value_error)?;
        let xy = view.as_slice().map_err(value_error)?;
        let per = shape[1];
        let guard = self.reading()?;
        let inner: &rse_core::EnvTerrains = &guard;
        let heights: Vec<f64> = py.detach(|| {
            envs.iter()
                .enumerate()
                .flat_map(|(i, &e)| (0..per).map(move |p| (i, e, p)))
                .map(|(i, e, p)| {
                    let at = 2 * (i * per + p);
                    inner.height_at(e, xy[at], xy[at + 1])
                })
                .collect()
        });
        PyArray1::from_vec(py, heights)
            .reshape([envs.len(), per])
            .map_err(value_error)
    }

    /// Writes the samples of `env_ids` (all when None) into `out`, an array
    /// of `samples`' shape and dtype (float32, C-contiguous, writable):
    /// numpy, or anything exposing `__dlpack__` or the buffer protocol on the CPU.
    #[pyo3(signature = (out, env_ids=None))]
    fn write(
        &self,
        py: Python<'_>,
        out: &Bound<'_, PyAny>,
        env_ids: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let envs = match env_ids {
            Some(ids) => self::env_ids(ids, self.fixed.num_envs)?,
            None => (0..self.fixed.num_envs).collect(),
        };
        let numpy = py.import("numpy")?;
        // An object offering DLPack alone (a torch tensor) through
        // `from_dlpack`; numpy's own arrays and the buffer protocol through
        // `asarray`, which shares their memory.
        let dlpack_only = out.cast::<PyArrayDyn<f32>>().is_err()
            && !out.hasattr("__array_interface__")?
            && out.hasattr("__dlpack__")?;
        let convert = if dlpack_only {
            "from_dlpack"
        } else {
            "asarray"
        };
        let array = numpy.call_method1(convert, (out,))?;
        let array = array
            .cast::<PyArrayDyn<f32>>()
            .map_err(|_| PyValueError::new_err("out: expected float32 samples"))?;
        let (n, rows, cols) = self.fixed.buffer_shape;
        if array.shape() != [n, rows, cols] {
            return Err(PyValueError::new_err(format!(
                "out: shape {:?}, expected ({n}, {rows}, {cols})",
                array.shape()
            )));
        }
        let mut view = writable_samples(array, "out")?;
        let slice = view.as_slice_mut().map_err(value_error)?;
        let guard = self.reading()?;
        let inner: &rse_core::EnvTerrains = &guard;
        py.detach(|| inner.write(&envs, slice)).map_err(value_error)
    }

    /// Copies the fields of `env_ids` out of `samples` into `data` (flat
    /// float32 numpy, C-contiguous and writable: a model's `hfield_data`,
    /// a host buffer a GPU upload reads) from `starts` (one each, not
    /// overlapping), every env on its own thread with the GIL released:
    /// the exact fields, or with `coarse` one sample a cell (the mean of
    /// its first and last). For the adapters (mjlab's reset); slots only.
    #[pyo3(signature = (env_ids, data, starts, *, coarse=false))]
    fn _copy_fields(
        &self,
        py: Python<'_>,
        env_ids: &Bound<'_, PyAny>,
        data: &Bound<'_, PyArray1<f32>>,
        starts: Vec<i64>,
        coarse: bool,
    ) -> PyResult<()> {
        let envs = self::env_ids(env_ids, self.fixed.num_envs)?;
        let starts = starts
            .into_iter()
            .map(|s| {
                usize::try_from(s).map_err(|_| {
                    PyValueError::new_err(format!("starts: {s} is not a place in data"))
                })
            })
            .collect::<PyResult<Vec<_>>>()?;
        let kind = if coarse {
            FieldSamples::Coarse
        } else {
            FieldSamples::Exact
        };
        let samples = self.samples.bind(py).try_readonly().map_err(value_error)?;
        let buffer = samples.as_slice().map_err(value_error)?;
        let mut view = writable_samples(data, "data")?;
        let out = view.as_slice_mut().map_err(value_error)?;
        let guard = self.reading()?;
        let inner: &rse_core::EnvTerrains = &guard;
        py.detach(|| inner.copy_fields(buffer, &envs, &starts, kind, out))
            .map_err(value_error)
    }
}

/// The pool's samples, zeros of `shape`, allocated by numpy (which asks
/// the kernel for huge pages for large arrays) through its own call: where
/// the allocation fails anyway (an address-space limit tighter than its
/// room once read), numpy raises `MemoryError`, named here for
/// `num_envs`, where `PyArray3::zeros` panicked on the null.
fn pool_samples(
    py: Python<'_>,
    shape: [usize; 3],
    num_envs: usize,
    oversample: u32,
) -> PyResult<Bound<'_, PyArray3<f32>>> {
    let [n, rows, cols] = shape;
    py.import("numpy")?
        .call_method1("zeros", ((n, rows, cols), "float32"))
        .map_err(|e| {
            if e.is_instance_of::<PyMemoryError>(py) {
                PyMemoryError::new_err(format!(
                    "num_envs: a pool of {num_envs} environments at oversample {oversample} does not fit ({e}); ask for fewer or a lower oversample"
                ))
            } else {
                e
            }
        })?
        .cast_into::<PyArray3<f32>>()
        .map_err(PyErr::from)
}
