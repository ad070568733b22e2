//! What `rse.json` keeps of an atlas: its schemes (by name, with their
//! canonical CSV), layout, difficulty range and spawn options, enough to
//! build it again.

use rse_core::{AtlasOptions, Difficulty, DifficultyRule, PatchOptions, Scheme};
use serde::{Deserialize, Serialize};

use crate::files::digest::sha256_hex;

/// A scheme with the file name the atlas records for it (no folder: a
/// world holds no path of the machine that made it).
#[derive(Debug, Clone)]
pub struct NamedScheme {
    /// The file name, e.g. `six_obstacles.csv`.
    pub name: String,
    /// The scheme, overrides applied.
    pub scheme: Scheme,
}

/// What `rse.json` keeps of an atlas: enough to build it again.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtlasRecord {
    /// Tiles along x (difficulty levels).
    pub rows: u32,
    /// Tiles along y.
    pub cols: u32,
    /// Cells of height 0 between and around the tiles.
    pub border: u32,
    /// Difficulty of the first row and of the last.
    pub difficulty: [Difficulty; 2],
    /// How the rows' heights are rounded; absent in atlases written before
    /// it was recorded (read as [`DifficultyRule::Nearest`]) and where every
    /// row is at full difficulty (no rounding happens).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub difficulty_rule: Option<DifficultyRule>,
    /// Spawn disc radius, metres.
    pub spawn_radius: f64,
    /// Flat patches asked for per tile.
    pub flat_patches: PatchRecord,
    /// The schemes, column `c` using `schemes[c mod len]`.
    pub schemes: Vec<SchemeRecord>,
}

/// Flat patch options as recorded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PatchRecord {
    /// At most this many per tile.
    pub count: u32,
    /// Disc radius, metres.
    pub radius: f64,
    /// Largest height difference under a disc, steps.
    pub max_step: u16,
}

/// One scheme of an atlas as recorded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SchemeRecord {
    /// Its file name.
    pub name: String,
    /// SHA-256 of `csv`.
    pub sha256: String,
    /// Its canonical CSV (overrides applied).
    pub csv: String,
}

impl AtlasRecord {
    /// The record of an atlas of `schemes` built with `options`.
    pub fn new(schemes: &[NamedScheme], options: &AtlasOptions) -> Self {
        AtlasRecord {
            rows: options.rows,
            cols: options.cols,
            border: options.border,
            difficulty: [options.difficulty.0, options.difficulty.1],
            difficulty_rule: (!options.difficulty.0.is_full() || !options.difficulty.1.is_full())
                .then_some(options.rule),
            spawn_radius: options.spawn_radius,
            flat_patches: PatchRecord {
                count: options.patches.count,
                radius: options.patches.radius,
                max_step: options.patches.max_step,
            },
            schemes: schemes
                .iter()
                .map(|s| {
                    let csv = s.scheme.to_csv();
                    SchemeRecord {
                        name: s.name.clone(),
                        sha256: sha256_hex(csv.as_bytes()),
                        csv,
                    }
                })
                .collect(),
        }
    }

    /// The options, with `seed`.
    pub fn options(&self, seed: u64) -> AtlasOptions {
        AtlasOptions {
            rows: self.rows,
            cols: self.cols,
            seed,
            border: self.border,
            difficulty: (self.difficulty[0], self.difficulty[1]),
            rule: self.difficulty_rule.unwrap_or(DifficultyRule::Nearest),
            spawn_radius: self.spawn_radius,
            patches: PatchOptions {
                count: self.flat_patches.count,
                radius: self.flat_patches.radius,
                max_step: self.flat_patches.max_step,
            },
        }
    }

    /// The schemes, parsed again from their CSV.
    pub fn schemes(&self) -> Result<Vec<NamedScheme>, rse_core::SchemeError> {
        self.schemes
            .iter()
            .map(|s| {
                Ok(NamedScheme {
                    name: s.name.clone(),
                    scheme: Scheme::from_csv(&s.csv, Some(&s.name))?,
                })
            })
            .collect()
    }
}
