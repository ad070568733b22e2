//! `rse-gen mesh`: one world's closed terrain mesh as OBJ, STL or GLB.

use crate::ExitStatus;
use crate::args::{MeshArgs, SchemeOverrides};

pub fn run(args: &MeshArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    // The format is known from the suffix: refuse a bad one before generating.
    rse_world::mesh_format(&args.output)?;
    let terrain = super::load_world(&args.scheme, overrides, &args.world)?;
    rse_world::write_mesh(&terrain.mesh(), terrain.globals(), &args.output)?;
    Ok(ExitStatus::Success)
}
