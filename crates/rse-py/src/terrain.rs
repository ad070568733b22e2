//! `rse.Terrain`: one generated world as numpy arrays, with its mesh, box
//! set, MJCF and mesh files.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::IntoPyObjectExt as _;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::sync::Arc;

use crate::errors::{core_error, world_error};

/// The caller's array `name` (float32 samples) borrowed for writing, if it
/// is C-contiguous and writable; else a `ValueError` naming it. numpy's
/// slice view alone would also take a Fortran-ordered array and fill it in
/// the wrong order.
pub(crate) fn writable_samples<'py, D: numpy::ndarray::Dimension>(
    out: &Bound<'py, numpy::PyArray<f32, D>>,
    name: &str,
) -> PyResult<numpy::PyReadwriteArray<'py, f32, D>> {
    if !out.is_c_contiguous() {
        return Err(PyValueError::new_err(format!(
            "{name}: must be C-contiguous"
        )));
    }
    out.try_readwrite()
        .map_err(|e| PyValueError::new_err(format!("{name}: not writable ({e})")))
}

/// One generated RSE.
#[pyclass(module = "rse", frozen)]
pub struct Terrain {
    pub inner: rse_core::Terrain,
    /// The scheme it was generated from (none for an atlas's map): what
    /// `rse.write_world` builds its world folder from.
    pub scheme: Option<Arc<rse_core::Scheme>>,
}

impl Terrain {
    /// World `index` of `seed` at `difficulty`, keeping its scheme.
    pub fn generate(
        scheme: &Arc<rse_core::Scheme>,
        seed: u64,
        index: u64,
        difficulty: rse_core::Difficulty,
    ) -> Terrain {
        Terrain {
            inner: rse_core::generate_at(scheme, seed, index, difficulty),
            scheme: Some(Arc::clone(scheme)),
        }
    }

    /// The heights as numpy `(ny, nx)` of `T`, the layout of `heights`.
    fn grid_array<T: numpy::Element>(&self, value: impl Fn(u32, u32) -> T) -> Array2<T> {
        let grid = self.inner.grid();
        let values = (0..grid.ny)
            .flat_map(|y| (0..grid.nx).map(move |x| (x, y)))
            .map(|(x, y)| value(x, y))
            .collect();
        Array2::from_shape_vec((grid.ny as usize, grid.nx as usize), values).expect("ny × nx cells")
    }
}

/// What `Terrain.hfield` returns: samples, MuJoCo's `size`, the geom's `pos`.
type HFieldTuple<'py> = (
    Bound<'py, PyArray2<f32>>,
    (f64, f64, f64, f64),
    (f64, f64, f64),
);

/// `array` made read-only: the terrain it shows is immutable.
fn read_only<T: numpy::Element>(array: Bound<'_, PyArray2<T>>) -> PyResult<Bound<'_, PyArray2<T>>> {
    array.getattr("flags")?.setattr("writeable", false)?;
    Ok(array)
}

/// Rows of `n` values as an `(rows, n)` numpy array.
fn rows<T: numpy::Element, const N: usize>(
    py: Python<'_>,
    items: Vec<[T; N]>,
) -> Bound<'_, PyArray2<T>> {
    let count = items.len();
    let flat: Vec<T> = items.into_iter().flatten().collect();
    Array2::from_shape_vec((count, N), flat)
        .expect("count × N values")
        .into_pyarray(py)
}

#[pymethods]
impl Terrain {
    /// For pickle only: make terrains with `Scheme.generate`. `state` is
    /// the terrain's JSON, `cells` its heights (little-endian uint16, row by
    /// row), `scheme` the scheme's CSV; with a scheme, the terrain must be
    /// the one it generates for the state's seed, index and difficulty.
    #[new]
    #[pyo3(signature = (state, cells, scheme=None))]
    fn restore(state: &str, cells: &[u8], scheme: Option<&str>) -> PyResult<Self> {
        let not_ours = || {
            PyValueError::new_err(
                "not the state of a pickled rse.Terrain: make terrains with Scheme.generate",
            )
        };
        let cells = cells
            .chunks_exact(2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
            .collect();
        let inner = rse_core::Terrain::from_parts(state, cells).ok_or_else(not_ours)?;
        let scheme = scheme
            .map(|csv| rse_core::Scheme::from_csv(csv, None).map_err(|_| not_ours()))
            .transpose()?
            .map(Arc::new);
        // A terrain with its scheme is that scheme's world of its seed,
        // index and difficulty, and `write_world` builds its folder from
        // them: heights or units it cannot have generated are a forgery.
        if let Some(scheme) = &scheme {
            let again =
                rse_core::generate_at(scheme, inner.seed(), inner.index(), inner.difficulty());
            if again.to_json() != inner.to_json()
                || again.heightmap().cells() != inner.heightmap().cells()
            {
                return Err(not_ours());
            }
        }
        Ok(Terrain { inner, scheme })
    }

    /// For pickle and `copy`: the constructor and the terrain's state.
    fn __reduce__(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let cells: Vec<u8> = self
            .inner
            .heightmap()
            .cells()
            .iter()
            .flat_map(|h| h.to_le_bytes())
            .collect();
        let state = (
            self.inner.to_json(),
            PyBytes::new(py, &cells),
            self.scheme.as_ref().map(|s| s.to_csv()),
        );
        (py.get_type::<Terrain>(), state).into_py_any(py)
    }

    /// Heights in steps, shape `(ny, nx)`, `heights[y, x]`; read-only.
    #[getter]
    fn heights<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u16>>> {
        let map = self.inner.heightmap();
        read_only(self.grid_array(|x, y| map.get(x, y)).into_pyarray(py))
    }

    /// Top of every cell in metres (`base + h·step`), shape `(ny, nx)`; read-only.
    #[getter]
    fn elevation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        read_only(
            self.grid_array(|x, y| self.inner.elevation(x, y))
                .into_pyarray(py),
        )
    }

    /// The top under points `(x, y)` in metres, in the terrain's frame
    /// (cell `(i, j)` covers `[i·s, (i+1)·s] × [j·s, (j+1)·s]`): a float
    /// for numbers, an array of their broadcast shape for arrays. On an
    /// edge shared by cells, the highest of them; off the terrain,
    /// `outside` (default 0.0: the ground every world has; pass `nan` to
    /// spot such points).
    #[pyo3(signature = (x, y, *, outside=0.0))]
    fn height_at<'py>(
        &self,
        py: Python<'py>,
        x: Bound<'py, PyAny>,
        y: Bound<'py, PyAny>,
        outside: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        // numpy does the conversions and the broadcasting; the loop runs
        // over contiguous float64 buffers without the GIL.
        let np = py.import("numpy")?;
        let as_array = |v: Bound<'py, PyAny>| np.call_method1("asarray", (v, "float64"));
        let both = np.call_method1("broadcast_arrays", (as_array(x)?, as_array(y)?))?;
        let (xs, ys): (Bound<'py, PyAny>, Bound<'py, PyAny>) = both.extract()?;
        let shape = xs.getattr("shape")?;
        let flat = |a: &Bound<'py, PyAny>| -> PyResult<Bound<'py, PyArray1<f64>>> {
            Ok(np
                .call_method1("ascontiguousarray", (np.call_method1("ravel", (a,))?,))?
                .cast_into::<PyArray1<f64>>()?)
        };
        let (xs, ys) = (flat(&xs)?, flat(&ys)?);
        let (xs, ys) = (xs.readonly(), ys.readonly());
        let (xs, ys) = (xs.as_slice()?, ys.as_slice()?);
        let terrain = &self.inner;
        let tops: Vec<f64> = py.detach(|| {
            xs.iter()
                .zip(ys)
                .map(|(&x, &y)| terrain.height_at(x, y).unwrap_or(outside))
                .collect()
        });
        let tops = tops.into_pyarray(py).call_method1("reshape", (&shape,))?;
        if shape.len()? == 0 {
            return tops.call_method0("item");
        }
        Ok(tops)
    }

    /// Cell side in metres.
    #[getter]
    fn block_size(&self) -> f64 {
        self.inner.block_size()
    }

    /// Height of one step in metres.
    #[getter]
    fn step_height(&self) -> f64 {
        self.inner.step_height()
    }

    /// Slab under the whole grid in metres (0: none).
    #[getter]
    fn base(&self) -> f64 {
        self.inner.base()
    }

    /// Base seed of the batch this world belongs to.
    #[getter]
    fn seed(&self) -> u64 {
        self.inner.seed()
    }

    /// Index of this world in its batch.
    #[getter]
    fn index(&self) -> u64 {
        self.inner.index()
    }

    /// The difficulty its obstacle heights were scaled to (1: as drawn).
    #[getter]
    fn difficulty(&self) -> f64 {
        self.inner.difficulty().get()
    }

    /// A spawn point `[x, y, z]` in metres: the terrain's centre, on the
    /// highest top within `radius` metres of it (a body whose footprint
    /// fits in that disc starts inside no block).
    #[pyo3(signature = (radius=None))]
    fn spawn_origin<'py>(
        &self,
        py: Python<'py>,
        radius: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let radius = radius.unwrap_or(rse_core::spawn::DEFAULT_SPAWN_RADIUS);
        check_radius("radius", radius)?;
        let origin = self.inner.spawn_origin(self.inner.region(), radius);
        Ok(origin.to_vec().into_pyarray(py))
    }

    /// Up to `n` flat patches: centres `[x, y, z]` (metres) of discs of
    /// `radius` metres inside the terrain over which every cell is within
    /// `max_step` steps of the others, z the highest top under the disc.
    /// Shape `(min(n, cells), 3)`; when fewer are found the rest are NaN
    /// rows. The same
    /// points `rse.Atlas` and `rse-gen atlas` give.
    #[pyo3(signature = (n, radius=None, max_step=0))]
    fn flat_patches<'py>(
        &self,
        py: Python<'py>,
        n: u32,
        radius: Option<f64>,
        max_step: u16,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let radius = radius.unwrap_or(rse_core::spawn::DEFAULT_PATCH_RADIUS);
        check_radius("radius", radius)?;
        // A terrain holds at most one patch a cell: rows past that would
        // only ever be NaN, so none are made (a caller's 10**8 once asked
        // for 9.6 GB and aborted the interpreter).
        let region = self.inner.region();
        let rows = u64::from(n).min(u64::from(region.nx) * u64::from(region.ny));
        // The (rows, 3) result and the points found, float64.
        crate::memory::fits(
            "n",
            rows.saturating_mul(48),
            format_args!("{n} flat patches"),
        )?;
        let found = py.detach(|| {
            self.inner
                .flat_patches(region, rows as u32, radius, max_step)
        });
        let mut out = Array2::from_elem((rows as usize, 3), f64::NAN);
        for (k, point) in found.into_iter().enumerate() {
            for (axis, v) in point.into_iter().enumerate() {
                out[[k, axis]] = v;
            }
        }
        Ok(out.into_pyarray(py))
    }

    /// The terrain as a MuJoCo height field with `oversample` samples per
    /// cell along each axis (`None`: `rse.DEFAULT_OVERSAMPLE`): `(data, size, pos)` — float32 `(nrow, ncol)`
    /// samples in [0, 1] (row 0 at the lowest y, MuJoCo's layout), MuJoCo's
    /// `size` `(radius_x, radius_y, elevation, base)` and the hfield geom's
    /// `pos`, metres. Exact but within half a sample spacing of a step edge.
    /// With `out=` (a writable C-contiguous float32 array of
    /// `hfield_shape(oversample)`), the samples go there and `out` is
    /// returned: no allocation, for loops.
    #[pyo3(signature = (oversample=None, *, out=None))]
    fn hfield<'py>(
        &self,
        py: Python<'py>,
        oversample: Option<u32>,
        out: Option<Bound<'py, PyArray2<f32>>>,
    ) -> PyResult<HFieldTuple<'py>> {
        let oversample = oversample.unwrap_or(rse_core::DEFAULT_OVERSAMPLE);
        let layout = self.inner.hfield_layout(oversample).map_err(hfield_error)?;
        let [rx, ry, elevation, base] = layout.size;
        let [x, y, z] = layout.pos;
        let data = if let Some(out) = out {
            self.hfield_into(py, &out, Some(oversample), z, elevation)?;
            out
        } else {
            let hf = self.inner.hfield(oversample).map_err(hfield_error)?;
            Array2::from_shape_vec((hf.nrow as usize, hf.ncol as usize), hf.data)
                .expect("nrow × ncol samples")
                .into_pyarray(py)
        };
        Ok((data, (rx, ry, elevation, base), (x, y, z)))
    }

    /// `hfield(oversample)` without its samples: `((nrow, ncol), size, pos)`
    /// — the shape, MuJoCo's `size` `(radius_x, radius_y, elevation, base)`
    /// and the geom's `pos`, metres (the grid's centre; z the lowest top).
    #[pyo3(signature = (oversample=None))]
    #[allow(clippy::type_complexity)]
    fn hfield_layout(
        &self,
        oversample: Option<u32>,
    ) -> PyResult<((u32, u32), (f64, f64, f64, f64), (f64, f64, f64))> {
        let oversample = oversample.unwrap_or(rse_core::DEFAULT_OVERSAMPLE);
        let layout = self.inner.hfield_layout(oversample).map_err(hfield_error)?;
        let ([rx, ry, elevation, base], [x, y, z]) = (layout.size, layout.pos);
        Ok((
            (layout.nrow, layout.ncol),
            (rx, ry, elevation, base),
            (x, y, z),
        ))
    }

    /// `(nrow, ncol)` of `hfield(oversample)`.
    #[pyo3(signature = (oversample=None))]
    fn hfield_shape(&self, oversample: Option<u32>) -> PyResult<(u32, u32)> {
        let oversample = oversample.unwrap_or(rse_core::DEFAULT_OVERSAMPLE);
        self.inner.hfield_shape(oversample).map_err(hfield_error)
    }

    /// Writes the samples into `out`, a writable C-contiguous float32 array
    /// of `hfield_shape(oversample)`, for a live height field whose surface
    /// is `z0` at 0 and `z0 + elevation` at 1: `(top − z0) / elevation`.
    /// Nothing is allocated; a wrong shape or a top outside that range is a
    /// `ValueError` and leaves `out` as it was.
    #[pyo3(signature = (out, oversample=None, z0=0.0, elevation=1.0))]
    fn hfield_into(
        &self,
        py: Python<'_>,
        out: &Bound<'_, PyArray2<f32>>,
        oversample: Option<u32>,
        z0: f64,
        elevation: f64,
    ) -> PyResult<()> {
        let oversample = oversample.unwrap_or(rse_core::DEFAULT_OVERSAMPLE);
        let (nrow, ncol) = self.inner.hfield_shape(oversample).map_err(hfield_error)?;
        let shape = out.shape().to_vec();
        if shape != [nrow as usize, ncol as usize] {
            return Err(PyValueError::new_err(format!(
                "out has shape {shape:?}, but the height field of this terrain at oversample {oversample} is ({nrow}, {ncol})"
            )));
        }
        let mut view = writable_samples(out, "out")?;
        let slice = view
            .as_slice_mut()
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let inner = &self.inner;
        py.detach(|| inner.hfield_into(oversample, z0, elevation, slice))
            .map_err(hfield_error)
    }

    /// The obstacles as drawn for this world, one dict each, with the
    /// keys of `drawn` in `rse.json`: `kind`, `height`, and `angle`, `p1`,
    /// `p2`, `sigma` where they apply.
    #[getter]
    fn drawn<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let json = serde_json::to_string(self.inner.drawn()).expect("drawn obstacles serialise");
        py.import("json")?.call_method1("loads", (json,))
    }

    /// The ramps laid on this world (crossing ramps as two), one dict each:
    /// `cells` (`[x0, y0, x1, y1]`, inclusive), `along_y`, `ascending`
    /// (climbing toward larger coordinates), `rise` (steps, after the
    /// difficulty).
    #[getter]
    fn ramps<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let json = serde_json::to_string(self.inner.ramps()).expect("ramps serialise");
        py.import("json")?.call_method1("loads", (json,))
    }

    /// Each rising ramp's wedge as its corners, float64 `(n, 3)` metres:
    /// its rectangle's four on the ground, then those on its plane above
    /// the ground (a convex solid: their hull is the wedge).
    fn wedges<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        let t = &self.inner;
        t.ramps()
            .iter()
            .filter(|r| r.rise > 0)
            .map(|r| {
                rows(
                    py,
                    r.wedge_corners(t.block_size(), t.base(), t.step_height()),
                )
            })
            .collect()
    }

    /// The closed terrain mesh (docs/meshes.md): `(vertices, faces)`, float32
    /// `(n, 3)` metres and uint32 `(m, 3)`, counter-clockwise from outside.
    fn mesh<'py>(&self, py: Python<'py>) -> (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<u32>>) {
        let terrain = &self.inner;
        let mesh = py.detach(|| terrain.mesh());
        (
            rows(py, mesh.vertices().to_vec()),
            rows(py, mesh.triangles().to_vec()),
        )
    }

    /// The box set: float64 `(n, 6)` rows `cx, cy, cz, hx, hy, hz`
    /// (centre and half sizes, metres); boxes stand on `z = 0`, their union
    /// is the solid, and they may overlap inside it.
    fn boxes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let boxes = self.inner.boxes();
        rows(
            py,
            boxes
                .iter()
                .map(|b| {
                    let ([cx, cy, cz], [hx, hy, hz]) = (b.center, b.half_size);
                    [cx, cy, cz, hx, hy, hz]
                })
                .collect(),
        )
    }

    /// An MJCF model of the terrain (floor, light, the boxes as static
    /// geoms) for `mujoco.MjModel.from_xml_string`. To fit it into a
    /// robot's model: `fragment=True` leaves out the globals (compiler,
    /// options, visual, light, floor: the robot's model has its own),
    /// `prefix` goes before every name, `offset` moves the terrain (metres,
    /// `(x, y, z)`; None: where it is),
    /// `friction` sets the geoms' (one number: sliding; three: MuJoCo's
    /// sliding, torsional, rolling). Attach it with `mujoco.MjSpec`:
    /// `robot.attach(mujoco.MjSpec.from_string(terrain.mjcf(fragment=True)),
    /// prefix="terrain/", frame=robot.worldbody.add_frame())`.
    #[pyo3(signature = (*, fragment=false, prefix="", offset=None, friction=None))]
    fn mjcf<'py>(
        &self,
        py: Python<'py>,
        fragment: bool,
        prefix: &str,
        offset: Option<Bound<'py, PyAny>>,
        friction: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let offset = offset.map_or(Ok([0.0; 3]), |o| {
            crate::args::reals::<3>("offset", &o, "(1.0, -2.0, 0.0)")
        })?;
        let xml = rse_world::mjcf(&self.inner).map_err(|e| world_error(py, &e))?;
        py.import("rse._adapters.mjcf")?.getattr("adapt")?.call1((
            xml,
            fragment,
            prefix,
            (offset[0], offset[1], offset[2]),
            friction,
        ))
    }

    /// The preview as PNG bytes (the world folder's `preview.png`: the map,
    /// north up, and its legend under it):
    /// `cell_pixels` pixels per cell, by default as many as keep the image
    /// near 512 pixels wide.
    #[pyo3(signature = (cell_pixels=None))]
    fn preview<'py>(
        &self,
        py: Python<'py>,
        cell_pixels: Option<u32>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let png =
            rse_core::preview::png(&self.inner, cell_pixels).map_err(|e| core_error(py, &e))?;
        Ok(PyBytes::new(py, &png))
    }

    /// The heightmap as CSV text (the world folder's `heightmap.csv`, what
    /// `rse-gen heightmap` prints): one row per y from 0, heights in steps.
    fn heightmap_csv(&self) -> String {
        self.inner.heightmap().to_csv()
    }

    /// Writes the terrain to `path`, by its suffix: the mesh as OBJ (with
    /// its `.mtl` beside it), STL or GLB; the preview as PNG; the
    /// heightmap as CSV.
    fn save(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        let suffix = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let text = match suffix.as_deref() {
            Some("png") => Some(self.preview(py, None)?.as_bytes().to_vec()),
            Some("csv") => Some(self.heightmap_csv().into_bytes()),
            _ => None,
        };
        match text {
            Some(bytes) => rse_world::write_atomically(&path, &bytes),
            None => rse_world::write_mesh(&self.inner.mesh(), self.inner.globals(), &path),
        }
        .map_err(|e| world_error(py, &e))
    }

    fn __repr__(&self) -> String {
        let grid = self.inner.grid();
        format!(
            "<rse.Terrain {}x{} seed={} index={}>",
            grid.nx,
            grid.ny,
            self.inner.seed(),
            self.inner.index()
        )
    }
}

/// A radius argument: a finite length of 0 m or more, else `ValueError`.
pub fn check_radius(name: &str, radius: f64) -> PyResult<()> {
    rse_core::spawn::check_radius(radius)
        .map(drop)
        .map_err(|why| pyo3::exceptions::PyValueError::new_err(format!("{name}: {why}")))
}

/// A height field error as `ValueError`.
fn hfield_error(e: rse_core::HFieldError) -> PyErr {
    PyValueError::new_err(e.to_string())
}
