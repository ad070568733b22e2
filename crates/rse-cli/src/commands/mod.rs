//! One module per subcommand, and what they share: loading a scheme with overrides.

use std::io::Write as _;
use std::path::Path;

use anyhow::Context as _;
use rse_core::{Scheme, SchemeErrorKind, Terrain};

use crate::ExitStatus;
use crate::args::{Cli, Command, SchemeOverrides, WorldArgs};

mod atlas;
mod batch;
pub mod check;
mod check_curriculum;
mod contact_sheet;
pub mod edit;
mod heightmap;
mod hfield;
mod mesh;
mod preview;
mod templates;

/// Runs the parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<ExitStatus> {
    let outer = cli.overrides;
    match cli.command {
        Command::Heightmap(args) => heightmap::run(&args, &args.overrides.or(outer)),
        Command::Preview(args) => preview::run(&args, &args.overrides.or(outer)),
        Command::Mesh(args) => mesh::run(&args, &args.overrides.or(outer)),
        Command::Hfield(args) => hfield::run(&args, &args.overrides.or(outer)),
        Command::Batch(args) => batch::run(&args, &args.overrides.or(outer)),
        Command::Atlas(args) => atlas::run(&args, &args.overrides.or(outer)),
        Command::Check(args) => {
            // A world's parameters are in its rse.json: a flag would be
            // silently ignored, so it is refused.
            if let Some(flag) = cli.overrides.first_set() {
                anyhow::bail!(
                    "{flag} does not apply to check: a world is checked against the parameters in its rse.json"
                );
            }
            check::run(&args)
        }
        Command::CheckCurriculum(args) => check_curriculum::run(&args, &args.overrides.or(outer)),
        Command::ContactSheet(args) => contact_sheet::run(&args, &args.overrides.or(outer)),
        Command::Edit(args) => edit::run(&args, &args.overrides.or(outer)),
        Command::Templates(args) => {
            if let Some(flag) = cli.overrides.first_set() {
                anyhow::bail!("{flag} does not apply to templates");
            }
            templates::run(&args)
        }
    }
}

/// Reads the scheme at `path` with the overrides and generates the world the
/// flags name: index `--index` of seed `--seed`, else of the scheme's seed.
pub fn load_world(
    path: &Path,
    overrides: &SchemeOverrides,
    world: &WorldArgs,
) -> anyhow::Result<Terrain> {
    Ok(world_of(&load_scheme(path, overrides)?, world))
}

/// The world of `scheme` the flags name.
pub fn world_of(scheme: &Scheme, world: &WorldArgs) -> Terrain {
    rse_core::WorldRequest {
        seed: world.seed,
        index: Some(world.index),
        difficulty: Some(world.difficulty.value),
    }
    .generate(scheme)
}

/// Reads every scheme of `paths` with the overrides, in order: a bad one
/// fails before any is used.
pub fn load_schemes(
    paths: &[std::path::PathBuf],
    overrides: &SchemeOverrides,
) -> anyhow::Result<Vec<Scheme>> {
    paths
        .iter()
        .map(|path| load_scheme(path, overrides))
        .collect()
}

/// Reads the scheme at `path` and applies the command-line overrides.
pub fn load_scheme(path: &Path, overrides: &SchemeOverrides) -> anyhow::Result<Scheme> {
    let scheme = Scheme::load(path)?;
    if scheme.obstacles().is_empty() {
        // Allowed (a flat field is a fair baseline), but an empty file or a
        // table lost to a bad paste deserves a word.
        let _ = writeln!(
            std::io::stderr(),
            "rse-gen: note: {} has no obstacles: every world is flat (pallet frames aside)",
            path.display()
        );
    }
    with_overrides(scheme, overrides)
}

/// `scheme` with the command-line overrides applied.
pub fn with_overrides(scheme: Scheme, overrides: &SchemeOverrides) -> anyhow::Result<Scheme> {
    let patch = overrides.patch();
    if patch.is_empty() {
        return Ok(scheme);
    }
    let globals = patch.apply(scheme.globals()).map_err(|e| {
        // The rule is core's; the words are the command line's.
        match e.kind {
            SchemeErrorKind::PalletsOff => anyhow::anyhow!(
                "--{} needs pallets: add --pallets PXxPY",
                e.field
                    .as_deref()
                    .unwrap_or("pallet-size")
                    .replace('_', "-")
            ),
            _ => e.into(),
        }
    })?;
    if globals == *scheme.globals() {
        return Ok(scheme);
    }
    scheme
        .with_globals(globals)
        .context("the scheme does not fit the parameters given on the command line")
}
