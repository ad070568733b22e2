//! `rse-gen` as a library: the command line (arguments, one module per
//! subcommand), for the binary and for the fuzz targets that drive the
//! editor's JSON API without a socket.

use std::process::ExitCode;

mod args;
mod commands;

pub use args::Cli;
pub use commands::run;

/// The editor's pure JSON API handlers (request body in, JSON answer out),
/// for the fuzz targets.
#[doc(hidden)]
pub mod editor_api {
    pub use crate::commands::edit::api::{Answer, parse, preview};
}

/// How a run ended: 0 success, 1 a check or validation failed, 2 usage or I/O error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExitStatus {
    /// Everything asked for was done.
    Success,
    /// The command ran, and what it checked failed.
    Failure,
    /// Bad input, usage or I/O.
    Error,
    /// Stopped by Ctrl-C (exit 130, as a shell reports SIGINT).
    Interrupted,
}

impl From<ExitStatus> for ExitCode {
    fn from(status: ExitStatus) -> Self {
        match status {
            ExitStatus::Success => ExitCode::SUCCESS,
            ExitStatus::Failure => ExitCode::from(1),
            ExitStatus::Error => ExitCode::from(2),
            ExitStatus::Interrupted => ExitCode::from(130),
        }
    }
}
