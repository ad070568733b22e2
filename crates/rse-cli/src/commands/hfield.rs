//! `rse-gen hfield`: one world as MuJoCo's binary height field file, with
//! what the MJCF needs to place it (size, geom pos) as JSON on stdout.

use std::io::Write as _;

use crate::ExitStatus;
use crate::args::{HfieldArgs, SchemeOverrides};

pub fn run(args: &HfieldArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let terrain = super::load_world(&args.scheme, overrides, &args.world)?;
    let hfield = terrain.hfield(args.oversample)?;
    rse_world::write_atomically(&args.output, &hfield.to_mujoco_bin())?;
    let summary = serde_json::json!({
        "file": args.output.file_name().map(|n| n.to_string_lossy()),
        "nrow": hfield.nrow,
        "ncol": hfield.ncol,
        "size": hfield.size,
        "pos": hfield.pos,
    });
    let mut stdout = std::io::stdout().lock();
    writeln!(stdout, "{summary}")?;
    stdout.flush()?;
    Ok(ExitStatus::Success)
}
