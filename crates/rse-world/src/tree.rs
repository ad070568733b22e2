//! Listing a folder's files the way worlds name them: `/`-separated paths
//! relative to the folder, sorted, so that every machine sees one order.

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
