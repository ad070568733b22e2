//! What can be wrong with a world: one typed fault per finding, with the
//! file it is in. Data first, text last: the CLI prints the message, JSON
//! and Python get the `kind` and its fields to match on.

use serde::Serialize;

/// One finding of `check`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fault {
    /// The file, `/`-separated and relative to the world folder (or the
    /// batch folder, for a batch fault); `None` for the folder itself.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// What is wrong.
    #[serde(flatten)]
    pub kind: FaultKind,
    /// `kind` in words, as the CLI prints it.
    pub message: String,
}

impl Fault {
    /// A fault of `file` (or of the folder, for `None`).
    pub fn new(file: Option<&str>, kind: FaultKind) -> Self {
        let message = kind.to_string();
        Fault {
            file: file.map(str::to_owned),
            kind,
            message,
        }
    }

    /// A fault of the file at `path`.
    pub fn of(path: &str, kind: FaultKind) -> Self {
        Self::new(Some(path), kind)
    }
}

impl std::fmt::Display for Fault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.file {
            Some(file) => write!(f, "{}: {}", printable(file), self.message),
            None => f.write_str(&self.message),
        }
    }
}

/// `name` (a file or folder name found on disk) safe to print on a
/// terminal: control characters (ESC, BEL, a carriage return…) written as
/// escapes (`\u{1b}`), everything else as it is. JSON and Python get the
/// name unchanged.
pub fn printable(name: &str) -> std::borrow::Cow<'_, str> {
    if name.chars().any(char::is_control) {
        name.chars()
            .map(|c| {
                if c.is_control() {
                    c.escape_unicode().to_string()
                } else {
                    c.to_string()
                }
            })
            .collect::<String>()
            .into()
    } else {
        name.into()
    }
}

/// How a fault quotes text read from a world (a path, a reference):
/// [`rse_core::excerpt`], escaped and cut to [`EXCERPT_CHARS`] characters.
/// Only text that parsed as a world file's own format is quoted at all: a
/// file that does not parse may be anyone's.
pub(crate) fn excerpt(text: &str) -> String {
    rse_core::excerpt(text, EXCERPT_CHARS)
}

/// The most characters of a world's text a fault quotes.
pub const EXCERPT_CHARS: usize = 60;

/// The 1-based line of byte `at` in `bytes` (the last line past the end).
pub(crate) fn line_of(bytes: &[u8], at: usize) -> usize {
    bytes[..at.min(bytes.len())].split(|&b| b == b'\n').count()
}

/// Why a sub-folder of a batch folder is not a world.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NotAWorld {
    /// A folder without `rse.json`: a world that lost it, or anything else.
    NoManifest,
    /// A symbolic link: never followed.
    Link,
}

/// The kinds of fault. In JSON, `kind` is the variant's snake-case name and
/// the fields sit beside it.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
#[non_exhaustive]
pub enum FaultKind {
    /// The folder or file cannot be read (permissions, I/O error, a name
    /// that is not UTF-8).
    Unreadable {
        /// The system's reason.
        reason: String,
    },
    /// A symbolic link or other non-regular file: `rse` writes none, and
    /// following one could read outside the world.
    NotAFile,
    /// A world file with more than one hard link: another name for it may
    /// lie outside the world (anyone's file), so it is not read. `rse`
    /// writes every file once.
    HardLinked {
        /// Its number of links.
        links: u64,
    },
    /// A file larger than any world's can be; refused before reading.
    TooLarge {
        /// Its size, bytes.
        bytes: u64,
        /// The cap it is over.
        cap: u64,
    },
    /// A path (in `rse.json` or named by a world file) that leads outside
    /// the world folder: absolute, or climbing out with `..`.
    OutsideWorld {
        /// The path as written.
        path: String,
    },
    /// `rse.json` is missing, is not JSON, or is not a manifest.
    BadManifest {
        /// What the JSON reader said.
        reason: String,
    },
    /// Rebuilding the world `rse.json` describes would cost more than
    /// `check`'s budget (`check --budget F` raises it): not rebuilt.
    OverBudget {
        /// Cells of the world.
        cells: u64,
        /// Memory the rebuild would take, bytes.
        bytes: u64,
        /// The memory budget, bytes.
        bytes_budget: u64,
        /// Cell visits the rebuild would cost, at most.
        visits: u64,
        /// The visit budget.
        visits_budget: u64,
    },
    /// Files of the world could be compared only with their hashes in
    /// `rse.json` (`check --strict` fails such a world).
    HashOnly {
        /// How many of its files were compared by hash alone.
        files: usize,
    },
    /// The scheme recorded in `rse.json` does not load.
    BadScheme {
        /// The scheme error.
        reason: String,
    },
    /// A file the world must have is not there.
    Missing,
    /// A file the world does not have is there.
    Unexpected,
    /// A file's bytes differ from the world regenerated from `rse.json`.
    Differs {
        /// 1-based line of the first difference (text files).
        #[serde(skip_serializing_if = "Option::is_none")]
        line: Option<usize>,
        /// Byte offset of the first difference.
        byte: usize,
    },
    /// A file that could only be hashed (from a user's template) does not
    /// match its SHA-256 in `rse.json`.
    HashMismatch,
    /// `heightmap.csv` does not parse or has the wrong size.
    BadHeightmap {
        /// What is wrong.
        reason: String,
    },
    /// A cell of `heightmap.csv` is not the regenerated height.
    HeightDiffers {
        /// Cell column.
        x: u32,
        /// Cell row.
        y: u32,
        /// Height in the file, steps.
        found: u16,
        /// Height regenerated, steps.
        expected: u16,
    },
    /// A file that must be UTF-8 text is not.
    NotText,
    /// An XML file that is not well-formed, declares a DTD, or nests too
    /// deep.
    BadXml {
        /// 1-based line of the fault.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A world file names a file that is not in the world.
    MissingReference {
        /// The reference as written.
        reference: String,
    },
    /// A world file names an absolute path: the world could not move.
    AbsoluteReference {
        /// The reference as written.
        reference: String,
    },
    /// A world file names more files than any world holds.
    TooManyReferences {
        /// The most a file may name.
        cap: usize,
    },
    /// The world's report stops here: this many more faults were found.
    MoreFaults {
        /// Faults not listed.
        more: usize,
    },
    /// A world's folder or `rse.json` holds more files than any world.
    TooManyFiles {
        /// The most a world may hold.
        cap: usize,
    },
    /// A world file names a URI of a scheme its simulator does not resolve
    /// inside the world (`file:`, `http:`, …): only `model://` (Gazebo) and
    /// `package://` (URDF) name files a world carries.
    ForeignUri {
        /// The URI's scheme, as written.
        scheme: String,
        /// The reference as written.
        reference: String,
    },
    /// An OBJ file that does not parse, or holds a non-triangle or a
    /// non-finite coordinate.
    BadObj {
        /// What is wrong.
        reason: String,
    },
    /// An OBJ mesh that breaks the mesh invariants of docs/meshes.md (holes, flips, T-junctions, …).
    BadMesh {
        /// How many faults the mesh check found.
        faults: usize,
        /// The first, in words.
        first: String,
    },
    /// The mesh's volume is not the heightmap's.
    VolumeDiffers {
        /// Enclosed by the mesh, m³.
        measured: f64,
        /// Of the heightmap's solid, m³.
        expected: f64,
    },
    /// The mesh's bounding box is not the heightmap's.
    BoundsDiffer {
        /// `[min, max]` of the mesh, metres (none for an empty mesh).
        measured: Option<[[f64; 3]; 2]>,
        /// `[min, max]` of the solid, metres (none for an empty solid).
        expected: Option<[[f64; 3]; 2]>,
    },
    /// An upward face that is not on the top of the cell under it.
    TopMisplaced {
        /// Cell column.
        x: u32,
        /// Cell row.
        y: u32,
        /// The face's height, metres.
        z: f64,
        /// The cell's top, metres.
        top: f64,
    },
    /// The physics smoke test found an error.
    Physics {
        /// The smoke test's words.
        error: String,
    },
    /// A temporary folder left by a run (a batch, an atlas, a single world)
    /// that was cut short.
    Leftover,
    /// A sub-folder of a batch folder that is not a world.
    NotAWorld {
        /// What the folder is instead of a world.
        reason: NotAWorld,
    },
    /// A world of a batch folder made from another recipe than the
    /// batch's first world (shards of different seeds in one folder).
    MixedRecipes {
        /// The batch's first world.
        first: String,
        /// The first setting that differs, in words.
        difference: String,
    },
    /// Two world folders of one batch are the same world.
    Duplicate {
        /// The other folder.
        of: String,
    },
    /// The world folder's name is not the name of the world its
    /// `rse.json` records: renamed, or moved into another world's folder.
    Renamed {
        /// The folder's name (of the folder itself, links resolved).
        folder: String,
        /// The index the manifest records.
        index: u64,
    },
}

impl std::fmt::Display for FaultKind {
    #[allow(clippy::too_many_lines)] // one short arm per kind
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FaultKind::Unreadable { reason } => write!(f, "cannot be read: {reason}"),
            FaultKind::NotAFile => {
                f.write_str("is a link or special file, not a regular file (not followed)")
            }
            FaultKind::HardLinked { links } => write!(
                f,
                "has {links} hard links: another name for it may be outside the world (not read; rse writes each file once)"
            ),
            FaultKind::TooLarge { bytes, cap } => write!(
                f,
                "is {bytes} bytes, over the cap of {cap} for this world (not read)"
            ),
            FaultKind::OutsideWorld { path } => {
                write!(f, "names {path}, outside the world folder (not read)")
            }
            FaultKind::BadManifest { reason } => write!(f, "is not a world manifest: {reason}"),
            FaultKind::BadScheme { reason } => write!(f, "its scheme does not load: {reason}"),
            FaultKind::Missing => {
                f.write_str("missing (the world regenerated from rse.json has it)")
            }
            FaultKind::Unexpected => {
                f.write_str("not a file of the world regenerated from rse.json")
            }
            FaultKind::Differs {
                line: Some(line), ..
            } => write!(
                f,
                "differs from the world regenerated from rse.json, first at line {line}"
            ),
            FaultKind::Differs { line: None, byte } => write!(
                f,
                "differs from the world regenerated from rse.json, first at byte {byte}"
            ),
            FaultKind::HashMismatch => {
                f.write_str("SHA-256 differs from rse.json (the file changed)")
            }
            FaultKind::BadHeightmap { reason } => write!(f, "not a heightmap: {reason}"),
            FaultKind::HeightDiffers {
                x,
                y,
                found,
                expected,
            } => write!(
                f,
                "cell ({x}, {y}) is {found}, but the world regenerated from rse.json has {expected}"
            ),
            FaultKind::NotText => f.write_str("not UTF-8 text"),
            FaultKind::BadXml { line, reason } => {
                write!(f, "not well-formed XML: line {line}: {reason}")
            }
            FaultKind::MissingReference { reference } => {
                write!(f, "names {reference}, which does not exist")
            }
            FaultKind::AbsoluteReference { reference } => write!(
                f,
                "names the absolute path {reference} (worlds must be movable)"
            ),
            FaultKind::TooManyReferences { cap } => write!(
                f,
                "names more than {cap} files (ours name a handful): not checked further"
            ),
            FaultKind::MoreFaults { more } => write!(f, "and {more} more faults, not listed"),
            FaultKind::TooManyFiles { cap } => write!(
                f,
                "holds more than {cap} files (a world holds a few dozen): not checked further"
            ),
            FaultKind::ForeignUri { scheme, reference } => write!(
                f,
                "names {reference}, a `{scheme}:` URI (a world names its own files: relative \
                 paths, model:// in Gazebo files, package:// in URDF)"
            ),
            FaultKind::BadObj { reason } => write!(f, "cannot be read as OBJ: {reason}"),
            FaultKind::BadMesh { faults, first } => write!(
                f,
                "not a closed, oriented, exact mesh: {faults} faults, first: {first}"
            ),
            FaultKind::VolumeDiffers { measured, expected } => write!(
                f,
                "encloses {measured:.6} m³, but the heightmap's solid is {expected:.6} m³"
            ),
            FaultKind::BoundsDiffer { measured, expected } => write!(
                f,
                "bounding box {measured:?}, but the heightmap's solid spans {expected:?}"
            ),
            FaultKind::TopMisplaced { x, y, z, top } => write!(
                f,
                "a top face at z = {z:.4} m lies over cell ({x}, {y}), whose top is at {top:.4} m"
            ),
            FaultKind::Physics { error } => write!(f, "physics: {error}"),
            FaultKind::Leftover => f.write_str(
                "a temporary folder of a run that was cut short: rerun it to finish (it removes the folder)",
            ),
            FaultKind::Duplicate { of } => {
                write!(f, "the same world (seed, index) as {}", printable(of))
            }
            FaultKind::Renamed { folder, index } => write!(
                f,
                "the folder is named {}, but its rse.json is another world's (index {index}): \
                 a world renamed, or moved into another's folder; a world's name is its folder's",
                printable(folder)
            ),
            FaultKind::OverBudget {
                cells,
                bytes,
                bytes_budget,
                visits,
                visits_budget,
            } => write!(
                f,
                "asks for a world of {cells} cells whose rebuild would take {} MiB and {visits} cell visits (some {:.0} s on one core), over check's budget of {} MiB and {visits_budget} visits: not rebuilt (check --budget F allows F times as much)",
                bytes >> 20,
                *visits as f64 * rse_world::VISIT_NANOS * 1e-9,
                bytes_budget >> 20
            ),
            FaultKind::HashOnly { files } => write!(
                f,
                "{files} files could be compared only with their hashes in rse.json (rendered from templates this check does not have: give them with --template DIR); --strict fails such a world"
            ),
            FaultKind::NotAWorld {
                reason: NotAWorld::NoManifest,
            } => f.write_str(
                "is in a batch folder but is not a world: it holds no rse.json (lost, or never a world)",
            ),
            FaultKind::NotAWorld {
                reason: NotAWorld::Link,
            } => f.write_str("is a link in a batch folder, not a world folder (not followed)"),
            FaultKind::MixedRecipes { first, difference } => write!(
                f,
                "was made from another recipe than {}, the batch's first world: {difference}",
                printable(first)
            ),
        }
    }
}
