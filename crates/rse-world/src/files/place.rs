//! Placing a world folder: written whole into a hidden temporary folder
//! beside its place, renamed into place, compared byte for byte when one is
//! there already, under a lock per folder. The temporary folders' names are
//! written and parsed here only.

use std::collections::BTreeSet;
use std::io::ErrorKind;
use std::path::Path;

use crate::error::Error;
use crate::files::digest::sha256_hex;
use crate::files::nofollow::{Listed, OpenFolder, ReadError, refused};
use crate::record::manifest::{MANIFEST, MAX_MANIFEST_BYTES, Manifest, what_differs};
use crate::render::world::WorldFiles;

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
            remove_entry(&entry.path())?;
        }
    }
    Ok(())
}

/// An exclusive lock on `what` in the folder `out`, or `busy()` when
/// another run holds it. The lock file lives in `out` itself
/// (`.rse-<hash of what>.lock`, hidden, never a world): anyone who can
/// write the worlds can take it, no one else can, and nothing is made in
/// the shared temporary folder. It is created without following a link (a
/// link planted there is an error, never written through), and removed
/// when the lock is dropped, so a finished run leaves the folder as it
/// found it but for the worlds; the process dying releases it too (the
/// file then stays, and the next run takes it over).
pub(crate) fn lock_in(out: &Path, what: &str, busy: impl FnOnce() -> Error) -> Result<Lock, Error> {
    take_lock(out, what, false)?.ok_or_else(busy)
}

/// [`lock_in`], waiting for the holder instead of failing: for a lock
/// held only for a moment (the shard registry of an output folder).
pub(crate) fn lock_in_waiting(out: &Path, what: &str) -> Result<Lock, Error> {
    Ok(take_lock(out, what, true)?.expect("a lock waited for is never busy"))
}

/// The lock on `what` in `out`: waited for (`wait`), or `None` when
/// another run holds it.
fn take_lock(out: &Path, what: &str, wait: bool) -> Result<Option<Lock>, Error> {
    let path = out.join(format!(".rse-{}.lock", &sha256_hex(what.as_bytes())[..16]));
    loop {
        let file = create_no_follow(&path).map_err(|e| match e.raw_os_error() {
            // ELOOP: the name is a link.
            #[cfg(unix)]
            Some(code) if code == rustix::io::Errno::LOOP.raw_os_error() => {
                Error::NotAFile { path: path.clone() }
            }
            _ => Error::io("create", &path)(e),
        })?;
        if wait {
            file.lock().map_err(Error::io("lock", &path))?;
        } else {
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => return Ok(None),
                Err(std::fs::TryLockError::Error(e)) => return Err(Error::io("lock", &path)(e)),
            }
        }
        // The holder before us may have removed the file between our open
        // and our lock: then we hold a lock on a name no one else sees,
        // and must take the file that is there now.
        if still_named(&file, &path) {
            return Ok(Some(Lock { file, path }));
        }
    }
}

/// A lock taken by [`lock_in`]: its file is removed, then released, when
/// dropped.
#[derive(Debug)]
pub(crate) struct Lock {
    file: std::fs::File,
    path: std::path::PathBuf,
}

impl Lock {
    /// Writes `text` into the lock file, for [`held_locks`] to read.
    pub(crate) fn record(&self, text: &str) -> Result<(), Error> {
        use std::io::Write as _;
        self.file
            .set_len(0)
            .map_err(Error::io("write", &self.path))?;
        (&self.file)
            .write_all(text.as_bytes())
            .map_err(Error::io("write", &self.path))
    }
}

/// What the lock files in `out` other than `mine` record ([`Lock::record`])
/// whose lock a live process holds right now. A file it cannot read, a
/// link, or one no one holds (its run died) is passed over.
pub(crate) fn held_locks(out: &Path, mine: &Lock) -> Result<Vec<String>, Error> {
    use std::io::Read as _;
    let mut held = Vec::new();
    for entry in std::fs::read_dir(out).map_err(Error::io("read", out))? {
        let entry = entry.map_err(Error::io("read", out))?;
        let path = entry.path();
        let is_lock = entry.file_name().to_str().is_some_and(|n| {
            n.starts_with(".rse-") && Path::new(n).extension().is_some_and(|e| e == "lock")
        });
        if !is_lock || path == mine.path {
            continue;
        }
        let Ok(file) = open_lock_to_read(&path) else {
            continue;
        };
        let mut text = String::new();
        if (&file).take(256).read_to_string(&mut text).is_err() || text.is_empty() {
            continue;
        }
        match file.try_lock_shared() {
            Err(std::fs::TryLockError::WouldBlock) => held.push(text),
            // Free: the run that wrote it is gone (our descriptor's lock
            // ends when it is closed, here).
            Ok(()) | Err(std::fs::TryLockError::Error(_)) => {}
        }
    }
    Ok(held)
}

/// Opens a lock file to read, refusing a link or a special file.
fn open_lock_to_read(path: &Path) -> std::io::Result<std::fs::File> {
    #[cfg(unix)]
    {
        use rustix::fs::{Mode, OFlags};
        let flags = OFlags::RDONLY | OFlags::NOFOLLOW | OFlags::NONBLOCK | OFlags::CLOEXEC;
        let file = std::fs::File::from(rustix::fs::open(path, flags, Mode::empty())?);
        if !file.metadata()?.is_file() {
            return Err(std::io::Error::other("not a regular file"));
        }
        Ok(file)
    }
    #[cfg(not(unix))]
    {
        std::fs::File::open(path)
    }
}

impl Drop for Lock {
    fn drop(&mut self) {
        // Removed while still held: a run that opens the name after this
        // makes a new file, one that opened it before finds it unnamed.
        let _ = std::fs::remove_file(&self.path);
        let _ = self.file.unlock();
    }
}

/// `true` when `path` still names the open `file` (same device and inode).
fn still_named(file: &std::fs::File, path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt as _;
        match (file.metadata(), std::fs::symlink_metadata(path)) {
            (Ok(open), Ok(named)) => open.dev() == named.dev() && open.ino() == named.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        let _ = (file, path);
        true
    }
}

/// Opens `path` for writing, creating it if needed, refusing a link.
fn create_no_follow(path: &Path) -> std::io::Result<std::fs::File> {
    #[cfg(unix)]
    {
        use rustix::fs::{Mode, OFlags};
        let flags =
            OFlags::WRONLY | OFlags::CREATE | OFlags::NOFOLLOW | OFlags::NONBLOCK | OFlags::CLOEXEC;
        let fd = rustix::fs::open(path, flags, Mode::from_raw_mode(0o644))?;
        let file = std::fs::File::from(fd);
        // Not a FIFO or device planted under the name: those would be
        // "locked" without being ours.
        if !file.metadata()?.is_file() {
            return Err(std::io::Error::other("not a regular file"));
        }
        Ok(file)
    }
    #[cfg(not(unix))]
    {
        std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(path)
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
    remove_entry(&old)?;
    Ok(Outcome::Replaced(size))
}

/// Removes `path` whatever it is: a folder with everything in it, or a
/// plain file or a link (never followed). What `force` replaces, and so
/// what a leftover `.NAME.old-PID` holds, need not be a folder: a plain
/// file named like a world once stayed behind as one, and every later run
/// failed removing it as a folder.
fn remove_entry(path: &Path) -> Result<(), Error> {
    let is_folder = std::fs::symlink_metadata(path)
        .map_err(Error::io("remove", path))?
        .is_dir();
    if is_folder {
        std::fs::remove_dir_all(path)
    } else {
        std::fs::remove_file(path)
    }
    .map_err(Error::io("remove", path))
}

/// Writes every file of `world` under `root`, making each folder once,
/// parents first (`create_dir_all` would try a nested folder before its
/// parents, and look again at folders it has made).
fn write_tree(root: &Path, world: &WorldFiles) -> Result<(), Error> {
    std::fs::create_dir(root).map_err(Error::io("create", root))?;
    let mut made = BTreeSet::new();
    for (relative, bytes) in &world.files {
        let mut folders: Vec<&Path> = Path::new(relative)
            .ancestors()
            .skip(1)
            .take_while(|folder| !folder.as_os_str().is_empty() && !made.contains(*folder))
            .collect();
        while let Some(folder) = folders.pop() {
            let dir = root.join(folder);
            std::fs::create_dir(&dir).map_err(Error::io("create", &dir))?;
            made.insert(folder);
        }
        let path = root.join(relative);
        std::fs::write(&path, bytes).map_err(Error::io("write", &path))?;
    }
    Ok(())
}

/// How the folder `dest` differs from `world`, or `None` if it holds
/// exactly its files with exactly their bytes: the setting its `rse.json`
/// records differently when there is one (`targets gazebo there,
/// gazebo,mujoco now`), else the first file that differs. Read by
/// descriptor ([`OpenFolder`]), no file past the size of ours: a link or
/// special file anywhere in it stops the run with its path.
fn difference(dest: &Path, world: &WorldFiles) -> Result<Option<String>, Error> {
    let meta = std::fs::symlink_metadata(dest).map_err(Error::io("read", dest))?;
    if meta.is_file() {
        return Ok(Some("not a folder".to_owned()));
    }
    if !meta.is_dir() {
        return Err(Error::NotAFile {
            path: dest.to_path_buf(),
        });
    }
    let folder = OpenFolder::open(dest, false).map_err(|e| refused(dest, "", e))?;
    let Some(file) = file_difference(&folder, world)? else {
        return Ok(None);
    };
    let manifest = |bytes: &[u8]| serde_json::from_slice::<Manifest>(bytes).ok();
    let there = folder
        .read(MANIFEST, MAX_MANIFEST_BYTES)
        .ok()
        .and_then(|file| manifest(&file.bytes));
    let now = world.files.get(MANIFEST).and_then(|b| manifest(b));
    Ok(Some(match (there, now) {
        (Some(there), Some(now)) => what_differs(&there, &now).unwrap_or_else(|| {
            format!("{file}, though it was made with the same settings (changed since?)")
        }),
        _ => file,
    }))
}

/// The first file of `folder` that is not `world`'s, or `None`.
fn file_difference(folder: &OpenFolder, world: &WorldFiles) -> Result<Option<String>, Error> {
    let dest = folder.path();
    for (path, listed) in folder.list() {
        match listed {
            Listed::File { .. } if world.files.contains_key(&path) => {}
            Listed::File { .. } => return Ok(Some(format!("unexpected file {path}"))),
            Listed::EmptyFolder => return Ok(Some(format!("unexpected folder {path}"))),
            Listed::NotAFile => {
                return Err(Error::NotAFile {
                    path: dest.join(path),
                });
            }
            Listed::Unreadable(reason) => {
                return Err(Error::io("read", dest.join(path))(std::io::Error::other(
                    reason,
                )));
            }
        }
    }
    for (path, bytes) in &world.files {
        // A longer file differs: read no more of it than ours holds.
        match folder.read(path, bytes.len() as u64) {
            // Another name for the file may lie outside the world: `check`
            // refuses such a world, and so does the rerun.
            Ok(file) if file.links > 1 => {
                return Ok(Some(format!(
                    "{path} is hard-linked ({} links)",
                    file.links
                )));
            }
            Ok(file) if file.bytes == *bytes => {}
            Ok(_) | Err(ReadError::TooLarge { .. }) => return Ok(Some(format!("{path} differs"))),
            Err(ReadError::Missing) => return Ok(Some(format!("{path} is missing"))),
            Err(e) => return Err(refused(dest, path, e)),
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
