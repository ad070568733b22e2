//! Every cap and tolerance of `check`, named once. The caps keep a hostile
//! or damaged world from making `check` read, allocate or loop without
//! bound; each is far above what any world `rse` writes can need.

/// `rse.json` larger than this is refused before it is read, bytes (a
/// batch rerun reads it with the same cap).
pub use rse_world::MAX_MANIFEST_BYTES;

/// A file `check` cannot regenerate (a user template's output) may hold
/// what a batch lets a template render: at most this many bytes per cell
/// of the world's grid, plus [`FIXED_FILE_BYTES`].
pub use rse_world::{FILE_BYTES_PER_CELL, FIXED_FILE_BYTES};

/// An XML element nested deeper than this is a fault: our world files
/// nest a dozen levels, and a parser that recurses (as some simulators'
/// do) could be overrun by a file nesting thousands.
pub const MAX_XML_DEPTH: usize = 256;

/// A world's report lists at most this many faults, then how many more
/// there were: a folder of 100,000 stray files once made a 421 MB report.
pub const MAX_FAULTS: usize = 100;

/// A world file naming more files than this is a fault, not read further:
/// ours name a handful, and the references are held while they are
/// checked (3.1 million in a 60 MiB file once took 1.3 GiB).
pub const MAX_REFERENCES: usize = 65_536;

/// The most files a world's `rse.json` may list: as many as a world folder
/// is listed to ([`rse_world::MAX_ENTRIES`]). Each listed file `check`
/// cannot rebuild is hashed, and 16 MiB of manifest holds ~180,000 names.
pub use rse_world::MAX_ENTRIES as MAX_MANIFEST_FILES;

/// An OBJ file with more `o` and `g` statements than this is a fault,
/// not parsed: the reader makes a model of each, tens of times the bytes
/// of the line. Ours have one.
pub const MAX_OBJ_OBJECTS: usize = 1024;

/// The cell visits one world's rebuild may cost under `check`'s default
/// budget ([`rse_world::RebuildCost`], [`rse_world::VISIT_NANOS`] each):
/// some 100 s on one core of the development machine, room for any
/// 1000×1000 world with every target (a field of random steps of height 4
/// takes some 45 s, of height 1000 some 80 s). `check --budget F` allows F
/// times as much. The same budget as `check-curriculum`'s.
pub const REBUILD_VISITS: u64 = rse_core::BUDGET_VISITS;

/// The memory one world's rebuild may take under the default budget: the
/// memory available (`MemAvailable`, or less under an address-space
/// limit); 8 GiB where that cannot be read. A world has all of it: the
/// worlds checked at once are as many as it holds together
/// ([`check_paths`](crate::check_paths)), never a share of it each.
pub fn rebuild_bytes() -> u64 {
    rse_world::available_bytes().unwrap_or(8 << 30)
}

/// The byte cap of a file that cannot be regenerated, in a world of
/// `cells` cells.
pub fn file_cap(cells: u64) -> u64 {
    rse_world::rendered_file_cap(cells)
}
