//! Splitting vertices where the solid touches itself only along a line.
//!
//! Where two diagonal cells are higher than the other two around a grid
//! corner (a saddle), four walls meet along one vertical line: as points the
//! line is shared, but the surface must pass it twice, once per cell, for
//! every edge to be used by exactly two faces. Around a lattice point the
//! solid is made of up to eight octants (four cells, below and above the
//! point), joined where they share a face. Each group of joined octants gets
//! its own copy of the point, and each triangle corner takes the copy of the
//! group on its inner side. Groups are found from the four cells' tops alone.

use super::faces::{LatticePoint, Levels, Normal};
use super::stitch::Triangles;

/// Gives saddle points one copy per piece of solid; returns the point of
/// every vertex, the triangles' vertex ids and their normals.
pub(crate) fn split_saddles(
    triangles: Triangles,
    levels: &Levels,
) -> (Vec<LatticePoint>, Vec<[u32; 3]>, Vec<Normal>) {
    let Triangles {
        corners,
        mut ids,
        normals,
    } = triangles;
    let mut keys = corners.keys;
    // One byte per point keeps this table in cache while the faces are read.
    let saddles: Vec<Saddle> = keys
        .iter()
        .map(|&[x, y, z]| saddle(levels.around(x, y), z))
        .collect();

    // The second piece's copy, per point.
    let mut copy_of = vec![NONE; keys.len()];
    for (face, &normal) in ids.iter_mut().zip(&normals) {
        if face.iter().all(|&id| saddles[id as usize] == Saddle::None) {
            continue;
        }
        let points = face.map(|id| keys[id as usize]);
        for (c, id) in face.iter_mut().enumerate() {
            // The piece of the smaller quadrant keeps the original id; the
            // other gets a new point, numbered in order of first use.
            let second = match saddles[*id as usize] {
                Saddle::None => continue,
                Saddle::SouthWestNorthEast => 3,
                Saddle::SouthEastNorthWest => 2,
            };
            if inner_quadrant(points, c, normal) != second {
                continue;
            }
            let original = *id as usize;
            if copy_of[original] == NONE {
                copy_of[original] = keys.len() as u32;
                keys.push(keys[original]);
            }
            *id = copy_of[original];
        }
    }
    (keys, ids, normals)
}

const NONE: u32 = u32::MAX;

/// How the solid around a point falls apart, if it does: the diagonal pair
/// of cell quadrants that hold its two pieces.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Saddle {
    /// One piece, or none.
    None,
    /// South-west (0) and north-east (3).
    SouthWestNorthEast,
    /// South-east (1) and north-west (2).
    SouthEastNorthWest,
}

/// The pieces of solid around a point at `level`, with the four cells'
/// `tops` (quadrants 0 south-west, 1 south-east, 2 north-west, 3 north-east).
///
/// Around a point the solid is made of up to eight octants: four quadrants,
/// below and above the point. The octants below form a ring of four, and a
/// subset of a ring of four falls apart only when it is a diagonal pair.
/// Above the point, a cell is solid only if it is below too, and joins its
/// own lower octant. So the solid splits exactly when the cells solid just
/// below form a diagonal pair — or, at the ground, where nothing is below,
/// the cells solid just above do — and each piece is one quadrant's column.
fn saddle(tops: [u32; 4], level: u32) -> Saddle {
    let solid = |top: u32| {
        if level > 0 { top >= level } else { top > 0 }
    };
    match tops.map(solid) {
        [true, false, false, true] => Saddle::SouthWestNorthEast,
        [false, true, true, false] => Saddle::SouthEastNorthWest,
        _ => Saddle::None,
    }
}

/// The cell quadrant on the inner (solid) side of a triangle, next to its
/// corner `c`. Where the triangle spans both sides of an axis at the point,
/// both quadrants lie behind the same face and are joined, so either is
/// right.
fn inner_quadrant(corners: [LatticePoint; 3], c: usize, normal: Normal) -> u8 {
    let p = corners[c];
    let side = |axis: usize| {
        let sum: u32 = corners.iter().map(|k| k[axis]).sum();
        sum >= 3 * p[axis]
    };
    let east = match normal {
        Normal::PosX => false,
        Normal::NegX => true,
        _ => side(0),
    };
    let north = match normal {
        Normal::PosY => false,
        Normal::NegY => true,
        _ => side(1),
    };
    u8::from(east) + 2 * u8::from(north)
}
