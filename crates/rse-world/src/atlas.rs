//! An atlas as a world folder: the tiled terrain's files as any world's,
//! plus `atlas.json` (one entry per tile, with its origin and flat patches)
//! and, in `rse.json`, everything needed to build it again.

use std::collections::BTreeMap;
use std::path::Path;

use rse_core::{Atlas, AtlasError, AtlasOptions, Difficulty, Scheme, build_atlas};
use serde::Serialize;

use crate::error::Error;
use crate::files::folder::place_folder;
use crate::files::place::Outcome;
use crate::memory::check_memory_for;
use crate::record::atlas_record::{AtlasRecord, NamedScheme, PatchRecord};
use crate::record::options::WorldOptions;
use crate::render::context::tidy;
use crate::render::templates::Templates;
use crate::render::world::{Recorded, WorldFiles, seal, terrain_files};

/// The tile list's file name in an atlas folder.
pub const ATLAS_JSON: &str = "atlas.json";

/// `atlas.json`: the layout and one entry per tile.
#[derive(Debug, Serialize)]
struct AtlasJson<'a> {
    rows: u32,
    cols: u32,
    border: u32,
    seed: u64,
    /// The whole map, `[nx, ny]` cells.
    cells: [u32; 2],
    /// One tile, `[nx, ny]` cells.
    tile_cells: [u32; 2],
    /// One tile, `[x, y]` metres.
    tile_size: [f64; 2],
    block_size: f64,
    step_height: f64,
    base: f64,
    spawn_radius: f64,
    flat_patches: PatchRecord,
    tiles: Vec<TileJson<'a>>,
}

#[derive(Debug, Serialize)]
struct TileJson<'a> {
    row: u32,
    col: u32,
    scheme: &'a str,
    scheme_sha256: &'a str,
    seed: u64,
    index: u64,
    difficulty: Difficulty,
    /// The tile's cells in the map: `[x0, y0, x1, y1]`, ends exclusive.
    cells: [u32; 4],
    origin: [f64; 3],
    flat_patches: Vec<[f64; 3]>,
}

/// The text of `atlas.json` for `atlas` built from `record`.
///
/// # Panics
/// Never: every field serialises.
pub fn atlas_json(atlas: &Atlas, record: &AtlasRecord) -> String {
    let terrain = atlas.terrain();
    let grid = terrain.grid();
    let first = atlas.tiles().first().map(|t| t.region);
    let (tnx, tny) = first.map_or((0, 0), |r| (r.nx, r.ny));
    let s = terrain.block_size();
    let json = AtlasJson {
        rows: record.rows,
        cols: record.cols,
        border: record.border,
        seed: atlas.options().seed,
        cells: [grid.nx, grid.ny],
        tile_cells: [tnx, tny],
        tile_size: [f64::from(tnx) * s, f64::from(tny) * s].map(tidy),
        block_size: s,
        step_height: terrain.step_height(),
        base: terrain.base(),
        spawn_radius: record.spawn_radius,
        flat_patches: record.flat_patches,
        tiles: atlas
            .tiles()
            .iter()
            .map(|t| {
                let scheme = &record.schemes[t.scheme];
                let r = t.region;
                TileJson {
                    row: t.row,
                    col: t.col,
                    scheme: &scheme.name,
                    scheme_sha256: &scheme.sha256,
                    seed: t.seed,
                    index: t.index,
                    difficulty: t.difficulty,
                    cells: [r.x0, r.y0, r.x0 + r.nx, r.y0 + r.ny],
                    origin: t.origin.map(tidy),
                    flat_patches: t.flat_patches.iter().map(|p| p.map(tidy)).collect(),
                }
            })
            .collect(),
    };
    let mut text = serde_json::to_string_pretty(&json).expect("atlas.json serialises");
    text.push('\n');
    text
}

/// [`build_atlas`] of named schemes: a mismatch between two names them.
pub fn atlas_of(schemes: &[NamedScheme], options: &AtlasOptions) -> Result<Atlas, Error> {
    let plain: Vec<Scheme> = schemes.iter().map(|s| s.scheme.clone()).collect();
    build_atlas(&plain, options).map_err(|e| match e {
        AtlasError::Mismatch {
            field,
            other,
            found,
            expected,
        } => Error::AtlasMismatch {
            field,
            scheme: schemes[other].name.clone(),
            found,
            first: schemes[0].name.clone(),
            expected,
        },
        e => Error::Atlas(e),
    })
}

/// The world folder of the atlas of `schemes` with `options`, named
/// `name`, and the atlas itself.
pub fn build_atlas_world(
    schemes: &[NamedScheme],
    atlas_options: &AtlasOptions,
    name: String,
    options: &WorldOptions,
    templates: &Templates,
) -> Result<(WorldFiles, Atlas), Error> {
    let atlas = atlas_of(schemes, atlas_options)?;
    let world = atlas_world(&atlas, schemes, atlas_options, name, options, templates)?;
    Ok((world, atlas))
}

/// The world folder of `atlas`, built already from `schemes` with
/// `atlas_options` (what `check` rebuilds once it has generated it).
pub(crate) fn atlas_world(
    atlas: &Atlas,
    schemes: &[NamedScheme],
    atlas_options: &AtlasOptions,
    name: String,
    options: &WorldOptions,
    templates: &Templates,
) -> Result<WorldFiles, Error> {
    let record = AtlasRecord::new(schemes, atlas_options);
    let extra = BTreeMap::from([(
        ATLAS_JSON.to_owned(),
        atlas_json(atlas, &record).into_bytes(),
    )]);
    let options = WorldOptions {
        difficulty: Difficulty::FULL,
        // The rows' rule is the atlas record's (atlas.json), not the world's.
        difficulty_rule: None,
        ..options.clone()
    };
    let world = terrain_files(atlas.terrain(), name, &options, templates, extra)?;
    let mut globals = *schemes[0].scheme.globals();
    let grid = atlas.terrain().grid();
    globals.size = [grid.nx, grid.ny];
    globals.pallets = None;
    globals.amount = 1;
    globals.seed = atlas_options.seed;
    let recorded = Recorded::Atlas {
        seed: atlas_options.seed,
        record,
        terrain: atlas.terrain(),
    };
    Ok(seal(world, recorded, &globals, &options, templates))
}

/// Builds the atlas and writes its world folder at `out` (a folder whose
/// name is the world's): whole or not at all, left alone when it already
/// holds this atlas, refused when it holds something else unless `force`.
/// Refused before building when the machine's free memory is short.
pub fn write_atlas(
    schemes: &[NamedScheme],
    atlas_options: &AtlasOptions,
    out: &Path,
    options: &WorldOptions,
    templates: &Templates,
    force: bool,
) -> Result<(Outcome, Atlas), Error> {
    if let Some(first) = schemes.first() {
        let grid = first.scheme.grid();
        let [nx, ny] = atlas_options.map_cells([grid.nx, grid.ny]);
        check_memory_for(nx.saturating_mul(ny), options, 1)?;
    }
    place_folder(out, force, |name| {
        build_atlas_world(schemes, atlas_options, name, options, templates)
    })
}
