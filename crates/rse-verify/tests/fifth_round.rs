//! The fifth hardening round (issue 50): fresh worlds that `check` failed
//! (a T-junction search that gave up on our own mesh, a volume summed from
//! `f32` vertices), each built here as the red team built it.

use rse_core::mesh::invariants::volume;
use rse_core::{Scheme, generate};
use rse_verify::{ObjMesh, mesh_faults_against};

/// The terrain of world `index` of `csv` and its mesh as an OBJ reads back
/// (the writer prints each `f32` exactly, so the reader gets its bits).
fn terrain_and_mesh(csv: &str, index: u64) -> (rse_core::Terrain, ObjMesh) {
    let scheme = Scheme::from_csv(csv, None).unwrap();
    let terrain = generate(&scheme, 0, index);
    let mesh = terrain.mesh();
    let obj = ObjMesh {
        vertices: mesh.vertices().to_vec(),
        triangles: mesh.triangles().to_vec(),
    };
    (terrain, obj)
}

/// Hole 1: a wall 600 steps tall along a 9×1000 grid made 4 of 5 fresh
/// worlds "too irregular to search for T-junctions": its fan edges, long
/// diagonals across the wall, walked every bucket of their bounding boxes.
/// They walk their path now; every world of the scheme is sound.
#[test]
fn a_tall_wall_on_a_long_thin_grid_is_searched_to_the_end() {
    let csv =
        "# size: 9x1000\ntype,height,angle,x1,y1,x2,y2\nrandom,1,,,,,\nwall,600,90,4,0,4,999\n";
    for index in 0..5 {
        let (terrain, obj) = terrain_and_mesh(csv, index);
        let faults = mesh_faults_against(&obj, &terrain);
        assert!(faults.is_empty(), "world {index}: {faults:?}");
    }
}

/// Hole 2: on a long strip (the red team's 1×1,000,000; here 1×100,000 of
/// 1 mm steps) the volume summed from the `f32` vertices is off by more
/// than the old tolerance (1e-5): it is decided on the lattice now, exactly.
#[test]
fn a_long_strip_has_its_volume_to_the_cell() {
    let csv = "# size: 1x100000\n# block_size: 0.1\n# step_height: 0.001\ntype,height\nrandom,1\n";
    let (terrain, obj) = terrain_and_mesh(csv, 0);
    // The case is the hole's: the f32 sum is past the old tolerance.
    let (b, step, base) = (terrain.block_size(), terrain.step_height(), terrain.base());
    let solid: f64 = terrain
        .heightmap()
        .cells()
        .iter()
        .map(|&h| base + f64::from(h) * step)
        .filter(|&top| top > 0.0)
        .map(|top| b * b * top)
        .sum();
    let summed = volume(&obj.vertices, &obj.triangles);
    assert!(
        (summed - solid).abs() > 1e-5 * solid,
        "the f32 sum {summed} is within 1e-5 of {solid}: not the hole's case"
    );
    let faults = mesh_faults_against(&obj, &terrain);
    assert!(faults.is_empty(), "{faults:?}");
}
