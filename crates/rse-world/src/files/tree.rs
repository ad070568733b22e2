//! Paths the way worlds name their files: `/`-separated, relative to the
//! world folder; listing a folder's files so, sorted, so that every
//! machine sees one order.

use std::path::Path;

/// Every file under `dir`, as sorted `/`-separated relative paths. A name
/// that is not UTF-8 is an error (`InvalidData`): world and template files
/// are named in UTF-8, and a lossy name could not be opened again.
pub fn list_files(dir: &Path) -> std::io::Result<Vec<String>> {
    fn walk(dir: &Path, prefix: &str, out: &mut Vec<String>) -> std::io::Result<()> {
        for entry in std::fs::read_dir(dir)? {
            let entry = entry?;
            let name = entry.file_name().into_string().map_err(|name| {
                std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    format!("file names must be UTF-8: {}", name.to_string_lossy()),
                )
            })?;
            let relative = format!("{prefix}{name}");
            if entry.file_type()?.is_dir() {
                walk(&entry.path(), &format!("{relative}/"), out)?;
            } else {
                out.push(relative);
            }
        }
        Ok(())
    }
    let mut out = Vec::new();
    walk(dir, "", &mut out)?;
    out.sort();
    Ok(out)
}

/// `path` if it is a plain relative path inside a folder: `/`-separated,
/// no empty, `.` or `..` part, no backslash, no drive or NUL. Such a path
/// names a file under the folder on every system.
pub fn inside(path: &str) -> bool {
    !path.is_empty()
        && !path.contains(['\\', ':', '\0'])
        && path
            .split('/')
            .all(|part| !part.is_empty() && part != "." && part != "..")
}
