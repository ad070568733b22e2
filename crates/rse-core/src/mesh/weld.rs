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

use super::faces::{Key, Levels, Normal};
use super::stitch::Triangles;

/// Gives saddle points one copy per piece of solid; returns the point of
/// every vertex, the triangles' vertex ids and their normals.
pub(crate) fn split_saddles(
    triangles: Triangles,
    levels: &Levels,
) -> (Vec<Key>, Vec<[u32; 3]>, Vec<Normal>) {
    let Triangles {
        corners,
        mut ids,
        normals,
    } = triangles;
    let mut keys = corners.keys;
    let pieces: Vec<Option<Pieces>> = keys
        .iter()
        .map(|&[x, y, z]| solid_pieces(levels.around(x, y), z))
        .collect();

    // A saddle has two pieces: the second one's copy, per point.
    let mut copy_of = vec![NONE; keys.len()];
    for (face, &normal) in ids.iter_mut().zip(&normals) {
        if face.iter().all(|&id| pieces[id as usize].is_none()) {
            continue;
        }
        let points = face.map(|id| keys[id as usize]);
        for (c, id) in face.iter_mut().enumerate() {
            let Some(piece) = pieces[*id as usize] else {
                continue;
            };
            let group = piece.group[inner_octant(points, c, normal)];
            // The first piece keeps the original id; the other gets a new
            // point, numbered in order of first use.
            if group == piece.first {
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

/// Octant index: cell quadrant (0 south-west, 1 south-east, 2 north-west,
/// 3 north-east) plus 4 above the point.
fn octant(east: bool, north: bool, above: bool) -> usize {
    usize::from(east) + 2 * usize::from(north) + 4 * usize::from(above)
}

/// The two pieces of solid around a saddle point.
#[derive(Clone, Copy)]
struct Pieces {
    /// Per octant, its piece, labelled by the piece's smaller cell quadrant.
    group: [u8; 8],
    /// The label of the piece of the smaller quadrant.
    first: u8,
}

/// The pieces of solid around a point at `level`, with the four cells'
/// `tops`, when there are two; `None` when there is one or none.
///
/// The octants below the point form a ring of four quadrants (south-west,
/// south-east, north-east, north-west), and a subset of a ring of four falls
/// apart only when it is a diagonal pair. Above the point, a cell is solid
/// only if it is below too, and joins its own lower octant. So the solid
/// splits exactly when the cells solid just below form a diagonal pair — or,
/// at the ground, where nothing is below, the cells solid just above do.
fn solid_pieces(tops: [u32; 4], level: u32) -> Option<Pieces> {
    let mask = |solid: &dyn Fn(u32) -> bool| {
        tops.iter()
            .enumerate()
            .fold(0u8, |m, (q, &top)| m | (u8::from(solid(top)) << q))
    };
    let cells = if level > 0 {
        mask(&|top| top >= level)
    } else {
        mask(&|top| top > 0)
    };
    let (a, b) = match cells {
        0b1001 => (0u8, 3u8),
        0b0110 => (1, 2),
        _ => return None,
    };
    Some(Pieces {
        group: std::array::from_fn(|o| if o as u8 % 4 == b { b } else { a }),
        first: a,
    })
}

/// The octant on the inner (solid) side of a triangle, next to its corner `c`.
/// Where the triangle spans both sides of an axis at the point, both octants
/// lie behind the same face and are joined, so either is right.
fn inner_octant(corners: [Key; 3], c: usize, normal: Normal) -> usize {
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
    let above = match normal {
        Normal::PosZ => false,
        Normal::NegZ => true,
        _ => side(2),
    };
    octant(east, north, above)
}
