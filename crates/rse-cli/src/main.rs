//! `rse-gen`: mass generation of Random Step Environment worlds for robot simulators.

use std::io::Write as _;
use std::process::ExitCode;

use clap::Parser as _;
use rse_cli::{Cli, ExitStatus};

fn main() -> ExitCode {
    let cli = Cli::parse();
    match rse_cli::run(cli) {
        Ok(status) => status.into(),
        Err(error) => {
            // A closed pipe (`rse-gen heightmap … | head`) is not a failure.
            if is_broken_pipe(&error) {
                return ExitCode::SUCCESS;
            }
            let _ = writeln!(std::io::stderr(), "rse-gen: {error:#}");
            ExitStatus::Error.into()
        }
    }
}

fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}
