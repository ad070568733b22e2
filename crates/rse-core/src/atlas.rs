//! An atlas: one terrain made of `rows × cols` tiles for RL curricula, as
//! Isaac Lab's and `legged_gym`'s terrain generators lay them out — rows run
//! along x and are difficulty levels, columns run along y and cycle through
//! the schemes — with a spawn origin and flat patches per tile.

use rayon::prelude::*;

use crate::difficulty::{Difficulty, DifficultyRule};
use crate::generate::generate_by;
use crate::globals::Grid;
use crate::heightmap::Heightmap;
use crate::limits::{MAX_CELLS, MAX_EXTENT};
use crate::scheme::Scheme;
use crate::shared_globals::{Together, unshared};
use crate::spawn::{DEFAULT_PATCH_RADIUS, DEFAULT_SPAWN_RADIUS, Region, check_radius};
use crate::terrain::Terrain;

/// Flat patches to find on every tile (none when `count` is 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchOptions {
    /// At most this many per tile.
    pub count: u32,
    /// Disc radius in metres.
    pub radius: f64,
    /// Largest height difference under a disc, in steps.
    pub max_step: u16,
}

impl Default for PatchOptions {
    fn default() -> Self {
        PatchOptions {
            count: 0,
            radius: DEFAULT_PATCH_RADIUS,
            max_step: 0,
        }
    }
}

/// How to lay out an atlas.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtlasOptions {
    /// Tiles along x: difficulty levels.
    pub rows: u32,
    /// Tiles along y: column `c` uses scheme `c mod (number of schemes)`.
    pub cols: u32,
    /// The base seed of every tile; tile `(r, c)` is world `r·cols + c`.
    pub seed: u64,
    /// Cells of height 0 between tiles and around the outside.
    pub border: u32,
    /// Difficulty of the first row and of the last.
    pub difficulty: (Difficulty, Difficulty),
    /// How the rows' scaled heights are rounded: today's rule, or the one
    /// an older atlas's record names.
    pub rule: DifficultyRule,
    /// Radius in metres of the disc around a tile's centre whose highest
    /// top is the origin's z.
    pub spawn_radius: f64,
    /// Flat patches per tile.
    pub patches: PatchOptions,
}

impl Default for AtlasOptions {
    fn default() -> Self {
        AtlasOptions {
            rows: 1,
            cols: 1,
            seed: 0,
            border: 0,
            difficulty: (
                Difficulty::new(0.0).expect("0 is a difficulty"),
                Difficulty::FULL,
            ),
            rule: DifficultyRule::CURRENT,
            spawn_radius: DEFAULT_SPAWN_RADIUS,
            patches: PatchOptions::default(),
        }
    }
}

/// An atlas as a user gives it (ruff's configuration pattern, as
/// `rse_world::BatchConfig`): the grid of tiles, and `None` for every
/// setting left to the first scheme (`seed`) or to
/// [`AtlasOptions::default`]. The command line and Python fill it with
/// what their user gave; [`resolve`](Self::resolve) is the one place the
/// rest is decided.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AtlasConfig {
    /// Tiles along x.
    pub rows: u32,
    /// Tiles along y.
    pub cols: u32,
    /// Base seed; default the first scheme's `# seed:` (0 without schemes).
    pub seed: Option<u64>,
    /// Border cells.
    pub border: Option<u32>,
    /// Difficulty of the first row and of the last.
    pub difficulty: Option<(Difficulty, Difficulty)>,
    /// Spawn radius, metres.
    pub spawn_radius: Option<f64>,
    /// Flat patches per tile.
    pub flat_patches: Option<u32>,
    /// A flat patch's radius, metres.
    pub patch_radius: Option<f64>,
    /// A flat patch's largest height difference, steps.
    pub max_step: Option<u16>,
}

impl AtlasConfig {
    /// The atlas options for `schemes`: the user's values, the first
    /// scheme's seed, the defaults for the rest.
    pub fn resolve<'a>(self, schemes: impl IntoIterator<Item = &'a Scheme>) -> AtlasOptions {
        let defaults = AtlasOptions::default();
        let first = schemes.into_iter().next();
        AtlasOptions {
            rows: self.rows,
            cols: self.cols,
            seed: first.map_or(self.seed.unwrap_or(0), |scheme| scheme.seed_or(self.seed)),
            border: self.border.unwrap_or(defaults.border),
            difficulty: self.difficulty.unwrap_or(defaults.difficulty),
            rule: defaults.rule,
            spawn_radius: self.spawn_radius.unwrap_or(defaults.spawn_radius),
            patches: PatchOptions {
                count: self.flat_patches.unwrap_or(defaults.patches.count),
                radius: self.patch_radius.unwrap_or(defaults.patches.radius),
                max_step: self.max_step.unwrap_or(defaults.patches.max_step),
            },
        }
    }
}

/// One tile of an atlas.
#[derive(Debug, Clone, PartialEq)]
pub struct Tile {
    /// Row, along x (difficulty level).
    pub row: u32,
    /// Column, along y.
    pub col: u32,
    /// Which of the atlas's schemes it comes from.
    pub scheme: usize,
    /// Base seed of the tile's world (the atlas's).
    pub seed: u64,
    /// World index: `row·cols + col`.
    pub index: u64,
    /// The difficulty its row is drawn at.
    pub difficulty: Difficulty,
    /// The cells it covers in the atlas's grid.
    pub region: Region,
    /// Spawn point `[x, y, z]` in metres in the atlas's frame: the tile's
    /// centre, on the highest top within the spawn radius.
    pub origin: [f64; 3],
    /// Flat patch centres `[x, y, z]` in metres, z the highest top under
    /// the patch.
    pub flat_patches: Vec<[f64; 3]>,
}

/// A built atlas: its terrain and tiles (row by row, `r·cols + c`).
#[derive(Debug, Clone, PartialEq)]
pub struct Atlas {
    terrain: Terrain,
    tiles: Vec<Tile>,
    options: AtlasOptions,
}

/// Why an atlas cannot be built; the field is the option's name.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AtlasError {
    /// No scheme given.
    #[error("an atlas needs at least one scheme")]
    NoScheme,
    /// An option out of range.
    #[error("{field}: {reason}")]
    BadOption {
        /// The option: `rows`, `cols`, `difficulty`, `spawn_radius`, …
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// Two schemes whose tiles cannot sit side by side.
    #[error(
        "scheme {other} has {field} {found}, but scheme 0 has {expected}: every tile of an atlas must share it"
    )]
    Mismatch {
        /// `block_size`, `step_height`, `base` or `size`.
        field: &'static str,
        /// The position of the scheme that differs.
        other: usize,
        /// That scheme's value, as text.
        found: String,
        /// Scheme 0's value.
        expected: String,
    },
    /// More cells or metres than one terrain may have.
    #[error(
        "the atlas would be {nx}x{ny} cells ({metres} m across); at most {MAX_CELLS} cells and {MAX_EXTENT} m"
    )]
    TooLarge {
        /// Cells along x.
        nx: u64,
        /// Cells along y.
        ny: u64,
        /// The longer side in metres.
        metres: f64,
    },
}

impl AtlasOptions {
    /// The whole map's `[nx, ny]` in cells for tiles of `tile` cells:
    /// `rows·(tile_nx + border) + border` by `cols·(tile_ny + border) + border`,
    /// saturating at `u64::MAX` (options read from a file may ask for
    /// anything: a size that does not fit is too large, never wrapped).
    pub fn map_cells(&self, tile: [u32; 2]) -> [u64; 2] {
        let b = u64::from(self.border);
        let side = |n: u32, t: u32| {
            u64::from(n)
                .saturating_mul(u64::from(t) + b)
                .saturating_add(b)
        };
        [side(self.rows, tile[0]), side(self.cols, tile[1])]
    }

    /// At most how many cells building this atlas of `schemes` visits: the
    /// map once, each tile's generation ([`Scheme::generation_visits`] of
    /// its column's scheme), and per tile its spawn disc (kept to the map)
    /// and flat patches (each candidate cell's disc, then about 32 visits per candidate for
    /// the sampling). Saturates rather than wraps: options read from a file
    /// may ask for anything. What `check` budgets before it rebuilds one.
    pub fn visits(&self, schemes: &[Scheme]) -> u64 {
        let Some(first) = schemes.first() else {
            return 0;
        };
        let grid = first.grid();
        let [nx, ny] = self.map_cells([grid.nx, grid.ny]);
        let tile_cells = grid.cells() as u64;
        let side = |radius: f64| {
            let r = (radius / first.globals().block_size).min(f64::from(u32::MAX));
            (2.0 * r.ceil() + 1.0) as u64
        };
        // The spawn disc is kept to the map, not the tile (a body on a
        // tile's edge stands on its neighbour too): a wide one crosses many
        // tiles. A patch's disc lies inside its tile.
        let spawn = side(self.spawn_radius)
            .min(nx)
            .saturating_mul(side(self.spawn_radius).min(ny));
        let patch = side(self.patches.radius)
            .saturating_mul(side(self.patches.radius))
            .min(tile_cells);
        let per_tile = spawn.saturating_add(if self.patches.count == 0 {
            0
        } else {
            tile_cells.saturating_mul(patch.saturating_add(32))
        });
        // Tiles per scheme: column c uses scheme c mod len.
        let rows = u64::from(self.rows);
        let generation = (0..u64::from(self.cols).min(schemes.len() as u64))
            .map(|c| {
                let columns = (u64::from(self.cols) - c).div_ceil(schemes.len() as u64);
                let tiles = rows.saturating_mul(columns);
                tiles.saturating_mul(
                    schemes[c as usize]
                        .generation_visits()
                        .saturating_add(per_tile),
                )
            })
            .fold(0u64, u64::saturating_add);
        nx.saturating_mul(ny).saturating_add(generation)
    }

    fn validate(&self) -> Result<(), AtlasError> {
        let bad = |field, reason: &str| {
            Err(AtlasError::BadOption {
                field,
                reason: reason.to_owned(),
            })
        };
        if self.rows == 0 {
            return bad("rows", "must be at least 1");
        }
        if self.cols == 0 {
            return bad("cols", "must be at least 1");
        }
        if self.difficulty.0 > self.difficulty.1 {
            return bad(
                "difficulty",
                &format!(
                    "the range {}..{} runs backwards",
                    self.difficulty.0, self.difficulty.1
                ),
            );
        }
        if let Err(why) = check_radius(self.spawn_radius) {
            return bad("spawn_radius", &why);
        }
        if let Err(why) = check_radius(self.patches.radius) {
            return bad("patch_radius", &why);
        }
        Ok(())
    }
}

/// Builds the atlas of `schemes` (the scheme of column `c` is
/// `schemes[c % len]`). Tile `(r, c)` is exactly
/// `generate_by(scheme, seed, r·cols + c, lo + (hi − lo)·r/(rows − 1), rule)`.
/// The same on any number of threads.
pub fn build_atlas(schemes: &[Scheme], options: &AtlasOptions) -> Result<Atlas, AtlasError> {
    options.validate()?;
    let first = schemes.first().ok_or(AtlasError::NoScheme)?;
    let units = first.globals();
    let tile_grid = first.grid();
    for (other, scheme) in schemes.iter().enumerate().skip(1) {
        if let Some(u) = unshared(units, scheme.globals(), Together::Atlas) {
            return Err(AtlasError::Mismatch {
                field: u.key.name(),
                other,
                found: u.found,
                expected: u.expected,
            });
        }
    }
    let [nx, ny] = options.map_cells([tile_grid.nx, tile_grid.ny]);
    let metres = nx.max(ny) as f64 * units.block_size;
    if nx.saturating_mul(ny) > MAX_CELLS || metres > MAX_EXTENT || nx.max(ny) > u64::from(u32::MAX)
    {
        return Err(AtlasError::TooLarge { nx, ny, metres });
    }
    let (nx, ny) = (nx as u32, ny as u32);

    let ((lo, hi), seed) = (options.difficulty, options.seed);
    let tiles: Vec<(Tile, Terrain)> = (0..options.rows * options.cols)
        .into_par_iter()
        .map(|i| {
            let (row, col) = (i / options.cols, i % options.cols);
            let scheme = col as usize % schemes.len();
            let difficulty = Difficulty::lerp(lo, hi, row, options.rows);
            let index = u64::from(i);
            let terrain = generate_by(&schemes[scheme], seed, index, difficulty, options.rule);
            let region = Region {
                x0: options.border + row * (tile_grid.nx + options.border),
                y0: options.border + col * (tile_grid.ny + options.border),
                nx: tile_grid.nx,
                ny: tile_grid.ny,
            };
            let tile = Tile {
                row,
                col,
                scheme,
                seed: options.seed,
                index,
                difficulty,
                region,
                origin: [0.0; 3],
                flat_patches: Vec::new(),
            };
            (tile, terrain)
        })
        .collect();

    let heightmap = map_of(&tiles, nx, ny);

    let grid = Grid {
        nx,
        ny,
        frame_period: None,
    };
    let terrain =
        Terrain::from_heightmap(grid, heightmap, units, options.seed).with_ramps(ramps_of(&tiles));
    let p = options.patches;
    let tiles: Vec<Tile> = tiles
        .into_par_iter()
        .map(|(mut tile, _)| {
            tile.origin = terrain.spawn_origin(tile.region, options.spawn_radius);
            tile.flat_patches = terrain.flat_patches(tile.region, p.count, p.radius, p.max_step);
            tile
        })
        .collect();
    Ok(Atlas {
        terrain,
        tiles,
        options: *options,
    })
}

/// The map of `nx` × `ny` cells holding each tile's heights where it lies.
fn map_of(tiles: &[(Tile, Terrain)], nx: u32, ny: u32) -> Heightmap {
    let mut heightmap = Heightmap::zeros(nx, ny);
    for (tile, terrain) in tiles {
        let r = tile.region;
        for y in 0..r.ny {
            let dest = &mut heightmap.row_mut(r.y0 + y)[r.x0 as usize..(r.x0 + r.nx) as usize];
            dest.copy_from_slice(terrain.heightmap().row(y));
        }
    }
    heightmap
}

/// Each tile's ramps, moved to where the tile lies on the map.
fn ramps_of(tiles: &[(Tile, Terrain)]) -> Vec<crate::Ramp> {
    tiles
        .iter()
        .flat_map(|(tile, terrain)| {
            let r = tile.region;
            terrain.ramps().iter().map(move |ramp| {
                let [x0, y0, x1, y1] = ramp.cells;
                crate::Ramp {
                    cells: [x0 + r.x0, y0 + r.y0, x1 + r.x0, y1 + r.y0],
                    ..*ramp
                }
            })
        })
        .collect()
}

impl Atlas {
    /// The whole map as one terrain (the atlas's grid frame: the outer
    /// corner of cell (0, 0) at the origin).
    pub fn terrain(&self) -> &Terrain {
        &self.terrain
    }

    /// The tiles, row by row: tile `(r, c)` is `tiles()[r·cols + c]`.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// The options it was built with.
    pub fn options(&self) -> &AtlasOptions {
        &self.options
    }
}
