//! The block model: axis-aligned boxes whose union is the solid, far fewer
//! than one per cell, for engines that collide boxes far better than meshes
//! (`MuJoCo`, `PyBullet`, Gazebo and Webots in block mode).

use super::MeshUnits;
use super::cover::{Cover, level_cover};
use super::faces;
use crate::heightmap::Heightmap;

/// An axis-aligned box, in metres, in the grid frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Block {
    /// Centre `[x, y, z]`.
    pub center: [f64; 3],
    /// Half the size along each axis.
    pub half_size: [f64; 3],
    /// The cells under it: `[x0, y0, x1, y1]`, `x1` and `y1` exclusive.
    pub cells: [u32; 4],
}

/// Boxes standing on `z = 0` whose union is exactly the solid
/// `{0 ≤ z ≤ base + h·step}`. Boxes may overlap inside the solid: a box of
/// height `h` may run under cells higher than `h`, never over a lower one,
/// and every cell has a box of its own height over it (so the volume is
/// not the sum of the boxes'). Cells with nothing on them get no box.
pub fn boxes(heights: &Heightmap, units: MeshUnits) -> Vec<Block> {
    boxes_of(heights, units, level_cover)
}

/// The boxes of the rectangles `cover` emits (one per rectangle).
pub(crate) fn boxes_of(heights: &Heightmap, units: MeshUnits, cover: Cover) -> Vec<Block> {
    let mut out = Vec::new();
    let s = units.block_size;
    cover(
        &faces::Levels::new(heights, units.base > 0.0),
        &mut |cells, level| {
            let [x0, y0, x1, y1] = cells;
            let top = units.z(level);
            out.push(Block {
                center: [
                    f64::from(x0 + x1) * s / 2.0,
                    f64::from(y0 + y1) * s / 2.0,
                    top / 2.0,
                ],
                half_size: [
                    f64::from(x1 - x0) * s / 2.0,
                    f64::from(y1 - y0) * s / 2.0,
                    top / 2.0,
                ],
                cells,
            });
        },
    );
    out
}
