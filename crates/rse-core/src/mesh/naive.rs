//! The naive terrain mesh our mesher is measured against: one closed box
//! per cell with solid, concatenated, as the RL terrain generators build
//! their grids; and the block model's cover as first written, walking the
//! area of every rectangle it tries. For benchmarks and comparisons, not
//! for simulators.

use super::Block;
use super::boxes::boxes_of;
use super::cover::reference;
use crate::terrain::Terrain;

/// The block model of `terrain` by the first greedy cover, which walks
/// every cell of every rectangle it tries: the same boxes as
/// [`Terrain::boxes`], in time growing with the rectangles' areas.
pub fn area_walk_boxes(terrain: &Terrain) -> Vec<Block> {
    boxes_of(
        terrain.heightmap(),
        terrain.mesh_units(),
        reference::level_cover,
    )
}

/// The 12 triangles of a closed box whose corner `i` is
/// `(i & 1, i >> 1 & 1, i >> 2 & 1)`, counter-clockwise from outside.
const BOX: [[u32; 3]; 12] = [
    [0, 2, 1],
    [1, 2, 3],
    [4, 5, 6],
    [5, 7, 6],
    [0, 1, 4],
    [1, 5, 4],
    [2, 6, 3],
    [3, 6, 7],
    [0, 4, 2],
    [2, 4, 6],
    [1, 3, 5],
    [3, 7, 5],
];

/// `(vertices, triangles)` of one closed box per cell whose top is above
/// the ground: 8 vertices and 12 triangles each, nothing shared.
pub fn box_per_cell(terrain: &Terrain) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let map = terrain.heightmap();
    let s = terrain.block_size() as f32;
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    for y in 0..map.ny() {
        for x in 0..map.nx() {
            let z = terrain.elevation(x, y) as f32;
            if z <= 0.0 {
                continue;
            }
            let first = vertices.len() as u32;
            for i in 0..8u32 {
                vertices.push([
                    (x + (i & 1)) as f32 * s,
                    (y + ((i >> 1) & 1)) as f32 * s,
                    if i >= 4 { z } else { 0.0 },
                ]);
            }
            triangles.extend(BOX.iter().map(|t| t.map(|k| first + k)));
        }
    }
    (vertices, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::invariants::volume;

    #[test]
    fn twelve_triangles_per_solid_cell_enclosing_the_solid() {
        let scheme = crate::Scheme::from_csv("# size: 6x5\ntype,height\nrandom,3\n", None).unwrap();
        let terrain = crate::generate(&scheme, 0, 1);
        let (v, t) = box_per_cell(&terrain);
        let cells = (0..5).flat_map(|y| (0..6).map(move |x| (x, y)));
        let solid_cells = cells
            .filter(|&(x, y)| terrain.elevation(x, y) > 0.0)
            .count();
        assert_eq!((v.len(), t.len()), (8 * solid_cells, 12 * solid_cells));
        let solid: f64 = (0..5)
            .flat_map(|y| (0..6).map(move |x| (x, y)))
            .map(|(x, y)| terrain.elevation(x, y) * 0.01)
            .sum();
        assert!((volume(&v, &t) - solid).abs() < 1e-6);
    }
}
