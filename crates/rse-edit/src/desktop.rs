//! Opening a folder or an address with the desktop's opener (`xdg-open`,
//! `open` on macOS): the editor's `--open` and its Open folder button.

use std::ffi::OsStr;

/// The desktop's opener on this system.
pub const OPENER: &str = if cfg!(target_os = "macos") {
    "open"
} else {
    "xdg-open"
};

/// Opens `target` (a folder, a URL) with [`OPENER`], waiting for it; why
/// not, in words, when there is none or it fails (no display).
///
/// # Errors
/// The reason, naming the opener.
pub fn open(target: &OsStr) -> Result<(), String> {
    let status = std::process::Command::new(OPENER)
        .arg(target)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status();
    match status {
        Ok(s) if s.success() => Ok(()),
        Ok(s) => Err(format!("{OPENER} failed ({s})")),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(format!("no {OPENER} here")),
        Err(e) => Err(format!("{OPENER}: {e}")),
    }
}
