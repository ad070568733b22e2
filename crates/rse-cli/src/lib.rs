//! `rse-gen` as a library: the command line (arguments, one module per
//! subcommand), for the binary and for the Python wheel's `rse-gen` command.

use std::ffi::OsString;
use std::io::Write as _;
use std::process::ExitCode;

use clap::Parser as _;

mod args;
mod commands;
mod examples;
mod hints;

pub use args::Cli;
pub use commands::run;

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

impl ExitStatus {
    /// The process exit status.
    pub fn code(self) -> u8 {
        match self {
            ExitStatus::Success => 0,
            ExitStatus::Failure => 1,
            ExitStatus::Error => 2,
            ExitStatus::Interrupted => 130,
        }
    }
}

impl From<ExitStatus> for ExitCode {
    fn from(status: ExitStatus) -> Self {
        ExitCode::from(status.code())
    }
}

/// Over a file size limit (`ulimit -f`) the system kills a writer with
/// SIGXFSZ, without a word. Handled (by a flag nobody reads), the write
/// fails with EFBIG instead, and the batch stops with the path and exit 2,
/// as on a full disk. (Python ignores the signal itself, so the wheel's
/// command gains nothing and loses nothing here.)
fn ignore_file_size_signal() {
    #[cfg(unix)]
    {
        use std::sync::Arc;
        use std::sync::atomic::AtomicBool;
        let _ = signal_hook::flag::register(
            signal_hook::consts::SIGXFSZ,
            Arc::new(AtomicBool::new(false)),
        );
    }
}

/// The whole `rse-gen` program on `args` (the program's name first): parse,
/// run, and print an error as `rse-gen: …` with what to do about it;
/// returns the exit status. The binary and the Python wheel's `rse-gen`
/// command both run this.
pub fn main_with<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    ignore_file_size_signal();
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            // Help and version go to stdout with status 0, usage errors
            // to stderr with status 2, as clap's own `parse` does.
            let _ = e.print();
            return u8::try_from(e.exit_code()).unwrap_or(2);
        }
    };
    match run(cli) {
        Ok(status) => status.code(),
        Err(error) => {
            // A closed pipe (`rse-gen heightmap … | head`) is not a failure.
            if hints::is_broken_pipe(&error) {
                return ExitStatus::Success.code();
            }
            let mut line = format!("rse-gen: {error:#}");
            if let Some(hint) = hints::hint(&error) {
                line.push_str("; ");
                line.push_str(hint);
            }
            let _ = writeln!(std::io::stderr(), "{line}");
            ExitStatus::Error.code()
        }
    }
}
