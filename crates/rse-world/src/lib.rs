//! Simulator worlds from Random Step Environments (docs/worlds.md): the files of a
//! world folder built in memory from templates, the `rse.json` manifest, and
//! batches written in parallel, atomically and resumably.
//!
//! Modules by concern (a test keeps every crate's module graph free of
//! circles): `files` (the folders on disk), `render` (a world's files in
//! memory), `record` (`rse.json`, its options and its rebuild), then
//! `batch` and `atlas`, which write worlds, `config` (what a user gives a
//! batch or a world, resolved once), and `memory` and `error`.
//!
//! ```no_run
//! use rse_world::{BatchConfig, Targets, Templates, WorldConfig, write_batch};
//! let scheme = rse_core::Scheme::load("schemes/wall.csv")?;
//! // What the user gave; the rest is the scheme's (`# amount:`, `# seed:`) or the default.
//! let options = BatchConfig {
//!     amount: Some(10),
//!     world: WorldConfig { targets: Some("gazebo,mujoco".parse::<Targets>()?), ..WorldConfig::default() },
//!     ..BatchConfig::default()
//! }
//! .resolve(&scheme, "out")?;
//! let summary = write_batch(&scheme, &Templates::builtin(), &options, &|_| {})?;
//! println!("{} worlds written", summary.written);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod atlas;
mod batch;
mod config;
mod disk;
mod error;
mod files;
mod memory;
mod record;
mod render;
mod world_option;

pub use atlas::{ATLAS_JSON, atlas_json, atlas_of, build_atlas_world, write_atlas};
pub use batch::{
    BatchOptions, FEWER_JOBS, Shard, Summary, thread_pool, world_index, world_name, write_batch,
    write_batch_until,
};
pub use config::BatchConfig;
pub use disk::{batch_disk_bytes, free_disk_bytes};
pub use error::Error;
pub use files::digest::sha256_hex;
pub use files::folder::{place_folder, write_world_at};
pub use files::names::{MAX_WORLD_NAME, world_name_problem};
pub use files::nofollow::{FileBytes, FileDigest, Listed, MAX_ENTRIES, OpenFolder, ReadError};
pub use files::place::{Leftover, Outcome, place_world};
pub use files::tree::{inside, list_files};
pub use files::write::{mesh_format, write_atomically, write_mesh};
pub use memory::{WORLD_BYTES_PER_CELL, available_bytes};
pub use record::atlas_record::{AtlasRecord, NamedScheme, PatchRecord, SchemeRecord};
pub use record::cost::{ModelCounts, RebuildCost, VISIT_NANOS};
pub use record::manifest::{MANIFEST, MAX_MANIFEST_BYTES, Manifest, TemplateSet, what_differs};
pub use record::options::{
    Collider, MeshFiles, MeshMode, MujocoCollider, Target, Targets, WorldOptions,
};
pub use record::rebuild::{Generated, RebuildError, Rebuilt, Recipe};
pub use render::templates::{
    BYTES_PER_FUEL, FILE_BYTES_PER_CELL, FIXED_FILE_BYTES, FIXED_FUEL, FUEL_PER_BOX,
    MAX_TEMPLATE_BYTES, MAX_TEMPLATE_FILE_BYTES, Templates, VISITS_PER_FUEL, rendered_file_cap,
};
pub use render::world::{HFIELD_FILE, WorldFiles, build_world, build_world_of, mjcf};
pub use world_option::{ColliderName, OptionValue, WORLD_OPTIONS, WorldConfig, WorldOptionInfo};
