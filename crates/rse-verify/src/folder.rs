//! A world folder as `check` sees it: opened once, its regular files
//! listed and read through that descriptor without following any link
//! ([`OpenFolder`]), only by their listed names and only up to a cap, so
//! nothing outside the folder is ever read, no special file is waited on,
//! and no file is read whole before its size is known.

use std::collections::BTreeMap;
use std::path::Path;

pub use rse_world::inside;
use rse_world::{Listed, OpenFolder, ReadError};

use crate::fault::{Fault, FaultKind};

/// The regular files of a world folder, by `/`-separated relative path,
/// with their sizes.
#[derive(Debug)]
pub struct Folder {
    open: Option<OpenFolder>,
    sizes: BTreeMap<String, u64>,
}

impl Folder {
    /// Lists `root`. Links and special files are faults and are left out;
    /// so is anything that cannot be read. Never follows a link below
    /// `root`.
    pub fn list(root: &Path) -> (Folder, Vec<Fault>) {
        let mut folder = Folder {
            open: None,
            sizes: BTreeMap::new(),
        };
        let open = match OpenFolder::open(root, true) {
            Ok(open) => open,
            Err(e) => {
                let reason = e.to_string();
                return (
                    folder,
                    vec![Fault::new(None, FaultKind::Unreadable { reason })],
                );
            }
        };
        let listing = open.list();
        if listing.len() > rse_world::MAX_ENTRIES {
            // More than any world holds: one fault, nothing read.
            let cap = rse_world::MAX_ENTRIES;
            return (
                folder,
                vec![Fault::new(None, FaultKind::TooManyFiles { cap })],
            );
        }
        let mut faults = Vec::new();
        for (path, listed) in listing {
            let at = (!path.is_empty()).then_some(path.as_str());
            match listed {
                Listed::File { size, .. } => {
                    folder.sizes.insert(path, size);
                }
                Listed::NotAFile => faults.push(Fault::new(at, FaultKind::NotAFile)),
                // rse writes no empty folder: an extra entry, as a file.
                Listed::EmptyFolder => faults.push(Fault::new(at, FaultKind::Unexpected)),
                Listed::Unreadable(reason) => {
                    faults.push(Fault::new(at, FaultKind::Unreadable { reason }));
                }
            }
        }
        folder.open = Some(open);
        (folder, faults)
    }

    /// The listed files' paths, sorted.
    pub fn paths(&self) -> impl Iterator<Item = &str> {
        self.sizes.keys().map(String::as_str)
    }

    /// The size of the listed regular file `path` when it was listed.
    pub fn size(&self, path: &str) -> Option<u64> {
        self.sizes.get(path).copied()
    }

    /// `true` when `path` is one of the listed regular files.
    pub fn has(&self, path: &str) -> bool {
        self.sizes.contains_key(path)
    }

    /// The bytes of the listed file `path`, if it is at most `cap` bytes
    /// and this folder's alone: a file with another hard link may be
    /// anyone's, and is a fault, not read. Opened without following a
    /// link, checked to be a regular file and read from that descriptor,
    /// never past the cap, should it have changed since it was listed.
    pub fn read(&self, path: &str, cap: u64) -> Result<Vec<u8>, FaultKind> {
        let (Some(open), true) = (&self.open, self.has(path)) else {
            return Err(FaultKind::Missing);
        };
        match open.read(path, cap) {
            Ok(file) if file.links > 1 => Err(FaultKind::HardLinked { links: file.links }),
            Ok(file) => Ok(file.bytes),
            Err(e) => Err(read_fault(e)),
        }
    }

    /// The SHA-256 (lower-case hex) and size of the listed file `path`,
    /// as [`read`](Self::read) would read it, hashed as it streams: memory
    /// that does not grow with the file, however large a manifest says it is.
    pub fn digest(&self, path: &str, cap: u64) -> Result<(String, u64), FaultKind> {
        let (Some(open), true) = (&self.open, self.has(path)) else {
            return Err(FaultKind::Missing);
        };
        match open.digest(path, cap) {
            Ok(file) if file.links > 1 => Err(FaultKind::HardLinked { links: file.links }),
            Ok(file) => Ok((file.sha256, file.size)),
            Err(e) => Err(read_fault(e)),
        }
    }
}

/// The fault of a file that could not be read.
fn read_fault(e: ReadError) -> FaultKind {
    match e {
        ReadError::Missing => FaultKind::Missing,
        ReadError::NotAFile => FaultKind::NotAFile,
        ReadError::TooLarge { bytes, cap } => FaultKind::TooLarge { bytes, cap },
        ReadError::Io(e) => FaultKind::Unreadable {
            reason: e.to_string(),
        },
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
