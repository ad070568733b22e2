//! `rse-gen mesh`: one world's closed terrain mesh as OBJ, STL or GLB.

use anyhow::{Context as _, anyhow};
use rse_core::export::{self, MeshFormat};

use crate::ExitStatus;
use crate::args::{MeshArgs, SchemeOverrides};
use crate::output;

pub fn run(args: &MeshArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let format = MeshFormat::from_path(&args.output).ok_or_else(|| {
        anyhow!(
            "{}: unknown mesh format; name the file .obj, .stl or .glb",
            args.output.display()
        )
    })?;
    let mesh = super::load_world(&args.scheme, overrides, &args.world)?.mesh();
    match format {
        MeshFormat::Obj => {
            // The material library sits beside the OBJ, named after it.
            let mtl_path = args.output.with_extension("mtl");
            let mtl_name = mtl_path
                .file_name()
                .and_then(|n| n.to_str())
                .context("the output file name is not UTF-8")?;
            output::write_atomically(&mtl_path, export::mtl().as_bytes())?;
            output::write_atomically(&args.output, export::obj(&mesh, Some(mtl_name)).as_bytes())?;
        }
        MeshFormat::Stl => output::write_atomically(&args.output, &export::stl(&mesh))?,
        MeshFormat::Glb => output::write_atomically(&args.output, &export::glb(&mesh))?,
    }
    Ok(ExitStatus::Success)
}
