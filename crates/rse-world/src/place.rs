//! Placing a world folder: written whole into a hidden temporary folder
//! beside its place, renamed into place, compared byte for byte when one is
//! there already, under a lock per folder. The temporary folders' names are
//! written and parsed here only.

use std::collections::BTreeSet;
use std::io::ErrorKind;
use std::path::Path;

use crate::digest::sha256_hex;
use crate::error::Error;
use crate::manifest::{MANIFEST, Manifest, what_differs};
use crate::tree::list_files;
use crate::world::WorldFiles;

/// What happened to one world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Written anew; with its size in bytes.
    Written(u64),
    /// Already there, identical: left alone.
    Skipped,
    /// Held something else and `force` was set; with the new size in bytes.
    Replaced(u64),
}

/// The two hidden folders a run makes beside a world folder `NAME`:
/// `.NAME.tmp-PID` (the world being written) and `.NAME.old-PID` (the
/// world being replaced, under `force`). One left behind is what a run cut
/// short leaves; the next run on that world removes it, `check` reports it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Leftover {
    /// `.NAME.tmp-PID`.
    Temp,
    /// `.NAME.old-PID`.
    Old,
}

impl Leftover {
    /// This process's folder of this kind for the world `name`.
    pub fn name_for(self, name: &str) -> String {
        let kind = match self {
            Leftover::Temp => "tmp",
            Leftover::Old => "old",
        };
        format!(".{name}.{kind}-{}", std::process::id())
    }

    /// The world whose temporary folder `folder` is (`.atlas.tmp-12` →
    /// `atlas`), whichever process made it; `None` for any other name.
    pub fn world_of(folder: &str) -> Option<&str> {
        let rest = folder.strip_prefix('.')?;
        let (name, pid) = rest
            .rsplit_once(".tmp-")
            .or_else(|| rest.rsplit_once(".old-"))?;
        let is_pid = !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit());
        (is_pid && !name.is_empty() && !name.starts_with('.')).then_some(name)
    }
}

/// Removes the leftovers in `parent` of the worlds `mine` accepts (by
/// name): those of this run's worlds, never another's, which may be
/// running right now into the same folder.
pub(crate) fn remove_leftovers(parent: &Path, mine: impl Fn(&str) -> bool) -> Result<(), Error> {
    for entry in std::fs::read_dir(parent).map_err(Error::io("read", parent))? {
        let entry = entry.map_err(Error::io("read", parent))?;
        let file_name = entry.file_name();
        let Some(world) = file_name.to_str().and_then(Leftover::world_of) else {
            continue;
        };
        if mine(world) {
            let path = entry.path();
            std::fs::remove_dir_all(&path).map_err(Error::io("remove", &path))?;
        }
    }
    Ok(())
}

/// An exclusive lock on `what` in the folder `out` (a lock file in the
/// system's temp folder, named after both), or `busy()` when another run
/// holds it. Dropping the file releases it; so does the process dying.
pub(crate) fn lock_in(
    out: &Path,
    what: &str,
    busy: impl FnOnce() -> Error,
) -> Result<std::fs::File, Error> {
    let canonical = out.canonicalize().map_err(Error::io("read", out))?;
    let key = sha256_hex(canonical.as_os_str().as_encoded_bytes());
    let what = sha256_hex(what.as_bytes());
    let path = std::env::temp_dir().join(format!("rse-batch-{}-{}.lock", &key[..16], &what[..16]));
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(Error::io("create", &path))?;
    match file.try_lock() {
        Ok(()) => Ok(file),
        Err(std::fs::TryLockError::WouldBlock) => Err(busy()),
        Err(std::fs::TryLockError::Error(e)) => Err(Error::io("lock", &path)(e)),
    }
}

/// Puts `world` at `out/<name>`: written into a temporary folder, then
/// renamed into place, so that the folder appears whole or not at all. A
/// folder already holding exactly `world` is left alone; one holding
/// anything else is an error unless `force`.
pub fn place_world(out: &Path, world: &WorldFiles, force: bool) -> Result<Outcome, Error> {
    let dest = out.join(&world.name);
    let existing = match std::fs::symlink_metadata(&dest) {
        Ok(_) => true,
        Err(e) if e.kind() == ErrorKind::NotFound => false,
        Err(e) => return Err(Error::io("read", &dest)(e)),
    };
    if existing {
        match difference(&dest, world)? {
            None => return Ok(Outcome::Skipped),
            Some(reason) if !force => return Err(Error::Conflict { path: dest, reason }),
            Some(_) => {}
        }
    }
    let temp = out.join(Leftover::Temp.name_for(&world.name));
    if let Err(e) = write_tree(&temp, world) {
        // Best effort: the error being reported matters more.
        let _ = std::fs::remove_dir_all(&temp);
        return Err(e);
    }
    let size = world.bytes();
    if !existing {
        std::fs::rename(&temp, &dest).map_err(Error::io("rename into place", &dest))?;
        return Ok(Outcome::Written(size));
    }
    // Replace: move the old folder aside first, since a folder cannot be
    // renamed over a non-empty one. A crash in between leaves the world
    // absent (and the leftovers are removed by the next run), never mixed.
    let old = out.join(Leftover::Old.name_for(&world.name));
    std::fs::rename(&dest, &old).map_err(Error::io("move aside", &dest))?;
    std::fs::rename(&temp, &dest).map_err(Error::io("rename into place", &dest))?;
    std::fs::remove_dir_all(&old).map_err(Error::io("remove", &old))?;
    Ok(Outcome::Replaced(size))
}

/// Writes every file of `world` under `root`.
fn write_tree(root: &Path, world: &WorldFiles) -> Result<(), Error> {
    std::fs::create_dir(root).map_err(Error::io("create", root))?;
    let mut made = BTreeSet::new();
    for (relative, bytes) in &world.files {
        let path = root.join(relative);
        if let Some(parent) = Path::new(relative).parent()
            && !parent.as_os_str().is_empty()
            && made.insert(parent.to_owned())
        {
            let dir = root.join(parent);
            std::fs::create_dir_all(&dir).map_err(Error::io("create", &dir))?;
        }
        std::fs::write(&path, bytes).map_err(Error::io("write", &path))?;
    }
    Ok(())
}

/// How the folder `dest` differs from `world`, or `None` if it holds
/// exactly its files with exactly their bytes: the setting its `rse.json`
/// records differently when there is one (`targets gazebo there,
/// gazebo,mujoco now`), else the first file that differs.
fn difference(dest: &Path, world: &WorldFiles) -> Result<Option<String>, Error> {
    let Some(file) = file_difference(dest, world)? else {
        return Ok(None);
    };
    let manifest = |bytes: &[u8]| serde_json::from_slice::<Manifest>(bytes).ok();
    let there = std::fs::read(dest.join(MANIFEST))
        .ok()
        .and_then(|b| manifest(&b));
    let now = world.files.get(MANIFEST).and_then(|b| manifest(b));
    Ok(Some(match (there, now) {
        (Some(there), Some(now)) => what_differs(&there, &now).unwrap_or_else(|| {
            format!("{file}, though it was made with the same settings (changed since?)")
        }),
        _ => file,
    }))
}

/// The first file of the folder `dest` that is not `world`'s, or `None`.
fn file_difference(dest: &Path, world: &WorldFiles) -> Result<Option<String>, Error> {
    if !dest.is_dir() {
        return Ok(Some("not a folder".to_owned()));
    }
    for path in &list_files(dest).map_err(Error::io("read", dest))? {
        if !world.files.contains_key(path) {
            return Ok(Some(format!("unexpected file {path}")));
        }
    }
    for (path, bytes) in &world.files {
        let file = dest.join(path);
        match std::fs::read(&file) {
            Ok(on_disk) if on_disk == *bytes => {}
            Ok(_) => return Ok(Some(format!("{path} differs"))),
            Err(e) if e.kind() == ErrorKind::NotFound => {
                return Ok(Some(format!("{path} is missing")));
            }
            Err(e) => return Err(Error::io("read", file)(e)),
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leftover_names_are_written_and_parsed_here() {
        for kind in [Leftover::Temp, Leftover::Old] {
            let name = kind.name_for("world_0007");
            assert_eq!(Leftover::world_of(&name), Some("world_0007"), "{name}");
            assert_eq!(Leftover::world_of(&kind.name_for("atlas")), Some("atlas"));
        }
        assert_eq!(Leftover::world_of(".my.world.tmp-12"), Some("my.world"));
        for other in [
            "world_0007",
            ".world_0007",
            ".x.tmp-",
            ".x.tmp-1a",
            "..tmp-1",
            "x.tmp-1",
        ] {
            assert_eq!(Leftover::world_of(other), None, "{other}");
        }
    }
}
