//! `rse.Atlas`: the tiled terrain of `rse-gen atlas` with its origins, tile
//! list and flat patches as numpy arrays, and `write()` for the same world
//! folder, byte for byte.

use numpy::ndarray::{Array3, Array4};
use numpy::{IntoPyArray, PyArray3, PyArray4};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rse_core::{AtlasConfig, Difficulty};
use rse_world::{AtlasRecord, NamedScheme, atlas_json};

use crate::args;
use crate::batch::{outcome_name, templates};
use crate::errors::{core_error, world_error};
use crate::keywords::{self, KeywordGroup as _, keyword_group};
use crate::options::{WorldKeywords, world_keywords_text};
use crate::scheme::{Scheme, difficulty_arg};
use crate::terrain::{Terrain, check_radius};

/// A grid of `rows × cols` tiles for curricula: rows run along x and go
/// from the easiest difficulty to the hardest, columns run along y and
/// cycle through `schemes`. Tile `(r, c)` is world `r·cols + c` of `seed`.
#[pyclass(module = "rse", frozen)]
pub struct Atlas {
    inner: rse_core::Atlas,
    schemes: Vec<NamedScheme>,
    record: AtlasRecord,
}

/// The schemes given: `Scheme` objects or paths to scheme files. A path's
/// file name is recorded; a `Scheme` read from a file records that file's
/// name, one built in Python `scheme_<i>.csv`.
fn named_schemes(py: Python<'_>, schemes: &[Bound<'_, PyAny>]) -> PyResult<Vec<NamedScheme>> {
    let file_name = |path: &str| {
        std::path::Path::new(path)
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
    };
    schemes
        .iter()
        .enumerate()
        .map(|(i, item)| {
            if let Ok(scheme) = item.cast::<Scheme>() {
                let scheme = rse_core::Scheme::clone(&scheme.get().inner);
                let name = scheme
                    .file()
                    .and_then(file_name)
                    .unwrap_or_else(|| format!("scheme_{i}.csv"));
                return Ok(NamedScheme { name, scheme });
            }
            let path: std::path::PathBuf = item.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "schemes[{i}]: expected an rse.Scheme or a path, got {}",
                    item.get_type()
                        .name()
                        .map_or_else(|_| "?".into(), |n| n.to_string())
                ))
            })?;
            let scheme = rse_core::Scheme::load(&path).map_err(|e| core_error(py, &e))?;
            let name = file_name(&path.to_string_lossy()).unwrap_or_default();
            Ok(NamedScheme { name, scheme })
        })
        .collect()
}

keyword_group! {
    /// What `Atlas(...)` takes beyond its schemes and tiles.
    pub struct AtlasKeywords {
        /// `seed=` (default: the first scheme's `# seed:`).
        seed: u64,
        /// `border=`: cells of ground between tiles.
        border: u32,
        /// `difficulty=`: `(easiest, hardest)` along the rows.
        difficulty: Py<PyAny>,
        /// `spawn_radius=`, metres.
        spawn_radius: f64,
        /// `flat_patches=`: patches a tile.
        flat_patches: u32,
        /// `patch_radius=`, metres.
        patch_radius: f64,
        /// `max_step=`: the steps a patch may hold.
        max_step: u16,
    }
}

#[pymethods]
impl Atlas {
    /// `Atlas(schemes, rows, cols, *, seed=None, …)`: the constructor's
    /// signature, from its keyword group.
    #[classattr]
    fn __signature__(py: Python<'_>) -> PyResult<Py<PyAny>> {
        keywords::signature(py, &["schemes", "rows", "cols"], &[AtlasKeywords::NAMES])
    }

    #[new]
    #[pyo3(signature = (schemes, rows, cols, **options))]
    fn new(
        py: Python<'_>,
        schemes: Vec<Bound<'_, PyAny>>,
        rows: u32,
        cols: u32,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let AtlasKeywords {
            seed,
            border,
            difficulty,
            spawn_radius,
            flat_patches,
            patch_radius,
            max_step,
        } = keywords::read::<AtlasKeywords>(py, "Atlas", options)?;
        let difficulty = match difficulty {
            None => None,
            Some(d) => {
                let [easiest, hardest] = args::reals("difficulty", d.bind(py), "(0.0, 1.0)")?;
                Some((difficulty_arg(easiest)?, difficulty_arg(hardest)?))
            }
        };
        let schemes = named_schemes(py, &schemes)?;
        let options = AtlasConfig {
            rows,
            cols,
            seed,
            border,
            difficulty,
            spawn_radius,
            flat_patches,
            patch_radius,
            max_step,
        }
        .resolve(schemes.iter().map(|s| &s.scheme));
        if let Some(first) = schemes.first() {
            // The map's heights, a terrain per tile, and its patches.
            let grid = first.scheme.grid();
            let [nx, ny] = options.map_cells([grid.nx, grid.ny]);
            let tiles = u64::from(rows) * u64::from(cols);
            let bytes = nx
                .saturating_mul(ny)
                .saturating_mul(2)
                .saturating_add(tiles.saturating_mul(crate::memory::terrain_bytes(&first.scheme)))
                .saturating_add(tiles.saturating_mul(u64::from(options.patches.count) * 48));
            crate::memory::fits(
                "rows",
                bytes,
                format_args!("an atlas of {rows}x{cols} tiles"),
            )?;
        }
        let inner = py
            .detach(|| rse_world::atlas_of(&schemes, &options))
            .map_err(|e| world_error(py, &e))?;
        let record = AtlasRecord::new(&schemes, &options);
        Ok(Atlas {
            inner,
            schemes,
            record,
        })
    }

    /// The whole map as one `Terrain` (`heights`, `mesh()`, `boxes()`,
    /// `mjcf()`, `save()`), in the atlas's frame: the outer corner of cell
    /// (0, 0) at the origin.
    #[getter]
    fn terrain(&self) -> Terrain {
        Terrain {
            inner: self.inner.terrain().clone(),
            scheme: None,
        }
    }

    /// Tiles along x: the difficulty levels.
    #[getter]
    fn rows(&self) -> u32 {
        self.inner.options().rows
    }

    /// Tiles along y.
    #[getter]
    fn cols(&self) -> u32 {
        self.inner.options().cols
    }

    /// Spawn origins `[x, y, z]` in metres, shape `(rows, cols, 3)`: each
    /// tile's centre on the highest top within `spawn_radius` of it.
    #[getter]
    fn origins<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let o = self.inner.options();
        let flat: Vec<f64> = self.inner.tiles().iter().flat_map(|t| t.origin).collect();
        Array3::from_shape_vec((o.rows as usize, o.cols as usize, 3), flat)
            .expect("rows × cols × 3")
            .into_pyarray(py)
    }

    /// The entries of `atlas.json`, one dict per tile, row by row.
    #[getter]
    fn tiles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = atlas_json(&self.inner, &self.record);
        let json = py.import("json")?.call_method1("loads", (text,))?;
        json.get_item("tiles")
    }

    /// `atlas.json` as written by `write()` and `rse-gen atlas`.
    fn to_json(&self) -> String {
        atlas_json(&self.inner, &self.record)
    }

    /// Up to `n` flat patches per tile: centres `[x, y, z]` (metres) of
    /// discs of `radius` metres inside the tile over which every cell is
    /// within `max_step` steps of the others, z the highest top under the
    /// disc. Shape `(rows, cols, min(n, cells of the largest tile), 3)`; a
    /// tile with fewer has NaN rows.
    #[pyo3(signature = (n, radius=None, max_step=0))]
    fn flat_patches<'py>(
        &self,
        py: Python<'py>,
        n: u32,
        radius: Option<f64>,
        max_step: u16,
    ) -> PyResult<Bound<'py, PyArray4<f64>>> {
        let radius = radius.unwrap_or(rse_core::spawn::DEFAULT_PATCH_RADIUS);
        check_radius("radius", radius)?;
        let o = self.inner.options();
        let terrain = self.inner.terrain();
        // At most one patch a cell of the largest tile: rows past that would
        // only ever be NaN, so none are made; what is left must fit memory
        // (a caller's number never sizes an allocation that could abort).
        let most = self
            .inner
            .tiles()
            .iter()
            .map(|t| u64::from(t.region.nx) * u64::from(t.region.ny))
            .max()
            .unwrap_or(0);
        let per_tile = u64::from(n).min(most);
        crate::memory::fits(
            "n",
            u64::from(o.rows)
                .saturating_mul(u64::from(o.cols))
                .saturating_mul(per_tile)
                .saturating_mul(48),
            format_args!("{n} flat patches in each of {} tiles", o.rows * o.cols),
        )?;
        let mut out = Array4::from_elem(
            (o.rows as usize, o.cols as usize, per_tile as usize, 3),
            f64::NAN,
        );
        let found: Vec<_> = py.detach(|| {
            self.inner
                .tiles()
                .iter()
                .map(|t| terrain.flat_patches(t.region, per_tile as u32, radius, max_step))
                .collect()
        });
        for (tile, patches) in self.inner.tiles().iter().zip(found) {
            for (k, point) in patches.into_iter().enumerate() {
                for (axis, v) in point.into_iter().enumerate() {
                    out[[tile.row as usize, tile.col as usize, k, axis]] = v;
                }
            }
        }
        Ok(out.into_pyarray(py))
    }

    #[doc = concat!("write($self, out, *, ", rse_world::for_each_world_option!(world_keywords_text), ")\n--\n")]
    /// Writes the atlas's world folder at `out`, as `rse-gen atlas` does
    /// (the same bytes): whole or not at all; an identical folder is left
    /// alone (returns `"skipped"`), a different one refused unless
    /// `force=True`. Returns `"written"`, `"skipped"` or `"replaced"`.
    /// Keywords: the world options every writer takes.
    #[pyo3(signature = (out, **options), text_signature = None)]
    // The signature heading the docstring is Python's, not markdown.
    #[allow(clippy::doc_markdown)]
    fn write(
        &self,
        py: Python<'_>,
        out: std::path::PathBuf,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<&'static str> {
        let world = keywords::read::<WorldKeywords>(py, "write", options)?;
        let options = world.options(py, Difficulty::FULL)?;
        let templates = templates(py, world.template.as_deref())?;
        let force = world.force.unwrap_or(false);
        let atlas_options = *self.inner.options();
        let (outcome, _) = py
            .detach(|| {
                rse_world::write_atlas(
                    &self.schemes,
                    &atlas_options,
                    &out,
                    &options,
                    &templates,
                    force,
                )
            })
            .map_err(|e| world_error(py, &e))?;
        Ok(outcome_name(outcome))
    }

    fn __repr__(&self) -> String {
        let o = self.inner.options();
        let grid = self.inner.terrain().grid();
        format!(
            "rse.Atlas({} schemes, rows={}, cols={}, seed={}, border={}, difficulty=({}, {}), cells={}x{})",
            self.schemes.len(),
            o.rows,
            o.cols,
            o.seed,
            o.border,
            o.difficulty.0,
            o.difficulty.1,
            grid.nx,
            grid.ny
        )
    }
}
