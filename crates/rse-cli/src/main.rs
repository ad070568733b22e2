//! `rse-gen`: mass generation of Random Step Environment worlds for robot simulators.

fn main() -> std::process::ExitCode {
    std::process::ExitCode::from(rse_cli::main_with(std::env::args_os()))
}
