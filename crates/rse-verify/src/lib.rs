//! Verification of Random Step Environment worlds, the last stage of the
//! pipeline: is a world folder whole, is it the world its `rse.json` says,
//! and is its terrain physically sound? Typed faults for the CLI to print,
//! Python to return and the editor to show.
//!
//! A world is fully determined by its `rse.json`, so `check` rebuilds it
//! in memory and compares every byte; only files rendered from templates
//! it does not have are compared by hash. Every path is checked to stay in
//! the world folder before anything is read, links are never followed, and
//! every file is read up to a cap (`limits`), so a hostile folder can make
//! `check` neither read outside, nor hang, nor panic.
//!
//! ```no_run
//! use rse_verify::{CheckOptions, check_world};
//! let report = check_world("out/world_0000".as_ref(), &CheckOptions::default());
//! for fault in &report.faults {
//!     eprintln!("{}: {fault}", report.world);
//! }
//! ```

mod batch;
mod budget;
mod config;
mod fault;
mod folder;
pub mod limits;
mod physics;
mod references;
mod terrain;
mod world;

pub use batch::{CheckReport, DiscoverError, check_paths, discover};
pub use budget::{Budget, BudgetError};
pub use config::{CheckConfig, CheckConfigError};
pub use fault::{Fault, FaultKind, NotAWorld, printable};
pub use physics::{PHYSICS, physics_unavailable};
pub use terrain::{ObjMesh, mesh_faults_against, read_obj};
pub use world::{CheckOptions, Estimate, WorldReport, check_world};
