//! `Terrain`: one world as generated (heightmap, units, seed pair, drawn
//! obstacles), its accessors and serialisation. Made by `generate`; its
//! mesh, height field, spawn points and probe are methods written beside
//! their algorithms (`mesh`, `hfield`, `spawn`, `probe`).

use serde::{Deserialize, Serialize};

use crate::difficulty::Difficulty;
use crate::globals::{Globals, Grid};
use crate::heightmap::Heightmap;
use crate::obstacle::DrawnObstacle;
use crate::ramp::Ramp;

/// One generated RSE: the heightmap, its units, and what was drawn for it.
///
/// Serialises without its heightmap (the cells go apart, as raw data):
/// [`Terrain::from_parts`] puts the two back together.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Terrain {
    grid: Grid,
    #[serde(skip, default = "no_cells")]
    heightmap: Heightmap,
    /// The globals it was generated with, as one value (an atlas's: its
    /// first tile's scheme's; its grid is `grid`), so a global added to
    /// the scheme reaches everything that reads a terrain.
    globals: Globals,
    seed: u64,
    index: u64,
    difficulty: Difficulty,
    drawn: Vec<DrawnObstacle>,
    /// The ramps laid on it, in table order (none: no key, so a terrain
    /// without ramps serialises as before they were).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    ramps: Vec<Ramp>,
}

/// The heightmap of a deserialised terrain until its cells are put in.
fn no_cells() -> Heightmap {
    Heightmap::zeros(0, 0)
}

impl Terrain {
    /// World `index` of `seed` at `difficulty`: `heightmap` on `grid` in the
    /// units of `globals`, with the obstacles `drawn` for it.
    pub(crate) fn new(
        grid: Grid,
        heightmap: Heightmap,
        globals: &Globals,
        (seed, index): (u64, u64),
        difficulty: Difficulty,
        drawn: Vec<DrawnObstacle>,
    ) -> Terrain {
        Terrain {
            grid,
            heightmap,
            globals: *globals,
            seed,
            index,
            difficulty,
            drawn,
            ramps: Vec::new(),
        }
    }

    /// The terrain with `ramps` laid on it (their staircases already in
    /// its heightmap).
    pub(crate) fn with_ramps(mut self, ramps: Vec<Ramp>) -> Terrain {
        self.ramps = ramps;
        self
    }

    /// A terrain of given heights (an atlas's map): no obstacles drawn,
    /// world 0 of `seed`, the units of `globals`.
    pub(crate) fn from_heightmap(
        grid: Grid,
        heightmap: Heightmap,
        globals: &Globals,
        seed: u64,
    ) -> Terrain {
        Terrain::new(
            grid,
            heightmap,
            globals,
            (seed, 0),
            Difficulty::FULL,
            Vec::new(),
        )
    }

    /// A terrain from its JSON (serde, without heightmap) and its cells,
    /// row by row from y = 0: what a Python pickle carries. `None` when
    /// the JSON does not parse, the cells do not fill its grid, or the
    /// grid or units are none a scheme could give (a 0×0 grid, a block of
    /// no size, frames every 0 cells): every method may then rely on them.
    pub fn from_parts(json: &str, cells: Vec<u16>) -> Option<Terrain> {
        use crate::limits::{MAX_CELLS, MAX_EXTENT, MAX_LATTICE_UNITS, MIN_LENGTH};
        let mut terrain: Terrain = serde_json::from_str(json).ok()?;
        let Grid {
            nx,
            ny,
            frame_period,
        } = terrain.grid;
        let length = |v: f64| v.is_finite() && v >= MIN_LENGTH;
        let sound = nx >= 1
            && ny >= 1
            && u64::from(nx) * u64::from(ny) <= MAX_CELLS
            && u64::from(nx.max(ny)) <= MAX_LATTICE_UNITS
            && frame_period.is_none_or(|p| p >= 2)
            && length(terrain.block_size())
            && length(terrain.step_height())
            && (terrain.base() == 0.0 || length(terrain.base()))
            && f64::from(nx.max(ny)) * terrain.block_size() <= MAX_EXTENT
            && terrain.base() / terrain.step_height() + 1.0 <= MAX_LATTICE_UNITS as f64
            // Units a scheme could give (a step of 1e300 m cannot).
            && terrain.globals.validate().is_ok();
        if !sound {
            return None;
        }
        terrain.heightmap = Heightmap::from_cells(nx, ny, cells)?;
        Some(terrain)
    }

    /// The JSON of [`Terrain::from_parts`].
    ///
    /// # Panics
    /// Never: every field serialises.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("a terrain serialises")
    }

    /// The grid, with where its pallet frames are.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// Heights in steps.
    pub fn heightmap(&self) -> &Heightmap {
        &self.heightmap
    }

    /// The globals it was generated with (an atlas's: its first tile's
    /// scheme's, whose grid is not the map's: see [`Terrain::grid`]).
    pub fn globals(&self) -> &Globals {
        &self.globals
    }

    /// Cell side in metres.
    pub fn block_size(&self) -> f64 {
        self.globals.block_size
    }

    /// Step height in metres.
    pub fn step_height(&self) -> f64 {
        self.globals.step_height
    }

    /// Slab thickness under the grid, metres.
    pub fn base(&self) -> f64 {
        self.globals.base
    }

    /// Top of cell `(x, y)` in metres: `base + h·step`.
    pub fn elevation(&self, x: u32, y: u32) -> f64 {
        self.base() + f64::from(self.heightmap.get(x, y)) * self.step_height()
    }

    /// The batch's base seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The world's index in its batch.
    pub fn index(&self) -> u64 {
        self.index
    }

    /// The difficulty its heights were scaled to.
    pub fn difficulty(&self) -> Difficulty {
        self.difficulty
    }

    /// The obstacles as drawn for this world, in table order.
    pub fn drawn(&self) -> &[DrawnObstacle] {
        &self.drawn
    }

    /// The ramps laid on it, in table order (crossing ramps as two).
    pub fn ramps(&self) -> &[Ramp] {
        &self.ramps
    }
}
