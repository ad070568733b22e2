//! What [`EnvTerrains`](super::EnvTerrains) is made with, resolved
//! ([`EnvOptions`], its [`EnvLayout`]), and why it may refuse
//! ([`EnvError`]): the leaf of this folder, which `request`, `layout` and
//! the pool itself read.

use crate::difficulty::Difficulty;
use crate::hfield::HFieldError;

/// Where each environment's samples go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EnvLayout {
    /// One height field per environment, all of one shape: the buffer is
    /// `num_envs × nrow × ncol`.
    Slots,
    /// One shared field of tiles, `cols` along x, rows along y as many as
    /// needed, `border` cells of height 0 between tiles and around them;
    /// environment `e`'s tile is row `e / cols`, column `e % cols`.
    Tiles {
        /// Tiles along x.
        cols: u32,
        /// Cells of height 0 between and around the tiles.
        border: u32,
    },
}

/// How the terrains of [`EnvTerrains`](super::EnvTerrains) are made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvOptions {
    /// How many environments: ids `0..num_envs` in this process.
    pub num_envs: usize,
    /// Height-field samples per cell along each axis.
    pub oversample: u32,
    /// Base seed of every terrain.
    pub seed: u64,
    /// The global id of environment 0 (one process per device: each its
    /// own range of ids).
    pub env_offset: u64,
    /// Slots or tiles.
    pub layout: EnvLayout,
    /// The starting difficulty of every environment.
    pub difficulty: Difficulty,
    /// Radius of the disc whose highest top an origin stands on, metres.
    pub spawn_radius: f64,
}

/// Why per-environment terrains cannot be made or reset as asked. Each
/// names the argument at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EnvError {
    /// An argument out of its range.
    #[error("{argument}: {reason}")]
    Bad {
        /// The argument, as the Python API names it.
        argument: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// The height field cannot be made.
    #[error(transparent)]
    HField(#[from] HFieldError),
}

pub(super) fn bad(argument: &'static str, reason: impl Into<String>) -> EnvError {
    EnvError::Bad {
        argument,
        reason: reason.into(),
    }
}
