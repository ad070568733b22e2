//! A world folder as `check` sees it: its regular files, listed without
//! following any link, read only by their listed names and only up to a
//! cap, so nothing outside the folder is ever read and no file is read
//! whole before its size is known.

use std::collections::BTreeMap;
use std::io::Read as _;
use std::path::{Path, PathBuf};

pub use rse_world::inside;

use crate::fault::{Fault, FaultKind};

/// The regular files of a world folder, by `/`-separated relative path,
/// with their sizes.
#[derive(Debug)]
pub struct Folder {
    root: PathBuf,
    sizes: BTreeMap<String, u64>,
}

impl Folder {
    /// Lists `root`. Links and special files are faults and are left out;
    /// so is anything that cannot be read. Never follows a link.
    pub fn list(root: &Path) -> (Folder, Vec<Fault>) {
        let mut folder = Folder {
            root: root.to_path_buf(),
            sizes: BTreeMap::new(),
        };
        let mut faults = Vec::new();
        folder.walk(root, "", &mut faults);
        (folder, faults)
    }

    fn walk(&mut self, dir: &Path, prefix: &str, faults: &mut Vec<Fault>) {
        let entries = match std::fs::read_dir(dir) {
            Ok(entries) => entries,
            Err(e) => {
                let at = prefix.trim_end_matches('/');
                faults.push(Fault::new(
                    (!at.is_empty()).then_some(at),
                    FaultKind::Unreadable {
                        reason: e.to_string(),
                    },
                ));
                return;
            }
        };
        let mut entries: Vec<_> = entries.collect();
        entries.sort_by_key(|e| e.as_ref().ok().map(std::fs::DirEntry::file_name));
        for entry in entries {
            let entry = match entry {
                Ok(entry) => entry,
                Err(e) => {
                    faults.push(Fault::new(
                        None,
                        FaultKind::Unreadable {
                            reason: e.to_string(),
                        },
                    ));
                    continue;
                }
            };
            let name = entry.file_name();
            let Some(name) = name.to_str() else {
                faults.push(Fault::of(
                    &format!("{prefix}{}", name.to_string_lossy()),
                    FaultKind::Unreadable {
                        reason: "the file name is not UTF-8".to_owned(),
                    },
                ));
                continue;
            };
            let relative = format!("{prefix}{name}");
            // `symlink_metadata` describes the link itself, never its target.
            match std::fs::symlink_metadata(entry.path()) {
                Ok(meta) if meta.is_dir() => {
                    self.walk(&entry.path(), &format!("{relative}/"), faults);
                }
                Ok(meta) if meta.is_file() => {
                    self.sizes.insert(relative, meta.len());
                }
                Ok(_) => faults.push(Fault::of(&relative, FaultKind::NotAFile)),
                Err(e) => faults.push(Fault::of(
                    &relative,
                    FaultKind::Unreadable {
                        reason: e.to_string(),
                    },
                )),
            }
        }
    }

    /// The listed files' paths, sorted.
    pub fn paths(&self) -> impl Iterator<Item = &str> {
        self.sizes.keys().map(String::as_str)
    }

    /// `true` when `path` is one of the listed regular files.
    pub fn has(&self, path: &str) -> bool {
        self.sizes.contains_key(path)
    }

    /// The bytes of the listed file `path`, if it is at most `cap` bytes.
    /// The size is checked before reading, and reading stops past the cap
    /// should the file have grown since it was listed.
    pub fn read(&self, path: &str, cap: u64) -> Result<Vec<u8>, FaultKind> {
        let Some(&size) = self.sizes.get(path) else {
            return Err(FaultKind::Missing);
        };
        if size > cap {
            return Err(FaultKind::TooLarge { bytes: size, cap });
        }
        let unreadable = |e: std::io::Error| FaultKind::Unreadable {
            reason: e.to_string(),
        };
        let file = std::fs::File::open(self.root.join(path)).map_err(unreadable)?;
        let mut bytes = Vec::with_capacity(size as usize);
        file.take(cap.saturating_add(1))
            .read_to_end(&mut bytes)
            .map_err(unreadable)?;
        if bytes.len() as u64 > cap {
            return Err(FaultKind::TooLarge {
                bytes: bytes.len() as u64,
                cap,
            });
        }
        Ok(bytes)
    }
}

/// The world-relative path that `reference`, written in a file in
/// `folder` (world-relative, `""` for the top), names; `None` if it climbs
/// out of the world. `.` and `..` are resolved by name, as the simulators
/// do, never through the file system.
pub fn resolve(folder: &str, reference: &str) -> Option<String> {
    let mut parts: Vec<&str> = folder.split('/').filter(|p| !p.is_empty()).collect();
    for part in reference.split('/') {
        match part {
            "" | "." => {}
            ".." => {
                parts.pop()?;
            }
            _ => parts.push(part),
        }
    }
    let path = parts.join("/");
    inside(&path).then_some(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_plain_relative_paths_are_inside() {
        for good in ["rse.json", "gazebo/rse_terrain/model.sdf", "a..b"] {
            assert!(inside(good), "{good}");
        }
        for bad in [
            "",
            "/etc/passwd",
            "../x",
            "a/../../x",
            "a//b",
            "./a",
            "a\\b",
            "C:x",
            "a/",
        ] {
            assert!(!inside(bad), "{bad}");
        }
    }

    #[test]
    fn references_resolve_by_name_and_may_not_climb_out() {
        assert_eq!(
            resolve("webots", "../meshes/terrain.obj").as_deref(),
            Some("meshes/terrain.obj")
        );
        assert_eq!(
            resolve("usd", "./terrain.usda").as_deref(),
            Some("usd/terrain.usda")
        );
        assert_eq!(resolve("webots", "../../etc/passwd"), None);
        assert_eq!(resolve("", "../x"), None);
    }

    #[cfg(unix)]
    #[test]
    fn links_are_faults_and_never_followed() {
        let dir = tempfile::tempdir().unwrap();
        let world = dir.path().join("w");
        std::fs::create_dir(&world).unwrap();
        std::fs::write(dir.path().join("secret"), "outside").unwrap();
        std::fs::write(world.join("a.txt"), "inside").unwrap();
        std::os::unix::fs::symlink(dir.path().join("secret"), world.join("link")).unwrap();
        let (folder, faults) = Folder::list(&world);
        assert_eq!(folder.paths().collect::<Vec<_>>(), ["a.txt"]);
        assert_eq!(faults, [Fault::of("link", FaultKind::NotAFile)]);
        assert_eq!(folder.read("link", 100), Err(FaultKind::Missing));
        assert_eq!(
            folder.read("a.txt", 3),
            Err(FaultKind::TooLarge { bytes: 6, cap: 3 })
        );
        assert_eq!(folder.read("a.txt", 6).unwrap(), b"inside");
    }
}
