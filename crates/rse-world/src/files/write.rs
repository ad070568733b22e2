//! Single output files, written whole or not at all: the one home of mesh
//! files for `rse-gen mesh`, `rse-gen preview` and Python's
//! `Terrain.save`; and [`Created`], the note of what a command made, so a
//! failure removes every file it wrote.

use std::io::Write as _;
use std::path::Path;

use rse_core::Globals;
use rse_core::export::{self, MeshFormat};
use rse_core::mesh::TriMesh;

use crate::error::Error;

/// Writes `bytes` to a temporary file beside `path`, then renames it over
/// `path`: an interrupted run never leaves a half-written file. Errors name
/// `path`, never the temporary file.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let dir = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    // Temporary files are private (0600); the output is an ordinary file.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o644));
    let mut file = builder
        .tempfile_in(dir)
        .map_err(|e| Error::io("write", path)(without_temp_path(&e)))?;
    file.write_all(bytes).map_err(Error::io("write", path))?;
    file.as_file()
        .sync_all()
        .map_err(Error::io("write", path))?;
    file.persist(path)
        .map_err(|e| Error::io("write", path)(e.error))?;
    Ok(())
}

/// `e` without the name of the temporary file `tempfile` adds to it
/// (`… at path "/out/.tmpyWYUw0"`): a name the user never gave, of a file
/// that does not exist. The system's error is kept.
fn without_temp_path(e: &std::io::Error) -> std::io::Error {
    let os_error = e
        .get_ref()
        .and_then(|inner| inner.source())
        .and_then(|source| source.downcast_ref::<std::io::Error>())
        .and_then(std::io::Error::raw_os_error);
    match os_error {
        Some(code) => std::io::Error::from_raw_os_error(code),
        None => std::io::Error::from(e.kind()),
    }
}

/// What one command has created so far, files and folders in order, so
/// that a failure takes them away again ([`Created::undone_on_error`]).
#[derive(Debug, Default)]
pub(crate) struct Created {
    paths: Vec<(std::path::PathBuf, bool)>,
}

impl Created {
    /// Runs `work`, which notes in the given [`Created`] what it makes; if
    /// it fails, everything noted is removed (the newest first), so a
    /// failed command leaves nothing behind.
    pub(crate) fn undone_on_error<T>(
        work: impl FnOnce(&mut Created) -> Result<T, Error>,
    ) -> Result<T, Error> {
        let mut made = Created::default();
        let result = work(&mut made);
        if result.is_err() {
            made.remove_all();
        }
        result
    }

    /// Every folder of `path` that does not exist yet, made one by one
    /// from the top. A part that exists must be a folder and, below
    /// `below` (a folder the user named, which may be a link), not a link:
    /// nothing is written through a link found in a folder given.
    pub(crate) fn folder_chain(&mut self, path: &Path, below: Option<&Path>) -> Result<(), Error> {
        let mut at = std::path::PathBuf::new();
        for part in path.components() {
            at.push(part);
            let checked = below.is_some_and(|top| at.starts_with(top) && at != top);
            // Looked at once more when another process made the folder
            // between our look and our `create_dir` (shards of one batch
            // starting together): then it is theirs, checked as any
            // existing part. Only once: a dangling link is not found by the
            // look and exists for `create_dir`, for ever.
            let mut again = false;
            loop {
                let meta = if checked {
                    std::fs::symlink_metadata(&at)
                } else {
                    std::fs::metadata(&at)
                };
                match meta {
                    Ok(m) if m.is_dir() => break,
                    Ok(m) if m.is_file() => return Err(Error::NotAFolder { path: at }),
                    Ok(_) => return Err(Error::NotAFile { path: at }),
                    Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                        match std::fs::create_dir(&at) {
                            Ok(()) => {
                                self.paths.push((at.clone(), true));
                                break;
                            }
                            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && !again => {
                                again = true;
                            }
                            Err(e) => return Err(Error::io("create", &at)(e)),
                        }
                    }
                    Err(e) => return Err(Error::io("create", &at)(e)),
                }
            }
        }
        Ok(())
    }

    /// Writes `bytes` into a file that must not exist yet (`O_EXCL`: an
    /// existing file or link, even a dangling one, is an error, never
    /// written through).
    pub(crate) fn new_file(&mut self, path: &Path, bytes: &[u8]) -> Result<(), Error> {
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(path)
            .map_err(Error::io("create", path))?;
        self.paths.push((path.to_owned(), false));
        file.write_all(bytes).map_err(Error::io("write", path))?;
        file.sync_all().map_err(Error::io("write", path))
    }

    /// Removes every file and folder noted, the newest first; what cannot
    /// be removed (a folder something was written into since, such as a
    /// batch's finished worlds, kept for a rerun) is left.
    fn remove_all(self) {
        for (path, folder) in self.paths.into_iter().rev() {
            let _ = if folder {
                std::fs::remove_dir(&path)
            } else {
                std::fs::remove_file(&path)
            };
        }
    }
}

/// The mesh format `path`'s suffix names (`.obj`, `.stl`, `.glb`), or the
/// error [`write_mesh`] gives: a caller can refuse a bad name before it
/// builds the mesh.
pub fn mesh_format(path: &Path) -> Result<MeshFormat, Error> {
    MeshFormat::from_path(path).ok_or_else(|| Error::BadMeshPath {
        path: path.to_owned(),
        reason: "unknown mesh format; name the file .obj, .stl or .glb",
    })
}

/// Writes `mesh` to `path` in the format its suffix names (`.obj`, `.stl`,
/// `.glb`). An OBJ gets its material library beside it, named after it
/// (`terrain.obj` → `terrain.mtl`); a name that is not UTF-8 is refused,
/// since the OBJ must name the `.mtl` in text. `globals` give its material (`export::mtl`).
pub fn write_mesh(mesh: &TriMesh, globals: &Globals, path: &Path) -> Result<(), Error> {
    let format = mesh_format(path)?;
    match format {
        MeshFormat::Obj => {
            let mtl_path = path.with_extension("mtl");
            let mtl_name = mtl_path
                .file_name()
                .and_then(|n| n.to_str())
                .ok_or_else(|| Error::BadMeshPath {
                    path: path.to_owned(),
                    reason: "the file name is not UTF-8, so the OBJ could not name its .mtl",
                })?;
            let obj = export::obj(mesh, Some(mtl_name));
            let had_mtl = mtl_path.symlink_metadata().is_ok();
            write_atomically(&mtl_path, export::mtl(globals).as_bytes())?;
            // A failed OBJ takes its new `.mtl` with it.
            write_atomically(path, obj.as_bytes()).inspect_err(|_| {
                if !had_mtl {
                    let _ = std::fs::remove_file(&mtl_path);
                }
            })
        }
        MeshFormat::Stl => write_atomically(path, &export::stl(mesh)),
        MeshFormat::Glb => write_atomically(path, &export::glb(mesh)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_obj_names_the_mtl_written_beside_it() {
        let dir = tempfile::tempdir().unwrap();
        let scheme =
            rse_core::Scheme::from_csv("# size: 3x3\ntype,height\nrandom,2\n", None).unwrap();
        let mesh = rse_core::generate(&scheme, 0, 0).mesh();
        write_mesh(&mesh, &Globals::default(), &dir.path().join("t.obj")).unwrap();
        let text = std::fs::read_to_string(dir.path().join("t.obj")).unwrap();
        assert!(text.contains("mtllib t.mtl"));
        assert!(dir.path().join("t.mtl").is_file());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            2,
            "no temporary file left"
        );
        let err = write_mesh(&mesh, &Globals::default(), &dir.path().join("t.ply")).unwrap_err();
        assert!(err.to_string().contains("unknown mesh format"), "{err}");
    }

    #[cfg(unix)]
    #[test]
    fn a_name_that_is_not_utf8_is_refused_before_writing() {
        use std::os::unix::ffi::OsStrExt as _;
        let dir = tempfile::tempdir().unwrap();
        let scheme =
            rse_core::Scheme::from_csv("# size: 3x3\ntype,height\nrandom,2\n", None).unwrap();
        let mesh = rse_core::generate(&scheme, 0, 0).mesh();
        let name = std::ffi::OsStr::from_bytes(b"t\xff.obj");
        let err = write_mesh(&mesh, &Globals::default(), &dir.path().join(name)).unwrap_err();
        assert!(err.to_string().contains("not UTF-8"), "{err}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn folders_made_by_another_process_meanwhile_are_fine() {
        // Shards of one batch start together and each makes the output
        // folder's chain: whoever comes second finds it made.
        for round in 0..40 {
            let dir = tempfile::tempdir().unwrap();
            let out = dir.path().join(format!("a{round}/b/c"));
            let start = std::sync::Barrier::new(8);
            std::thread::scope(|scope| {
                for _ in 0..8 {
                    scope.spawn(|| {
                        start.wait();
                        let mut made = Created::default();
                        made.folder_chain(&out, None).unwrap();
                    });
                }
            });
            assert!(out.is_dir());
        }
        // A dangling link is not found, and exists for `create_dir`: an
        // error, not a loop.
        let dir = tempfile::tempdir().unwrap();
        std::os::unix::fs::symlink(dir.path().join("nowhere"), dir.path().join("a")).unwrap();
        let mut made = Created::default();
        assert!(made.folder_chain(&dir.path().join("a/b"), None).is_err());
    }
}
