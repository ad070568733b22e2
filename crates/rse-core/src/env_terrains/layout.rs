//! Where each environment's samples go in the caller's buffer: one slot
//! per environment or one tile of a shared map, the buffer's shape, MuJoCo's
//! `size` and `pos` of a slot or of the map, and the writes.

use rayon::prelude::*;

use super::EnvTerrains;
use super::options::{EnvError, EnvLayout, EnvOptions, bad};
use crate::globals::Grid;
use crate::hfield::{MAX_HFIELD_SAMPLES, field_geometry, hfield_shape_of};
use crate::terrain::Terrain;

/// One environment's field, `(nrow, ncol)`, and the whole buffer,
/// `(slots, rows, columns)`.
pub(super) struct Shapes {
    pub env_shape: (usize, usize),
    pub shape: (usize, usize, usize),
}

/// The shape of one environment's field, `(nrow, ncol)`, and of the whole
/// buffer, `(slots, rows, columns)`, for `options.num_envs` environments of `grid` laid
/// out as `options` say; refused, naming the argument, past MuJoCo's or
/// memory's limits.
pub(super) fn buffer_shape_of(grid: Grid, options: EnvOptions) -> Result<Shapes, EnvError> {
    // Each option in its range first (`cols` of 1 or more among them),
    // whoever built the options.
    super::EnvRequest::given(&options).check_ranges()?;
    let n = options.num_envs;
    let k = options.oversample;
    let (nrow, ncol) = hfield_shape_of(grid, k)?;
    let env_shape = (nrow as usize, ncol as usize);
    let shape = match options.layout {
        EnvLayout::Slots => (n, env_shape.0, env_shape.1),
        EnvLayout::Tiles { cols, border } => {
            let rows = n.div_ceil(cols as usize) as u64;
            let b = u64::from(border);
            let side = |tiles: u64, cells: u32| {
                tiles
                    .saturating_mul(u64::from(cells) + b)
                    .saturating_add(b)
                    .saturating_mul(u64::from(k))
            };
            let (r, c) = (side(rows, grid.ny), side(u64::from(cols), grid.nx));
            if r.saturating_mul(c) > MAX_HFIELD_SAMPLES {
                return Err(bad(
                    "cols",
                    format!("a {r}x{c} tile map is more than {MAX_HFIELD_SAMPLES} samples"),
                ));
            }
            (1, r as usize, c as usize)
        }
    };
    let total = (shape.0 as u64)
        .saturating_mul(shape.1 as u64)
        .saturating_mul(shape.2 as u64);
    if total > 1 << 32 {
        return Err(bad(
            "num_envs",
            format!("{total} samples in all, more than 2^32 (16 GiB of float32)"),
        ));
    }
    Ok(Shapes { env_shape, shape })
}

/// The memory `num_envs` environments of `scheme` take at their peak, bytes,
/// as [`EnvTerrains::new`] builds them: the samples (float32, allocated by
/// the caller), each environment's terrain twice (made, then stored) and
/// its bookkeeping, and `extra_per_env` bytes a caller keeps per
/// environment (Python's episode, difficulty and origin arrays). Refused
/// as [`EnvTerrains::new`] refuses a shape; computed before anything is
/// allocated, so a caller can refuse a pool that cannot fit.
pub fn env_pool_bytes(
    scheme: &crate::Scheme,
    options: EnvOptions,
    extra_per_env: u64,
) -> Result<u64, EnvError> {
    mix_pool_bytes(std::slice::from_ref(scheme), options, extra_per_env)
}

/// [`env_pool_bytes`] of a mix of `schemes` ([`EnvTerrains::mixed`]): the
/// slots of the largest grid, each environment's terrain as large as the
/// largest scheme's.
pub fn mix_pool_bytes(
    schemes: &[crate::Scheme],
    options: EnvOptions,
    extra_per_env: u64,
) -> Result<u64, EnvError> {
    if schemes.is_empty() {
        return Err(bad("schemes", "no scheme to draw terrains from"));
    }
    let Shapes { shape, .. } = buffer_shape_of(super::mix::largest_grid(schemes), options)?;
    let samples = (shape.0 as u64)
        .saturating_mul(shape.1 as u64)
        .saturating_mul(shape.2 as u64)
        .saturating_mul(4);
    let cells = schemes
        .iter()
        .map(|s| s.grid().cells() as u64)
        .max()
        .unwrap_or(0);
    let obstacles = schemes
        .iter()
        .map(|s| s.obstacles().len() as u64)
        .max()
        .unwrap_or(0);
    let terrain = (std::mem::size_of::<Terrain>() as u64)
        .saturating_add(cells.saturating_mul(std::mem::size_of::<u16>() as u64))
        .saturating_add(
            obstacles.saturating_mul(std::mem::size_of::<crate::obstacle::DrawnObstacle>() as u64),
        );
    let per_env = terrain
        .saturating_mul(2)
        .saturating_add(std::mem::size_of::<[f64; 3]>() as u64 + 8)
        .saturating_add(extra_per_env);
    Ok(samples.saturating_add((options.num_envs as u64).saturating_mul(per_env)))
}

impl EnvTerrains {
    /// The buffer's shape: `(num_envs, nrow, ncol)` for slots, `(1, rows,
    /// columns)` of the whole map for tiles.
    pub fn buffer_shape(&self) -> (usize, usize, usize) {
        self.shape
    }

    /// One environment's field: `(nrow, ncol)`.
    pub fn field_shape(&self) -> (usize, usize) {
        self.env_shape
    }

    /// MuJoCo's `size` of one slot's field (slots) or of the map (tiles):
    /// `[radius_x, radius_y, elevation, base]`, the surface at sample 1
    /// being the highest top any of its schemes can have above the geom
    /// (placed at z = 0) and the box under it one step deep (the deepest
    /// step of a mix).
    pub fn hfield_size(&self) -> [f64; 4] {
        self.geometry().0
    }

    /// Where the field's geom goes in its own frame (slots: the terrain's,
    /// corner at the origin; tiles: the map's), metres: the centre, z = 0.
    pub fn hfield_pos(&self) -> [f64; 3] {
        self.geometry().1
    }

    /// [`hfield_size`](Self::hfield_size) and
    /// [`hfield_pos`](Self::hfield_pos), by the formula every height field
    /// of rse uses.
    fn geometry(&self) -> ([f64; 4], [f64; 3]) {
        let globals = self.scheme.globals();
        let spacing = globals.block_size / f64::from(self.options.oversample);
        let (width, depth) = (self.shape.2 as f64 * spacing, self.shape.1 as f64 * spacing);
        let step = self
            .schemes()
            .iter()
            .map(|s| s.globals().step_height)
            .fold(globals.step_height, f64::max);
        field_geometry(width, depth, spacing, self.elevation, step, 0.0)
    }

    /// The sample of a cell of height 0 (`base / elevation`): what the
    /// borders of a tile map hold, which [`write`](Self::write) never
    /// touches; fill a new buffer with it first. In a mix of bases, the
    /// lowest: no border stands above a tile's ground.
    pub fn ground_sample(&self) -> f32 {
        let base = self
            .schemes()
            .iter()
            .map(|s| s.globals().base)
            .fold(self.scheme.globals().base, f64::min);
        (base / self.elevation) as f32
    }

    /// Environment `e`'s field's first sample in the buffer, `(row,
    /// column)`: its tile's corner in the map (tiles), `(0, 0)` in its own
    /// slot (slots). Its field is the [`field_shape`](Self::field_shape)
    /// from there.
    pub fn field_corner(&self, e: usize) -> (usize, usize) {
        let (x0, y0) = self.tile_origin(e);
        let k = self.options.oversample as usize;
        (y0 as usize * k, x0 as usize * k)
    }

    /// Environment `e`'s tile's first cell in the map, `(x0, y0)`; `(0, 0)`
    /// for slots.
    pub(super) fn tile_origin(&self, e: usize) -> (u32, u32) {
        match self.options.layout {
            EnvLayout::Slots => (0, 0),
            EnvLayout::Tiles { cols, border } => {
                let grid = self.slot;
                let (row, col) = ((e / cols as usize) as u32, (e % cols as usize) as u32);
                (
                    border + col * (grid.nx + border),
                    border + row * (grid.ny + border),
                )
            }
        }
    }

    /// Refuses an `out` that is not the whole buffer.
    pub(super) fn check_out(&self, out: &[f32]) -> Result<(), EnvError> {
        let (n, rows, cols) = self.shape;
        if out.len() != n * rows * cols {
            return Err(bad(
                "out",
                format!("{} samples, but the buffer is {n}x{rows}x{cols}", out.len()),
            ));
        }
        Ok(())
    }

    /// Writes the samples of `envs` into `out` (the whole buffer,
    /// [`buffer_shape`](Self::buffer_shape), row-major float32): each into
    /// its slot or tile, the rest of `out` untouched. A sample is `top /
    /// elevation` ([`hfield_size`](Self::hfield_size)), in `[0, 1]`.
    pub fn write(&self, envs: &[usize], out: &mut [f32]) -> Result<(), EnvError> {
        self.check_envs(envs, None)?;
        self.check_out(out)?;
        let mut named = vec![false; self.num_envs()];
        for &e in envs {
            named[e] = true;
        }
        match self.options.layout {
            EnvLayout::Slots => {
                out.par_chunks_mut(self.slot_len())
                    .enumerate()
                    .filter(|(e, _)| named[*e])
                    .for_each(|(e, slot)| self.write_slot(&self.terrains[e], slot));
            }
            EnvLayout::Tiles { cols, .. } => {
                // One chunk per tile row (with the border rows above it):
                // tiles of different rows are written in parallel.
                let per_row = cols as usize;
                out.par_chunks_mut(self.band_len())
                    .take(self.num_envs().div_ceil(per_row))
                    .enumerate()
                    .for_each(|(row, band)| {
                        let first = row * per_row;
                        for e in
                            (first..(first + per_row).min(self.num_envs())).filter(|&e| named[e])
                        {
                            self.write_tile(e, &self.terrains[e], band);
                        }
                    });
            }
        }
        Ok(())
    }

    /// Samples in one slot.
    pub(super) fn slot_len(&self) -> usize {
        self.env_shape.0 * self.env_shape.1
    }

    /// Samples in one tile row of the map with the border rows above it.
    pub(super) fn band_len(&self) -> usize {
        let b = match self.options.layout {
            EnvLayout::Tiles { border, .. } => border as usize,
            EnvLayout::Slots => 0,
        };
        (b * self.options.oversample as usize + self.env_shape.0) * self.shape.2
    }

    /// Writes `terrain` into a slot: a terrain smaller than the slot (a
    /// mix of grids) in its first cells, the ground plane (0) around it.
    pub(super) fn write_slot(&self, terrain: &Terrain, slot: &mut [f32]) {
        let k = self.options.oversample;
        if self.smaller(terrain) {
            slot.fill(0.0);
        }
        terrain.fill_hfield_rows(k, 0.0, self.elevation, slot, self.env_shape.1);
    }

    /// Whether `terrain` fills less than a slot (a mix of grids).
    fn smaller(&self, terrain: &Terrain) -> bool {
        let grid = terrain.grid();
        (grid.nx, grid.ny) != (self.slot.nx, self.slot.ny)
    }

    /// Writes `terrain` as environment `e`'s tile into the band of its tile
    /// row.
    pub(super) fn write_tile(&self, e: usize, terrain: &Terrain, band: &mut [f32]) {
        let k = self.options.oversample as usize;
        let cols = self.shape.2;
        let border_rows = band.len() / cols - self.env_shape.0;
        let (x0, _) = self.tile_origin(e);
        let at = border_rows * cols + x0 as usize * k;
        if self.smaller(terrain) {
            // The tile's cells past the terrain: ground, as the borders.
            let ground = self.ground_sample();
            let width = self.slot.nx as usize * k;
            for row in band[at..].chunks_mut(cols).take(self.env_shape.0) {
                row[..width].fill(ground);
            }
        }
        terrain.fill_hfield_rows(k as u32, 0.0, self.elevation, &mut band[at..], cols);
    }
}

/// The chunks of `size` samples at `indices` (ascending, distinct, in
/// range) of `out`, each borrowed apart so threads can fill them.
pub(super) fn chunks_at(
    out: &mut [f32],
    size: usize,
    indices: impl Iterator<Item = usize>,
) -> Vec<&mut [f32]> {
    let mut chunks = out.chunks_mut(size).enumerate();
    indices
        .map(|i| {
            chunks
                .find_map(|(j, chunk)| (j == i).then_some(chunk))
                .expect("indices ascending and inside the buffer")
        })
        .collect()
}
