//! A folder read by descriptor: opened once, its files listed and opened
//! relative to that descriptor without following any link (at any level)
//! or blocking on a special file, each checked by `fstat` to be a regular
//! file, and read up to a cap from the very descriptor that was checked.
//! `check` reads worlds so, and a batch rerun compares them so: a link,
//! FIFO or device swapped in after the listing is refused, never followed,
//! waited on or read without bound.

use std::io::Read as _;
use std::path::{Path, PathBuf};

use crate::error::Error;

/// The deepest folder listed, counted from the folder opened: a world is
/// three deep at most. Deeper folders are listed as unreadable, not
/// entered, so a forged chain of thousands of folders can neither
/// exhaust the stack nor hold a descriptor per level.
pub const MAX_DEPTH: usize = 16;

/// The most entries listed under a folder: a world holds a few dozen
/// files (an atlas or a user's templates some more). Past it the listing
/// stops with one unreadable entry saying so: 100,000 files with long
/// names once cost `check` 1.5 GiB and a 421 MB report.
pub const MAX_ENTRIES: usize = 4096;

/// `true` once `out` holds [`MAX_ENTRIES`]: the walk stops, and the
/// folder where it stopped (`here`) is listed once more, unreadable, to
/// say so.
fn listing_full(out: &mut Vec<(String, Listed)>, here: impl FnOnce() -> String) -> bool {
    if out.len() == MAX_ENTRIES {
        let reason = format!("more than {MAX_ENTRIES} entries: the rest not listed");
        out.push((here(), Listed::Unreadable(reason)));
    }
    out.len() > MAX_ENTRIES
}

/// The reason given for a folder deeper than [`MAX_DEPTH`].
fn too_deep() -> String {
    format!("more than {MAX_DEPTH} folders deep: not listed")
}

/// What a listed entry is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Listed {
    /// A regular file: its size in bytes and its number of hard links.
    File {
        /// Its size, bytes.
        size: u64,
        /// Hard links to it (1 for a file only this folder holds).
        links: u64,
    },
    /// A symbolic link, FIFO, socket or device: never opened.
    NotAFile,
    /// A folder with nothing in it: rse never writes one, so in a world it
    /// is an extra entry, as a file would be.
    EmptyFolder,
    /// An entry that could not be looked at, or a folder that could not be
    /// listed; with the system's reason.
    Unreadable(String),
}

/// A regular file's bytes, read from the descriptor that was checked.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileBytes {
    /// The content (at most the cap asked for).
    pub bytes: Vec<u8>,
    /// Hard links to the file when it was opened.
    pub links: u64,
}

/// A regular file's SHA-256, computed as it was read from the descriptor
/// that was checked, a buffer at a time (nothing kept).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileDigest {
    /// Lowercase hex SHA-256 of the content.
    pub sha256: String,
    /// Bytes read.
    pub size: u64,
    /// Hard links to the file when it was opened.
    pub links: u64,
}

/// Why a file of an [`OpenFolder`] was not read.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// There is no such file (or a folder on its path is missing).
    #[error("is missing")]
    Missing,
    /// A link (the file or a folder on its path), or a special file.
    #[error("is a link or special file, not a regular file (not followed)")]
    NotAFile,
    /// Larger than the cap: not read (or read up to the cap only).
    #[error("holds {bytes} bytes, over the cap of {cap}")]
    TooLarge {
        /// Its size, bytes (at least `cap + 1` if it grew while read).
        bytes: u64,
        /// The largest size read, bytes.
        cap: u64,
    },
    /// Any other failure of the system.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

/// A folder opened once; every file under it is reached from this
/// descriptor, never again by the folder's path.
#[derive(Debug)]
pub struct OpenFolder {
    path: PathBuf,
    #[cfg(unix)]
    fd: std::os::fd::OwnedFd,
}

impl OpenFolder {
    /// Opens the folder `path`. `follow`: whether `path` itself may be a
    /// link (a folder named on the command line may; a sub-folder found
    /// in a batch folder may not). Links below it are never followed.
    pub fn open(path: &Path, follow: bool) -> Result<Self, ReadError> {
        #[cfg(unix)]
        {
            let fd = unix::open_dir(rustix::fs::CWD, path, follow)?;
            Ok(OpenFolder {
                path: path.to_path_buf(),
                fd,
            })
        }
        #[cfg(not(unix))]
        {
            let meta = if follow {
                std::fs::metadata(path)
            } else {
                std::fs::symlink_metadata(path)
            };
            match meta {
                Ok(m) if m.is_dir() => Ok(OpenFolder {
                    path: path.to_path_buf(),
                }),
                Ok(_) => Err(ReadError::NotAFile),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(ReadError::Missing),
                Err(e) => Err(ReadError::Io(e)),
            }
        }
    }

    /// The folder's path, as given.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Every entry under the folder but the folders themselves (save empty
    /// ones), as `/`-separated relative paths, sorted. A name that is not
    /// UTF-8 is listed lossily as [`Listed::Unreadable`]; a folder that
    /// cannot be listed, or lies deeper than `MAX_DEPTH` (16) levels, appears as
    /// itself, unreadable.
    pub fn list(&self) -> Vec<(String, Listed)> {
        let mut out = Vec::new();
        #[cfg(unix)]
        unix::walk(&self.fd, "", 0, &mut out);
        #[cfg(not(unix))]
        portable::walk(&self.path, "", 0, &mut out);
        out.sort_by(|a, b| a.0.cmp(&b.0));
        out
    }

    /// The regular file at the relative path `relative` (`/`-separated,
    /// [`inside`](crate::files::tree::inside)), if it holds at most `cap` bytes: opened
    /// without following a link at any level, checked to be a regular
    /// file, and read from that descriptor, never more than `cap + 1`
    /// bytes.
    pub fn read(&self, relative: &str, cap: u64) -> Result<FileBytes, ReadError> {
        let (mut file, size, links) = self.open_capped(relative, cap)?;
        let mut bytes = Vec::with_capacity(size as usize);
        file.read_to_end(&mut bytes)?;
        within(bytes.len() as u64, cap)?;
        Ok(FileBytes { bytes, links })
    }

    /// The SHA-256 of the regular file at `relative`, opened as
    /// [`read`](Self::read) opens it and hashed as it streams, never past
    /// `cap + 1` bytes: memory that does not grow with the file.
    pub fn digest(&self, relative: &str, cap: u64) -> Result<FileDigest, ReadError> {
        use sha2::{Digest as _, Sha256};
        let (mut file, _, links) = self.open_capped(relative, cap)?;
        let (mut hasher, mut buffer, mut size) = (Sha256::new(), vec![0u8; 64 << 10], 0u64);
        loop {
            let n = file.read(&mut buffer)?;
            if n == 0 {
                break;
            }
            hasher.update(&buffer[..n]);
            size += n as u64;
        }
        within(size, cap)?;
        Ok(FileDigest {
            sha256: crate::files::digest::hex(&hasher.finalize()),
            size,
            links,
        })
    }

    /// The regular file at `relative`, opened as [`read`](Self::read)
    /// describes, refused when its size is past `cap`, and limited to
    /// `cap + 1` bytes (it may grow after the check): with its size and
    /// hard links.
    fn open_capped(
        &self,
        relative: &str,
        cap: u64,
    ) -> Result<(std::io::Take<std::fs::File>, u64, u64), ReadError> {
        if !crate::files::tree::inside(relative) {
            return Err(ReadError::Missing);
        }
        #[cfg(unix)]
        let (file, links) = unix::open_file(&self.fd, relative)?;
        #[cfg(not(unix))]
        let (file, links) = portable::open_file(&self.path, relative)?;
        let size = file.metadata()?.len();
        within(size, cap)?;
        Ok((file.take(cap.saturating_add(1)), size, links))
    }
}

/// `TooLarge` when `bytes` is past `cap`.
fn within(bytes: u64, cap: u64) -> Result<(), ReadError> {
    if bytes > cap {
        return Err(ReadError::TooLarge { bytes, cap });
    }
    Ok(())
}

/// The error of reading `path` (relative, `""` for the folder itself) in
/// the folder `dest`: what every reader of a folder it was given reports.
pub(crate) fn refused(dest: &Path, path: &str, e: ReadError) -> Error {
    let at = if path.is_empty() {
        dest.to_path_buf()
    } else {
        dest.join(path)
    };
    match e {
        ReadError::NotAFile => Error::NotAFile { path: at },
        ReadError::Io(e) => Error::io("read", at)(e),
        other => Error::io("read", at)(std::io::Error::other(other.to_string())),
    }
}

#[cfg(unix)]
mod unix {
    //! The descriptor-relative calls (`openat`, `fstat`, `getdents`).

    use std::os::fd::{AsFd, OwnedFd};
    use std::path::Path;

    use rustix::fs::{AtFlags, FileType, Mode, OFlags};
    use rustix::io::Errno;

    use super::{Listed, ReadError};

    fn refusal(e: Errno) -> ReadError {
        match e {
            Errno::NOENT => ReadError::Missing,
            // A link where `O_NOFOLLOW` forbids one (ELOOP; EMLINK on
            // FreeBSD), or a non-folder on the path (ENOTDIR).
            Errno::LOOP | Errno::MLINK | Errno::NOTDIR => ReadError::NotAFile,
            e => ReadError::Io(e.into()),
        }
    }

    /// The folder `name` in `dir`, opened as a folder only.
    pub(super) fn open_dir(
        dir: impl AsFd,
        name: &Path,
        follow: bool,
    ) -> Result<OwnedFd, ReadError> {
        let mut flags = OFlags::RDONLY | OFlags::DIRECTORY | OFlags::CLOEXEC;
        if !follow {
            flags |= OFlags::NOFOLLOW;
        }
        rustix::fs::openat(dir, name, flags, Mode::empty()).map_err(refusal)
    }

    /// The regular file at `relative` under `root`, and its link count.
    pub(super) fn open_file(
        root: &OwnedFd,
        relative: &str,
    ) -> Result<(std::fs::File, u64), ReadError> {
        let (folders, name) = relative.rsplit_once('/').unwrap_or(("", relative));
        let mut at: Option<OwnedFd> = None;
        for part in folders.split('/').filter(|p| !p.is_empty()) {
            let next = match &at {
                Some(fd) => open_dir(fd, Path::new(part), false)?,
                None => open_dir(root, Path::new(part), false)?,
            };
            at = Some(next);
        }
        // O_NONBLOCK: opening a FIFO returns at once instead of waiting for
        // a writer; fstat then refuses it.
        let flags = OFlags::RDONLY | OFlags::NOFOLLOW | OFlags::NONBLOCK | OFlags::CLOEXEC;
        let fd = match &at {
            Some(dir) => rustix::fs::openat(dir, name, flags, Mode::empty()),
            None => rustix::fs::openat(root, name, flags, Mode::empty()),
        }
        .map_err(refusal)?;
        let stat = rustix::fs::fstat(&fd).map_err(refusal)?;
        if FileType::from_raw_mode(stat.st_mode) != FileType::RegularFile {
            return Err(ReadError::NotAFile);
        }
        Ok((std::fs::File::from(fd), stat.st_nlink as u64))
    }

    /// Lists the folder `dir` (at `prefix`, `depth` folders down) into
    /// `out`, recursively.
    pub(super) fn walk(dir: &OwnedFd, prefix: &str, depth: usize, out: &mut Vec<(String, Listed)>) {
        let here = || prefix.trim_end_matches('/').to_owned();
        let listed = out.len();
        let entries = match rustix::fs::Dir::read_from(dir) {
            Ok(entries) => entries,
            Err(e) => return out.push((here(), Listed::Unreadable(e.to_string()))),
        };
        for entry in entries {
            if super::listing_full(out, here) {
                return;
            }
            let entry = match entry {
                Ok(entry) => entry,
                Err(e) => {
                    out.push((here(), Listed::Unreadable(e.to_string())));
                    break;
                }
            };
            let raw = entry.file_name();
            if matches!(raw.to_bytes(), b"." | b"..") {
                continue;
            }
            let Ok(name) = raw.to_str() else {
                let lossy = raw.to_string_lossy();
                let reason = "the file name is not UTF-8".to_owned();
                out.push((format!("{prefix}{lossy}"), Listed::Unreadable(reason)));
                continue;
            };
            let relative = format!("{prefix}{name}");
            // `lstat` relative to the folder: the entry itself, never a
            // link's target.
            let stat = match rustix::fs::statat(dir, raw, AtFlags::SYMLINK_NOFOLLOW) {
                Ok(stat) => stat,
                Err(e) => {
                    out.push((relative, Listed::Unreadable(e.to_string())));
                    continue;
                }
            };
            match FileType::from_raw_mode(stat.st_mode) {
                FileType::Directory if depth >= super::MAX_DEPTH => {
                    out.push((relative, Listed::Unreadable(super::too_deep())));
                }
                FileType::Directory => match open_dir(dir, Path::new(name), false) {
                    Ok(sub) => walk(&sub, &format!("{relative}/"), depth + 1, out),
                    Err(ReadError::NotAFile) => out.push((relative, Listed::NotAFile)),
                    Err(e) => out.push((relative, Listed::Unreadable(e.to_string()))),
                },
                FileType::RegularFile => out.push((
                    relative,
                    Listed::File {
                        size: stat.st_size as u64,
                        links: stat.st_nlink as u64,
                    },
                )),
                _ => out.push((relative, Listed::NotAFile)),
            }
        }
        if out.len() == listed && !prefix.is_empty() {
            out.push((here(), Listed::EmptyFolder));
        }
    }
}

#[cfg(not(unix))]
mod portable {
    //! Elsewhere: by path, links refused by `symlink_metadata` (a race
    //! the descriptor calls close is left open).

    use std::path::Path;

    use super::{Listed, ReadError};

    pub(super) fn open_file(
        root: &Path,
        relative: &str,
    ) -> Result<(std::fs::File, u64), ReadError> {
        let path = root.join(relative);
        match std::fs::symlink_metadata(&path) {
            Ok(m) if m.is_file() => Ok((std::fs::File::open(&path)?, 1)),
            Ok(_) => Err(ReadError::NotAFile),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(ReadError::Missing),
            Err(e) => Err(ReadError::Io(e)),
        }
    }

    pub(super) fn walk(dir: &Path, prefix: &str, depth: usize, out: &mut Vec<(String, Listed)>) {
        let here = || prefix.trim_end_matches('/').to_owned();
        let listed = out.len();
        let entries = match std::fs::read_dir(dir) {
            Ok(entries) => entries,
            Err(e) => return out.push((here(), Listed::Unreadable(e.to_string()))),
        };
        for entry in entries {
            if super::listing_full(out, here) {
                return;
            }
            let Ok(entry) = entry else { continue };
            let name = entry.file_name();
            let Some(name) = name.to_str() else {
                let reason = "the file name is not UTF-8".to_owned();
                out.push((
                    format!("{prefix}{}", name.to_string_lossy()),
                    Listed::Unreadable(reason),
                ));
                continue;
            };
            let relative = format!("{prefix}{name}");
            match std::fs::symlink_metadata(entry.path()) {
                Ok(m) if m.is_dir() && depth >= super::MAX_DEPTH => {
                    out.push((relative, Listed::Unreadable(super::too_deep())));
                }
                Ok(m) if m.is_dir() => walk(&entry.path(), &format!("{relative}/"), depth + 1, out),
                Ok(m) if m.is_file() => out.push((
                    relative,
                    Listed::File {
                        size: m.len(),
                        links: 1,
                    },
                )),
                Ok(_) => out.push((relative, Listed::NotAFile)),
                Err(e) => out.push((relative, Listed::Unreadable(e.to_string()))),
            }
        }
        if out.len() == listed && !prefix.is_empty() {
            out.push((here(), Listed::EmptyFolder));
        }
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    fn world() -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("w/sub")).unwrap();
        std::fs::write(dir.path().join("w/a.txt"), "inside").unwrap();
        std::fs::write(dir.path().join("w/sub/b.txt"), "deeper").unwrap();
        std::fs::write(dir.path().join("secret"), "outside").unwrap();
        dir
    }

    #[test]
    fn regular_files_are_listed_and_read_within_their_cap() {
        let dir = world();
        let folder = OpenFolder::open(&dir.path().join("w"), false).unwrap();
        let listed = folder.list();
        let file = Listed::File { size: 6, links: 1 };
        assert_eq!(
            listed,
            [
                ("a.txt".to_owned(), file.clone()),
                ("sub/b.txt".to_owned(), file)
            ]
        );
        assert_eq!(folder.read("sub/b.txt", 6).unwrap().bytes, b"deeper");
        assert!(matches!(
            folder.read("a.txt", 5),
            Err(ReadError::TooLarge { bytes: 6, cap: 5 })
        ));
        assert!(matches!(folder.read("none", 5), Err(ReadError::Missing)));
        assert!(matches!(
            folder.read("../secret", 99),
            Err(ReadError::Missing)
        ));
    }

    #[test]
    fn links_at_any_level_and_fifos_are_refused_not_followed() {
        let dir = world();
        let w = dir.path().join("w");
        std::os::unix::fs::symlink(dir.path().join("secret"), w.join("link")).unwrap();
        std::os::unix::fs::symlink(dir.path(), w.join("up")).unwrap();
        let fifo = std::process::Command::new("mkfifo")
            .arg(w.join("fifo"))
            .status()
            .unwrap();
        assert!(fifo.success());
        let folder = OpenFolder::open(&w, false).unwrap();
        let listed: Vec<_> = folder
            .list()
            .into_iter()
            .filter(|(_, l)| *l == Listed::NotAFile)
            .collect();
        let names: Vec<&str> = listed.iter().map(|(p, _)| p.as_str()).collect();
        assert_eq!(names, ["fifo", "link", "up"]);
        for path in ["link", "up/secret", "fifo"] {
            assert!(
                matches!(folder.read(path, 99), Err(ReadError::NotAFile)),
                "{path}"
            );
        }
        // The folder itself as a link: refused unless named to be followed.
        std::os::unix::fs::symlink(&w, dir.path().join("w2")).unwrap();
        assert!(matches!(
            OpenFolder::open(&dir.path().join("w2"), false),
            Err(ReadError::NotAFile)
        ));
        assert!(OpenFolder::open(&dir.path().join("w2"), true).is_ok());
    }

    #[test]
    fn a_hard_link_is_counted() {
        let dir = world();
        std::fs::hard_link(dir.path().join("secret"), dir.path().join("w/hard")).unwrap();
        let folder = OpenFolder::open(&dir.path().join("w"), false).unwrap();
        assert_eq!(folder.read("hard", 99).unwrap().links, 2);
        assert!(
            folder
                .list()
                .contains(&("hard".to_owned(), Listed::File { size: 7, links: 2 }))
        );
    }

    /// The depth limit where it lives (the CLI and Python test it from
    /// outside): a chain of folders `MAX_DEPTH` deep is listed to its file;
    /// one level more is listed as its deepest folder, unreadable, and
    /// nothing below it is opened.
    #[test]
    fn folders_deeper_than_the_limit_are_listed_unreadable() {
        let dir = tempfile::tempdir().unwrap();
        let chain = |levels: usize| -> String { vec!["d"; levels].join("/") };
        std::fs::create_dir_all(dir.path().join(chain(MAX_DEPTH))).unwrap();
        std::fs::write(dir.path().join(chain(MAX_DEPTH)).join("f"), b"x").unwrap();
        let folder = OpenFolder::open(dir.path(), false).unwrap();
        assert_eq!(
            folder.list(),
            [(
                format!("{}/f", chain(MAX_DEPTH)),
                Listed::File { size: 1, links: 1 }
            )]
        );
        std::fs::create_dir(dir.path().join(chain(MAX_DEPTH + 1))).unwrap();
        std::fs::rename(
            dir.path().join(chain(MAX_DEPTH)).join("f"),
            dir.path().join(chain(MAX_DEPTH + 1)).join("f"),
        )
        .unwrap();
        assert_eq!(
            folder.list(),
            [(chain(MAX_DEPTH + 1), Listed::Unreadable(too_deep()))]
        );
    }
}
