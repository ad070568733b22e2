//! `rse-gen` inside the wheel: the command line's own `main`, run in this
//! process, so `pip install` gives Python users the command without a Rust
//! toolchain (as ruff's and maturin's wheels do).

use pyo3::prelude::*;

/// Runs `rse-gen` with `argv` (the program's name first) and returns its
/// exit status. The GIL is released while it runs.
#[pyfunction]
pub fn _main(py: Python<'_>, argv: Vec<std::ffi::OsString>) -> u8 {
    py.detach(|| rse_cli::main_with(argv))
}
