//! The single mesh of a world (docs/meshes.md): the closed solid under the heightmap.

mod boxes;
mod cover;
mod faces;
pub mod invariants;
pub mod naive;
mod segment_buckets;
mod staircase;
mod stitch;
mod wedge;
mod weld;

pub use boxes::{Block, boxes};
pub use faces::Normal;
pub use invariants::LatticeVolume;

use faces::LatticePoint;

use crate::heightmap::Heightmap;
use crate::terrain::Terrain;

/// A triangle mesh as plain buffers, in the grid frame (metres, Z up, origin
/// at the outer corner of cell (0, 0)). Triangles are counter-clockwise seen
/// from outside; every edge is used by exactly two triangles, in opposite
/// directions.
#[derive(Debug, Clone, PartialEq)]
pub struct TriMesh {
    vertices: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    normals: Vec<Normal>,
    /// Each vertex as the mesher placed it, before rounding to `f32`.
    lattice: Vec<LatticePoint>,
    units: MeshUnits,
}

impl TriMesh {
    /// Vertex positions in metres.
    pub fn vertices(&self) -> &[[f32; 3]] {
        &self.vertices
    }

    /// Vertex indices of each triangle.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The outward normal of each triangle (axis-aligned, but for ramps'
    /// planes).
    pub fn face_normals(&self) -> &[Normal] {
        &self.normals
    }

    /// `true` for the mesh of an empty solid.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Its faults against docs/meshes.md, checked exactly on the lattice
    /// its vertices come from ([`invariants::lattice_faults`]).
    pub fn faults(&self) -> Vec<invariants::MeshFault> {
        let points: Vec<[i128; 3]> = self
            .lattice
            .iter()
            .map(|&p| self.units.lattice_point(p))
            .collect();
        let positions: Vec<[f64; 3]> = points.iter().map(|&p| self.units.position(p)).collect();
        invariants::lattice_faults(&points, &positions, &self.triangles)
    }
}

/// `v = m · 2^e` for a finite `v ≥ 0`, `m` a whole number.
fn binary(v: f64) -> (u64, i32) {
    if v == 0.0 {
        return (0, 0);
    }
    let bits = v.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i32;
    let fraction = bits & ((1 << 52) - 1);
    if exponent == 0 {
        (fraction, -1074)
    } else {
        (fraction | 1 << 52, exponent - 1075)
    }
}

/// Lengths that place the lattice in space, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshUnits {
    /// Cell side, metres: the lattice's x and y unit.
    pub block_size: f64,
    /// Step height, metres: the lattice's level unit.
    pub step_height: f64,
    /// Slab under the grid (0: none).
    pub base: f64,
}

impl MeshUnits {
    /// The height in metres of a lattice level: 0 is the ground, `h + 1`
    /// the top of a cell of `h` steps.
    pub fn z(self, level: u32) -> f64 {
        if level == 0 {
            0.0
        } else {
            self.base + f64::from(level - 1) * self.step_height
        }
    }

    /// The exact binary unit of heights, `2^e`, and `base` and
    /// `step_height` as whole multiples of it (both are `f64`: each is a
    /// whole number times a power of two). A height is `a·base + k·step`
    /// with whole `a`, `k`: a whole multiple of the unit, so collinearity
    /// is a question of integers.
    fn height_unit(self) -> (i32, i128, i128) {
        let ((mb, eb), (ms, es)) = (binary(self.base), binary(self.step_height));
        let e = if mb == 0 { es } else { eb.min(es) };
        // Shifts stay small: base ≤ 2^21 steps (MAX_LATTICE_UNITS), so
        // base's exponent is at most ~75 above step's.
        let whole = |m: u64, exp: i32| i128::from(m) << (exp - e).clamp(0, 100);
        (e, whole(mb, eb), whole(ms, es))
    }

    /// A lattice point `[x, y, level]` in whole units: cells along x and y,
    /// units of height up (`2^e`, whole multiples of which `base` and
    /// `step_height` both are).
    pub fn lattice_point(self, [x, y, level]: [u32; 3]) -> [i128; 3] {
        let (_, base, step) = self.height_unit();
        let z = if level == 0 {
            0
        } else {
            base + i128::from(level - 1) * step
        };
        [i128::from(x), i128::from(y), z]
    }

    /// A whole-unit lattice point in metres (for sorting, not deciding).
    pub fn position(self, [x, y, z]: [i128; 3]) -> [f64; 3] {
        let (e, ..) = self.height_unit();
        [
            x as f64 * self.block_size,
            y as f64 * self.block_size,
            z as f64 * 2f64.powi(e),
        ]
    }

    /// The lattice point whose vertex the mesher writes as `v`, in whole
    /// units, or `None` when `v` is not exactly such a vertex (its `f32`
    /// coordinates are not the rounding of a cell corner, the ground or a
    /// cell's top).
    pub fn snap(self, v: [f32; 3]) -> Option<[i128; 3]> {
        self.snap_level(v).map(|p| self.lattice_point(p))
    }

    /// The lattice point `[x, y, level]` (cell corners, and the level code
    /// of [`MeshUnits::z`]: 0 the ground, `h + 1` a top of `h` steps) whose
    /// vertex the mesher writes as `v`, or `None` as for [`MeshUnits::snap`].
    pub fn snap_level(self, v: [f32; 3]) -> Option<[u32; 3]> {
        let s = self.block_size;
        let corner = |c: f32| {
            let i = (f64::from(c) / s).round();
            // The very bits the mesher writes: an exact test, by intent.
            let same = ((i * s) as f32).to_bits() == c.to_bits();
            (i >= 0.0 && i <= f64::from(u32::MAX) && same).then_some(i as u32)
        };
        let (x, y) = (corner(v[0])?, corner(v[1])?);
        let level = if v[2] == 0.0 {
            0
        } else {
            let k = ((f64::from(v[2]) - self.base) / self.step_height).round();
            // Out of range (an infinite or huge quotient too) is no level:
            // tested before the cast, which saturates, and the `+ 1`.
            if !(k >= 0.0 && k < f64::from(u16::MAX) + 1.0) {
                return None;
            }
            let level = (k as u32) + 1;
            ((self.z(level) as f32).to_bits() == v[2].to_bits()).then_some(level)?
        };
        Some([x, y, level])
    }

    /// The level code of the top of a cell of `h` steps: `h + 1`, or 0 (the
    /// ground) for a cell of 0 steps with no slab under the grid.
    pub fn top_level(self, h: u16) -> u32 {
        if h == 0 && self.base <= 0.0 {
            0
        } else {
            u32::from(h) + 1
        }
    }
}

impl Terrain {
    /// The lengths of this terrain's lattice.
    pub fn mesh_units(&self) -> MeshUnits {
        MeshUnits {
            block_size: self.block_size(),
            step_height: self.step_height(),
            base: self.base(),
        }
    }

    /// The single mesh of this terrain (docs/meshes.md): the blocks' shell,
    /// then a closed wedge for each ramp.
    pub fn mesh(&self) -> TriMesh {
        let mut mesh = build_mesh(self.heightmap(), self.mesh_units());
        for ramp in self.ramps() {
            mesh.add_wedge(ramp);
        }
        mesh
    }

    /// The volume its single mesh encloses, exactly: the cells' solid and
    /// each ramp's wedge (shells of their own, each counted whole).
    pub fn lattice_volume(&self) -> LatticeVolume {
        let map = self.heightmap();
        let units = self.mesh_units();
        let (cells, steps) = map.cells().iter().fold((0u64, 0u64), |(c, s), &h| {
            let solid = units.top_level(h) > 0;
            (c + u64::from(solid), s + u64::from(h))
        });
        self.ramps()
            .iter()
            .filter(|r| r.rise > 0)
            .map(|r| LatticeVolume::of_wedge(r.cell_count(), units.base > 0.0, r.rise))
            .fold(LatticeVolume::of_solid(cells, steps), LatticeVolume::plus)
    }

    /// The block model of this terrain: boxes whose union is the solid.
    pub fn boxes(&self) -> Vec<Block> {
        boxes(self.heightmap(), self.mesh_units())
    }
}

/// Building the block model, per cell of the grid, in cell visits
/// ([`crate::VISIT_NANOS`] each): its work is near linear in the cells and
/// the boxes (at most one a cell), measured 200–470 ns a cell on random
/// fields of height 4 to 1000, cones of radius 100 to 1000 and a 1×10⁶
/// strip (`cargo bench -p rse-core --bench boxes`).
pub const BOXES_VISITS_PER_CELL: u64 = 80;

/// The most bytes building the block model of an `nx` × `ny` grid holds
/// at once: the cover's indexes and the boxes, one a cell at most.
pub fn boxes_bytes(nx: u32, ny: u32) -> u64 {
    let cells = u64::from(nx) * u64::from(ny);
    cover::level_cover_bytes(nx, ny) + cells * std::mem::size_of::<Block>() as u64
}

/// Building the block model of heights already known, per cell (the
/// cover's indexes: 3–14 ns a cell on flat fields) and per wall
/// ([`crate::Walls`]: the cover's rectangles start and stop at them,
/// 56–165 ns a wall on random fields, strips and cones), in cell visits
/// (`cargo bench -p rse-core --bench boxes`). A flat field, priced as a
/// random one a cell, was priced ten times what it took.
pub const BOXES_VISITS_PER_INDEXED_CELL: u64 = 3;
/// See [`BOXES_VISITS_PER_INDEXED_CELL`].
pub const BOXES_VISITS_PER_WALL: u64 = 20;

/// The bytes building the block model of an `nx` × `ny` grid of `walls`
/// holds: the cover's indexes and its boxes, which number a twentieth to
/// two thirds of the walls (most on strips), estimated at half, never more
/// than one a cell.
pub fn counted_boxes_bytes(nx: u32, ny: u32, walls: crate::Walls) -> u64 {
    let cells = u64::from(nx) * u64::from(ny);
    let boxes = (walls.count / 2 + 1).min(cells);
    cover::level_cover_bytes(nx, ny) + boxes * std::mem::size_of::<Block>() as u64
}

/// The closed mesh of the solid `{0 ≤ z ≤ base + h·step}` over every cell.
pub fn build_mesh(heights: &Heightmap, units: MeshUnits) -> TriMesh {
    let levels = faces::Levels::new(heights, units.base > 0.0);
    let triangles = stitch::triangulate(&levels, |emit| faces::faces(&levels, emit));
    let (keys, ids, normals) = weld::split_saddles(triangles, &levels);
    TriMesh {
        vertices: keys.iter().map(|&p| units.vertex(p)).collect(),
        triangles: ids,
        normals,
        lattice: keys,
        units,
    }
}

impl TriMesh {
    /// Appends `ramp`'s wedge as a shell of its own (vertices shared with
    /// nothing before it).
    fn add_wedge(&mut self, ramp: &crate::Ramp) {
        let Some((points, triangles, normals)) = wedge::wedge(ramp, self.units) else {
            return;
        };
        // Fewer than 2^32 vertices: a wedge has 8, the blocks' mesh is
        // indexed by u32.
        let first = self.lattice.len() as u32;
        self.vertices
            .extend(points.iter().map(|&p| self.units.vertex(p)));
        self.lattice.extend(points);
        self.triangles
            .extend(triangles.into_iter().map(|t| t.map(|v| v + first)));
        self.normals.extend(normals);
    }
}

impl MeshUnits {
    /// A lattice point's vertex in metres, rounded to `f32` as every
    /// writer stores it.
    fn vertex(self, [x, y, level]: LatticePoint) -> [f32; 3] {
        [
            (f64::from(x) * self.block_size) as f32,
            (f64::from(y) * self.block_size) as f32,
            self.z(level) as f32,
        ]
    }
}
