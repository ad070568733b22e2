//! Deterministic generator of Random Step Environments (RSE): the NIST
//! "stepfield" pallets of wooden blocks used to test rescue robots.
//!
//! A [`Scheme`] holds the global parameters (grid, block size, step height,
//! pallets) and an ordered table of obstacles (random, gaussian, peak, pit,
//! wall, long pit). [`generate`] turns a scheme and a seed pair `(seed, index)`
//! into a [`Terrain`]: a [`Heightmap`] of whole steps plus what was drawn.
//! The same inputs give the same heights on every machine.
//!
//! ```
//! use rse_core::{generate, Scheme};
//!
//! let scheme = Scheme::from_csv(
//!     "# size: 20x10\n\
//!      type,height,angle,x1,y1,x2,y2\n\
//!      random,1,,,,,\n\
//!      wall,4,45,2,5,17,5\n",
//!     None,
//! )?;
//! let terrain = generate(&scheme, 42, 7);
//! assert_eq!(terrain.heightmap().get(10, 5), 4); // on the wall
//! assert_eq!(generate(&scheme, 42, 7), terrain); // reproducible
//! let png = rse_core::preview::encode_png(&rse_core::preview::render(&terrain, 8))?;
//! assert!(png.starts_with(b"\x89PNG"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The grid, units, obstacle math, seeding and scheme files are documented
//! in the repository's `docs/schemes.md`, the mesh guarantees in
//! `docs/meshes.md`.

mod atlas;
mod canvas;
mod color;
mod curriculum;
mod difficulty;
mod env_terrains;
mod error;
pub mod export;
mod generate;
mod global_key;
pub mod global_range;
mod global_value;
mod globals;
mod globals_patch;
mod heightmap;
pub mod hfield;
mod limits;
pub mod mesh;
mod obstacle;
mod param;
mod png_rows;
pub mod preview;
mod probe;
mod ramp;
mod request;
mod rng;
mod scheme;
mod scheme_csv;
mod scheme_file;
mod shared_globals;
pub mod spawn;
mod stamp;
mod terrain;

pub use atlas::{Atlas, AtlasConfig, AtlasError, AtlasOptions, PatchOptions, Tile, build_atlas};
pub use color::Color;
pub use curriculum::{
    CURRICULUM_VISITS, CurriculumOptions, CurriculumOptionsError, CurriculumProblem,
    CurriculumReport, DEFAULT_DRAWS, DEFAULT_LEVELS, LevelStats, MAX_DRAWS, MAX_LEVELS,
    check_curriculum, check_curriculum_within, within_curriculum_budget,
};
pub use difficulty::{Difficulty, DifficultyError, DifficultyRule};
pub use env_terrains::{
    DEFAULT_ENV_OVERSAMPLE, ENV_BITS, ENV_OPTIONS, EnvError, EnvLayout, EnvOptionInfo, EnvOptions,
    EnvRequest, EnvTerrains, FieldSamples, LayoutKind, SchemeMix, SheetOptions, SheetTile,
    check_mixable, contact_sheet, contact_sheet_named, env_pool_bytes, env_world, mix_pool_bytes,
    tiles_sheet,
};
pub use error::{Error, SchemeError, SchemeErrorKind, excerpt};
pub use generate::{generate, generate_at, generate_by};
pub use global_key::{GLOBAL_KEYS, GlobalKey};
pub use global_value::{format_dims, parse_dims, parse_pallets};
pub use globals::{Globals, Grid, Pallets};
pub use globals_patch::GlobalsPatch;
pub use heightmap::{Heightmap, HeightmapCsvError, Walls};
pub use hfield::{DEFAULT_OVERSAMPLE, HField, HFieldError, MAX_HFIELD_SAMPLES};
pub use limits::{
    DEFAULT_PALLET_SIZE, DEFAULT_SIGMA, MAX_CELLS, MAX_EXTENT, MAX_HEIGHT, MAX_LATTICE_UNITS,
    MAX_TOP_IN_BLOCKS, MIN_LENGTH, QUOTE_CHARS,
};
pub use obstacle::{DrawnObstacle, Field, Obstacle, ObstacleFields, ObstacleKind, Usage};
pub use param::{Param, range_parts, range_text};
pub use ramp::Ramp;
pub use request::{WorldAt, WorldRequest};
pub use scheme::{BUDGET_VISITS, Scheme, VISIT_NANOS};
pub use scheme_file::{MAX_SCHEME_BYTES, read_scheme_file};
pub use terrain::Terrain;

/// The generator's version, written into every world's manifest.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
