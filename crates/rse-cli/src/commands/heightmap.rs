//! `rse-gen heightmap`: the CSV of one world's heights on stdout.

use std::io::Write as _;

use crate::ExitStatus;
use crate::args::{HeightmapArgs, SchemeOverrides};

pub fn run(args: &HeightmapArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let terrain = super::load_world(&args.scheme, overrides, &args.world)?;
    let mut stdout = std::io::stdout().lock();
    stdout.write_all(terrain.heightmap().to_csv().as_bytes())?;
    stdout.flush()?;
    Ok(ExitStatus::Success)
}
