//! Simulator worlds from Random Step Environments (docs/worlds.md): the files of a
//! world folder built in memory from templates, the `rse.json` manifest, and
//! batches written in parallel, atomically and resumably.
//!
//! Modules, each using only those above it (a test keeps it so):
//! `digest`, `error`, `tree`, `nofollow`, `memory`, `options` → `atlas_record` →
//! `manifest`, `box_value` → `context`, `join_filter` → `templates` → `world` → `files`, `place` →
//! `folder`, `batch` → `atlas` → `rebuild`.
//!
//! ```no_run
//! use rse_world::{BatchOptions, Targets, Templates, write_batch};
//! let scheme = rse_core::Scheme::load("schemes/wall.csv")?;
//! let options = BatchOptions::new("out", 10, 0, "gazebo,mujoco".parse::<Targets>()?);
//! let summary = write_batch(&scheme, &Templates::builtin(), &options, &|_| {})?;
//! println!("{} worlds written", summary.written);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod atlas;
mod atlas_record;
mod batch;
mod box_value;
mod context;
mod cost;
mod digest;
mod error;
mod files;
mod folder;
mod join_filter;
mod manifest;
mod memory;
mod names;
mod nofollow;
mod options;
mod place;
mod rebuild;
mod templates;
mod tree;
mod world;

pub use atlas::{ATLAS_JSON, atlas_json, atlas_of, build_atlas_world, write_atlas};
pub use atlas_record::{AtlasRecord, NamedScheme, PatchRecord, SchemeRecord};
pub use batch::{
    BatchOptions, Shard, Summary, thread_pool, world_index, world_name, write_batch,
    write_batch_until,
};
pub use cost::{RebuildCost, VISIT_NANOS};
pub use digest::sha256_hex;
pub use error::Error;
pub use files::{mesh_format, write_atomically, write_mesh};
pub use folder::{place_folder, write_world_at};
pub use manifest::{MANIFEST, MAX_MANIFEST_BYTES, Manifest, TemplateSet, what_differs};
pub use memory::{WORLD_BYTES_PER_CELL, available_bytes};
pub use names::{MAX_WORLD_NAME, world_name_problem};
pub use nofollow::{FileBytes, Listed, OpenFolder, ReadError};
pub use options::{Collider, MeshMode, MujocoCollider, Target, Targets, WorldOptions};
pub use place::{Leftover, Outcome, place_world};
pub use rebuild::{RebuildError, Rebuilt};
pub use templates::{
    FILE_BYTES_PER_CELL, FIXED_FILE_BYTES, FIXED_FUEL, FUEL_PER_BOX, MAX_TEMPLATE_BYTES,
    MAX_TEMPLATE_FILE_BYTES, Templates, rendered_file_cap,
};
pub use tree::{inside, list_files};
pub use world::{HFIELD_FILE, WorldFiles, build_world, build_world_of, mjcf};
