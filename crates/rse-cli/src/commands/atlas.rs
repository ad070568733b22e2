//! `rse-gen atlas`: one world folder whose terrain is a grid of tiles, with
//! `atlas.json` listing every tile's world, origin and flat patches.

use anyhow::Context as _;
use rse_core::AtlasConfig;
use rse_world::{NamedScheme, Outcome, thread_pool, write_atlas};

use crate::ExitStatus;
use crate::args::{AtlasArgs, SchemeOverrides};

pub fn run(args: &AtlasArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let mut schemes = Vec::with_capacity(args.schemes.len());
    for path in &args.schemes {
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .with_context(|| format!("{}: the scheme's file name is not UTF-8", path.display()))?;
        schemes.push(NamedScheme {
            name: name.to_owned(),
            scheme: super::load_scheme(path, overrides)?,
        });
    }
    let atlas_options = AtlasConfig {
        rows: args.rows,
        cols: args.cols,
        seed: args.seed,
        border: Some(args.border),
        difficulty: Some(args.difficulty),
        spawn_radius: Some(args.spawn_radius),
        flat_patches: Some(args.flat_patches),
        patch_radius: Some(args.patch_radius),
        max_step: Some(args.max_step),
    }
    .resolve(schemes.iter().map(|s| &s.scheme));
    let templates = args.files.templates()?;
    // An atlas's tiles carry their own difficulties; the map is as drawn.
    let options = args.files.options(rse_core::Difficulty::FULL)?;
    let pool = thread_pool(args.jobs.map(usize::from))?;
    let (outcome, atlas) = pool
        .install(|| {
            write_atlas(
                &schemes,
                &atlas_options,
                &args.output,
                &options,
                &templates,
                args.force,
            )
        })
        .with_context(|| format!("atlas {} not written", args.output.display()))?;
    let grid = atlas.terrain().grid();
    let what = match outcome {
        Outcome::Skipped => "already there, unchanged",
        Outcome::Written(_) => "written",
        Outcome::Replaced(_) => "replaced",
    };
    eprintln!(
        "rse-gen: atlas of {}x{} tiles ({}x{} cells) {what}: {}",
        args.rows,
        args.cols,
        grid.nx,
        grid.ny,
        args.output.display()
    );
    Ok(ExitStatus::Success)
}
