//! `rse.Terrain`: one generated world as numpy arrays, with its mesh, box
//! set, MJCF and mesh files.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::world_error;

/// One generated RSE.
#[pyclass(module = "rse", frozen)]
pub struct Terrain {
    pub inner: rse_core::Terrain,
}

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
    /// Heights in steps, shape `(ny, nx)`, `heights[y, x]`; read-only.
    #[getter]
    fn heights<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u16>>> {
        let map = self.inner.heightmap();
        let shape = (map.ny() as usize, map.nx() as usize);
        let array = Array2::from_shape_vec(shape, map.cells().to_vec()).expect("ny × nx cells");
        read_only(array.into_pyarray(py))
    }

    /// Top of every cell in metres (`base + h·step`), shape `(ny, nx)`; read-only.
    #[getter]
    fn elevation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let grid = self.inner.grid();
        let values = (0..grid.ny)
            .flat_map(|y| (0..grid.nx).map(move |x| (x, y)))
            .map(|(x, y)| self.inner.elevation(x, y))
            .collect();
        let array = Array2::from_shape_vec((grid.ny as usize, grid.nx as usize), values)
            .expect("ny × nx cells");
        read_only(array.into_pyarray(py))
    }

    #[getter]
    fn block_size(&self) -> f64 {
        self.inner.block_size()
    }

    #[getter]
    fn step_height(&self) -> f64 {
        self.inner.step_height()
    }

    #[getter]
    fn base(&self) -> f64 {
        self.inner.base()
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.inner.seed()
    }

    #[getter]
    fn index(&self) -> u64 {
        self.inner.index()
    }

    /// The difficulty its obstacle heights were scaled to (1: as drawn).
    #[getter]
    fn difficulty(&self) -> f64 {
        self.inner.difficulty().get()
    }

    /// The obstacles as drawn for this world: one dict each (`type`,
    /// `height`, and `angle`, `p1`, `p2`, `sigma` where they apply).
    #[getter]
    fn drawn<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.inner
            .drawn()
            .iter()
            .map(|d| {
                let dict = PyDict::new(py);
                dict.set_item("type", d.kind.name())?;
                dict.set_item("height", d.height)?;
                if let Some(angle) = d.angle {
                    dict.set_item("angle", angle)?;
                }
                if let Some([x, y]) = d.p1 {
                    dict.set_item("p1", (x, y))?;
                }
                if let Some([x, y]) = d.p2 {
                    dict.set_item("p2", (x, y))?;
                }
                if let Some(sigma) = d.sigma {
                    dict.set_item("sigma", sigma)?;
                }
                Ok(dict)
            })
            .collect()
    }

    /// The closed terrain mesh (SPEC §6): `(vertices, faces)`, float32
    /// `(n, 3)` metres and uint32 `(m, 3)`, counter-clockwise from outside.
    fn mesh<'py>(&self, py: Python<'py>) -> (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<u32>>) {
        let terrain = &self.inner;
        let mesh = py.detach(|| terrain.mesh());
        (
            rows(py, mesh.vertices().to_vec()),
            rows(py, mesh.triangles().to_vec()),
        )
    }

    /// The merged box set: float64 `(n, 6)` rows `cx, cy, cz, hx, hy, hz`
    /// (centre and half sizes, metres); boxes stand on `z = 0`.
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
    /// geoms) for `mujoco.MjModel.from_xml_string`.
    fn mjcf(&self, py: Python<'_>) -> PyResult<String> {
        rse_world::mjcf(&self.inner).map_err(|e| world_error(py, &e))
    }

    /// Writes the mesh as OBJ (with its `.mtl` beside it), STL or GLB, by
    /// the path's suffix.
    fn save(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        let mesh = self.inner.mesh();
        rse_world::write_mesh(&mesh, &path).map_err(|e| world_error(py, &e))
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
