//! The limits and defaults of the scheme model: read by the model
//! (`globals`, `obstacle`, the ranges of `global_range`) and its errors
//! (`error`) alike, so that neither has to import the other.

/// Pallet side in cells when a scheme turns pallets on without `pallet_size`:
/// a NIST pallet holds 10×10 blocks inside its frame.
pub const DEFAULT_PALLET_SIZE: u32 = 10;

/// Standard deviation in steps of a gaussian obstacle that sets no `sigma`
/// (the paper's value).
pub const DEFAULT_SIGMA: f64 = 1.0;

/// The shortest `block_size` and `step_height` (and `base`, unless 0), metres
/// (docs/schemes.md, "Errors"): mesh vertices are `f32` and `check` tells
/// heights apart to 10⁻⁵ m, so a step must be far above both.
pub const MIN_LENGTH: f64 = 1e-3;

/// Largest grid the generator accepts, in cells (docs/schemes.md,
/// "Errors"). 10⁸ cells is a 1 km square at 10 cm blocks: 200 MB of
/// heights, and several GB once meshed.
pub const MAX_CELLS: u64 = 100_000_000;

/// The longest side a grid may measure, metres (`nx·block_size`,
/// `ny·block_size`). Meshes store `f32`: far below its range, and keeps a
/// block's corners distinct in it.
pub const MAX_EXTENT: f64 = 1e5;

/// How many block sizes high a top may be (`base + h·step_height`). Past
/// this a wall one block wide is so slender that its triangles' corners lie
/// within one `f32` unit of their neighbours' edges: the mesh is no longer
/// exact in the files (measured: `random,2000` at 0.1 m/0.1 m breaks 25 of
/// 60 worlds, `random,1000` none of 620).
pub const MAX_TOP_IN_BLOCKS: f64 = 1000.0;

/// The most lattice units along a grid side (cells) or up a top (step
/// heights, `(base + h·step_height) / step_height`), 2^21: an `f32` then
/// tells every lattice point from its neighbours by at least four units in
/// the last place, so a mesh file's vertices map back to the lattice
/// exactly ([`MeshUnits::snap`](crate::mesh::MeshUnits::snap)) and `check`
/// decides its invariants without a tolerance.
pub const MAX_LATTICE_UNITS: u64 = 1 << 21;

/// Largest obstacle height in steps; cells are stored as `u16`.
pub const MAX_HEIGHT: u32 = u16::MAX as u32;

/// The most characters of a field an error quotes.
pub const QUOTE_CHARS: usize = 80;
