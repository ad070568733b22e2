//! Simulator worlds from Random Step Environments (docs/worlds.md): the files of a
//! world folder built in memory from templates, the `rse.json` manifest, and
//! batches written in parallel, atomically and resumably.
//!
//! ```no_run
//! use rse_world::{BatchOptions, Targets, Templates, write_batch};
//! let scheme = rse_core::Scheme::load("schemes/wall.csv")?;
//! let options = BatchOptions::new("out", 10, 0, Targets::parse("gazebo,mujoco")?);
//! let summary = write_batch(&scheme, &Templates::builtin(), &options, &|_| {})?;
//! println!("{} worlds written", summary.written);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod atlas;
mod batch;
mod context;
mod error;
mod files;
mod manifest;
mod memory;
mod single;
mod target;
mod templates;
mod tree;
mod world;

pub use atlas::{
    ATLAS_JSON, AtlasRecord, NamedScheme, PatchRecord, SchemeRecord, atlas_json, atlas_of,
    build_atlas_world, write_atlas,
};
pub use batch::{
    BatchOptions, Outcome, Shard, Summary, WORLD_BYTES_PER_CELL, leftover_index, place_world,
    thread_pool, world_name, write_batch, write_batch_until,
};
pub use error::Error;
pub use files::{write_atomically, write_mesh};
pub use manifest::{MANIFEST, Manifest, sha256_hex, what_differs};
pub use single::{place_folder, write_world_at};
pub use target::{Collider, MeshMode, MujocoCollider, Target, Targets};
pub use templates::Templates;
pub use tree::list_files;
pub use world::{HFIELD_FILE, WorldFiles, WorldOptions, build_world, mjcf};
