//! `rse-gen mesh`: one world's closed terrain mesh as OBJ, STL or GLB.

use crate::ExitStatus;
use crate::args::{MeshArgs, SchemeOverrides};

pub fn run(args: &MeshArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    // The format is known from the suffix: refuse a bad one before generating.
    if rse_core::export::MeshFormat::from_path(&args.output).is_none() {
        anyhow::bail!(
            "{}: unknown mesh format; name the file .obj, .stl or .glb",
            args.output.display()
        );
    }
    let mesh = super::load_world(&args.scheme, overrides, &args.world)?.mesh();
    rse_world::write_mesh(&mesh, &args.output)?;
    Ok(ExitStatus::Success)
}
