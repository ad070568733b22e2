//! `rse-gen templates export DIR`: our world templates written out, for a
//! user to copy and edit (a `--template DIR` overlays ours file by file).

use crate::ExitStatus;
use crate::args::{TemplatesAction, TemplatesArgs};

pub fn run(args: &TemplatesArgs) -> anyhow::Result<ExitStatus> {
    match &args.action {
        TemplatesAction::Export { dir } => {
            let written = rse_world::Templates::export_builtin(dir)?;
            for path in &written {
                println!("{}", path.display());
            }
            eprintln!(
                "rse-gen: {} templates in {}; edit any, delete the rest, and pass --template {}",
                written.len(),
                dir.display(),
                dir.display()
            );
            Ok(ExitStatus::Success)
        }
    }
}
