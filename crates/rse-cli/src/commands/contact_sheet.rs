//! `rse-gen contact-sheet`: the terrains of N parallel envs in one PNG, the
//! picture `rse.EnvTerrains.contact_sheet` draws, for one scheme or a mix.

use anyhow::Context as _;
use rse_core::{Difficulty, SchemeMix, SheetOptions, SheetTile, env_world, generate_at, preview};

use crate::ExitStatus;
use crate::args::{ContactSheetArgs, SchemeOverrides};

pub fn run(args: &ContactSheetArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let schemes = super::load_schemes(&args.schemes, overrides)?;
    let proportions = match &args.proportions {
        Some(p) if p.len() != schemes.len() => anyhow::bail!(
            "--proportions: {} given for {} schemes; give one per scheme, in their order",
            p.len(),
            schemes.len()
        ),
        Some(p) => p.clone(),
        None => vec![1.0; schemes.len()],
    };
    let mix = SchemeMix::new(&proportions).map_err(|e| anyhow::anyhow!("--{e}"))?;
    rse_core::check_mixable(&schemes).map_err(|e| anyhow::anyhow!("SCHEME…: {e}"))?;
    let n = args.envs as usize;
    let mix_seed = schemes[0].seed_or(args.seed);
    let drawn = mix.schemes_of(mix_seed, 0, n);
    let names: Vec<String> = args
        .schemes
        .iter()
        .map(|p| {
            p.file_stem().map_or_else(
                || p.display().to_string(),
                |s| s.to_string_lossy().into_owned(),
            )
        })
        .collect();
    // Env e's terrain is world (episode, e) of its own scheme, as
    // `EnvTerrains` draws it (docs/envs.md).
    let mut terrains = Vec::with_capacity(n);
    let mut labels = Vec::with_capacity(n);
    for (e, &s) in drawn.iter().enumerate() {
        let difficulty = match (args.levels, args.difficulty) {
            (Some(levels), _) => {
                let level = (e as u64 * u64::from(levels) / n as u64) as u32;
                Difficulty::new(f64::from(level) / f64::from(levels - 1))
                    .context("--levels: a level's difficulty")?
            }
            (None, Some(d)) => d,
            (None, None) => Difficulty::FULL,
        };
        let scheme = &schemes[s];
        // One base seed for every scheme, as a pool has: the first's.
        let seed = mix_seed;
        let world =
            env_world(e as u64, u64::from(args.episode)).expect("ids and episodes below 2^32");
        terrains.push(generate_at(scheme, seed, world, difficulty));
        let title = if schemes.len() > 1 {
            format!("env {e} {}", names[s])
        } else {
            format!("env {e}")
        };
        labels.push((
            title,
            format!("ep {} D {:.3}", args.episode, difficulty.get()),
        ));
    }
    let tiles: Vec<SheetTile<'_>> = terrains
        .iter()
        .zip(&labels)
        .zip(&drawn)
        .map(|((terrain, (title, caption)), &s)| SheetTile {
            terrain,
            title,
            caption,
            // A mix: each scheme on its own colour scale.
            scale: (schemes.len() > 1).then(|| names[s].as_str()),
        })
        .collect();
    let options = SheetOptions {
        cols: args.cols,
        cell_pixels: args.cell_pixels,
        one_scale: args.one_scale,
    };
    let sheet = rse_core::tiles_sheet(&tiles, options)?;
    let png = preview::encode_png(&sheet)?;
    rse_world::write_atomically(&args.output, &png)
        .with_context(|| format!("writing {}", args.output.display()))?;
    Ok(ExitStatus::Success)
}
