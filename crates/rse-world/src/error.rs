//! What can go wrong while building or writing worlds.

use std::path::PathBuf;

/// An error of world building or batch writing.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// An option value that is not one of those allowed: a target, mesh
    /// mode, shard or worker count.
    #[error("{message}")]
    BadOption {
        /// The option, as the library names it: "target", "mesh", "shard", "jobs".
        option: &'static str,
        /// What was given and what is allowed.
        message: String,
    },
    /// A mesh file name the writer cannot serve.
    #[error("{}: {reason}", path.display())]
    BadMeshPath {
        /// The file asked for.
        path: PathBuf,
        /// Why it cannot be written.
        reason: &'static str,
    },
    /// A template folder that cannot be used.
    #[error("template folder {}: {reason}", path.display())]
    BadTemplateFolder {
        /// The folder given.
        path: PathBuf,
        /// What is wrong with it.
        reason: String,
    },
    /// A template renders a file the generator writes itself.
    #[error("the {target} template has a file {path} that the generator writes itself")]
    TemplateClash {
        /// The target whose template it is.
        target: String,
        /// The file, relative to the world folder.
        path: String,
    },
    /// The worker threads could not be started.
    #[error("cannot start {jobs} worker threads")]
    Threads {
        /// How many were asked for ("one per core" when unset).
        jobs: String,
        /// The system's reason.
        source: rayon::ThreadPoolBuildError,
    },
    /// A template that does not parse or render.
    #[error("{file}:{line}: {message}")]
    Template {
        /// The template file, as its folder names it.
        file: String,
        /// 1-based line of the fault.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// Reading or writing a file failed. The message names the path; the
    /// system's reason is the error's source (printed after it by `{:#}`).
    #[error("cannot {action} {}", path.display())]
    Io {
        /// What was being done: "write", "read", "rename"…
        action: &'static str,
        /// The file or folder.
        path: PathBuf,
        /// The system's error.
        source: std::io::Error,
    },
    /// A link or special file (FIFO, device, socket) where a world's file
    /// or folder is: never followed, opened or replaced.
    #[error("{} is a link or special file, not a regular file or folder: rse writes neither, and neither follows nor reads one; remove it, or write to another folder", path.display())]
    NotAFile {
        /// Where it is.
        path: PathBuf,
    },
    /// A file where rse must make or enter a folder.
    #[error("{} is a file, not a folder: rse cannot write into it; remove it, or write to another folder", path.display())]
    NotAFolder {
        /// Where it is.
        path: PathBuf,
    },
    /// A world folder already holds something else.
    #[error("{} holds a different world: {reason}", path.display())]
    Conflict {
        /// The world folder.
        path: PathBuf,
        /// The first difference found.
        reason: String,
    },
    /// A batch too large for this machine's memory.
    #[error("{message}")]
    TooBig {
        /// What it needs and what there is.
        message: String,
    },
    /// Another run is writing the same shard of the same output folder.
    #[error("another rse-gen batch is writing shard {shard} of {} right now; wait for it to end (a rerun then skips every world it wrote)", path.display())]
    Busy {
        /// The output folder.
        path: PathBuf,
        /// The shard, `K/N`.
        shard: String,
    },
    /// An atlas that cannot be laid out.
    #[error(transparent)]
    Atlas(#[from] rse_core::AtlasError),
    /// Two schemes of an atlas whose tiles cannot sit side by side.
    #[error(
        "{scheme} has {field} {found}, but {first} has {expected}: every tile of an atlas must share it"
    )]
    AtlasMismatch {
        /// `block_size`, `step_height`, `base` or `size`.
        field: &'static str,
        /// The scheme that differs, by name.
        scheme: String,
        /// That scheme's value, as text.
        found: String,
        /// The first scheme, by name.
        first: String,
        /// The first scheme's value.
        expected: String,
    },
    /// Another run is writing the same world folder (an atlas).
    #[error("another rse-gen is writing {} right now; wait for it to end", path.display())]
    BusyWorld {
        /// The world folder.
        path: PathBuf,
    },
    /// A height field that cannot be made.
    #[error(transparent)]
    HField(#[from] rse_core::HFieldError),
    /// Encoding a world file failed.
    #[error(transparent)]
    Core(#[from] rse_core::Error),
}

impl Error {
    /// An I/O error with what was being done and where.
    pub(crate) fn io(
        action: &'static str,
        path: impl Into<PathBuf>,
    ) -> impl FnOnce(std::io::Error) -> Error {
        let path = path.into();
        move |source| Error::Io {
            action,
            path,
            source,
        }
    }
}
