//! `rse-gen preview`: one world seen from above, as a PNG file.

use rse_core::preview;

use crate::ExitStatus;
use crate::args::{PreviewArgs, SchemeOverrides};

pub fn run(args: &PreviewArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let scheme = super::load_scheme(&args.scheme, overrides)?;
    let grid = scheme.grid();
    let cell_pixels = args
        .cell_pixels
        .unwrap_or_else(|| preview::auto_cell_pixels(grid.nx, grid.ny));
    // Refused before the world is generated, let alone drawn.
    preview::validate_size(grid.nx, grid.ny, cell_pixels)?;
    let terrain = super::world_of(&scheme, &args.world);
    let png = preview::png(&terrain, Some(cell_pixels))?;
    rse_world::write_atomically(&args.output, &png)?;
    Ok(ExitStatus::Success)
}
