//! Every cap and tolerance of `check`, named once. The caps keep a hostile
//! or damaged world from making `check` read, allocate or loop without
//! bound; each is far above what any world `rse` writes can need.

/// `rse.json` larger than this is refused before it is read, bytes. A
/// manifest holds the scheme, the drawn obstacles and one hash per file:
/// kilobytes for any real scheme.
pub const MAX_MANIFEST_BYTES: u64 = 16 << 20;

/// A file `check` cannot regenerate (a user template's output) may hold at
/// most this many bytes per cell of the world's grid, plus
/// [`FIXED_FILE_BYTES`]. Our largest per-cell file, a block-mode world's
/// box list or a random field's OBJ, is well under 1 KiB per cell.
pub const FILE_BYTES_PER_CELL: u64 = 4096;

/// The fixed part of the per-file cap, bytes: room for a robot model or a
/// texture a user's template adds to every world.
pub const FIXED_FILE_BYTES: u64 = 64 << 20;

/// An XML element nested deeper than this is a fault: our world files
/// nest a dozen levels, and a parser that recurses (as some simulators'
/// do) could be overrun by a file nesting thousands.
pub const MAX_XML_DEPTH: usize = 256;

/// Relative tolerance of lengths and volumes read back from a mesh file:
/// OBJ coordinates are printed from `f32`, about 7 significant digits.
pub const MESH_RELATIVE_TOLERANCE: f64 = 1e-5;

/// The byte cap of a file that cannot be regenerated, in a world of
/// `cells` cells.
pub fn file_cap(cells: u64) -> u64 {
    FIXED_FILE_BYTES.saturating_add(cells.saturating_mul(FILE_BYTES_PER_CELL))
}
