//! The single mesh against every invariant of docs/meshes.md, on samples and on
//! property-test heightmaps (checkerboards, single cells, all-zero, base > 0).

use proptest::prelude::*;
use rse_core::mesh::{MeshUnits, TriMesh, build_mesh, invariants};
use rse_core::{Heightmap, Ramp, Scheme, generate};

use crate::util::{repo, sample_paths};

/// Asserts closedness, orientation, area, no T-junction (exactly, on the
/// lattice), exact volume and box: the cells' solid and a wedge for each
/// of `ramps` (of any rise: a ramp of none adds nothing).
fn assert_exact(map: &Heightmap, ramps: &[Ramp], units: MeshUnits, mesh: &TriMesh) {
    let faults = mesh.faults();
    assert!(
        faults.is_empty(),
        "{} faults, first {:?}",
        faults.len(),
        &faults[..faults.len().min(5)]
    );
    let cell_area = units.block_size * units.block_size;
    let tops = map
        .cells()
        .iter()
        .map(|&h| units.base + f64::from(h) * units.step_height);
    let wedges = ramps.iter().filter(|r| r.rise > 0);
    let expected: f64 = tops.clone().map(|z| z * cell_area).sum::<f64>()
        + wedges
            .clone()
            .map(|r| {
                let [x0, y0, x1, y1] = r.cells;
                let cells = f64::from((x1 - x0 + 1) * (y1 - y0 + 1));
                cells * cell_area * (units.base + f64::from(r.rise) * units.step_height / 2.0)
            })
            .sum::<f64>();
    let volume = invariants::volume(mesh.vertices(), mesh.triangles());
    assert!(
        (volume - expected).abs() <= 1e-5 * expected.max(1e-9),
        "volume {volume}, expected {expected}"
    );
    // The exact box: around the cells with solid, from z = 0 to the highest top.
    let solid: Vec<(u32, u32, f64)> = (0..map.ny())
        .flat_map(|y| (0..map.nx()).map(move |x| (x, y)))
        .map(|(x, y)| {
            (
                x,
                y,
                units.base + f64::from(map.get(x, y)) * units.step_height,
            )
        })
        .filter(|&(_, _, z)| z > 0.0)
        .chain(wedges.flat_map(|r| {
            let [x0, y0, x1, y1] = r.cells;
            let top = units.base + f64::from(r.rise) * units.step_height;
            [(x0, y0, top), (x1, y1, top)]
        }))
        .collect();
    let found = invariants::bounding_box(mesh.vertices());
    if solid.is_empty() {
        assert_eq!(found, None, "an empty solid has an empty mesh");
        return;
    }
    let s = units.block_size;
    let lo = [
        solid.iter().map(|c| c.0).min().unwrap(),
        solid.iter().map(|c| c.1).min().unwrap(),
    ];
    let hi = [
        solid.iter().map(|c| c.0).max().unwrap() + 1,
        solid.iter().map(|c| c.1).max().unwrap() + 1,
    ];
    let top = solid.iter().map(|c| c.2).fold(0.0, f64::max);
    let expected = (
        [f64::from(lo[0]) * s, f64::from(lo[1]) * s, 0.0],
        [f64::from(hi[0]) * s, f64::from(hi[1]) * s, top],
    );
    let (min, max) = found.expect("a solid has a mesh");
    for k in 0..3 {
        assert!(
            (min[k] - expected.0[k]).abs() < 1e-6,
            "box {min:?}..{max:?}, expected {expected:?}"
        );
        assert!(
            (max[k] - expected.1[k]).abs() < 1e-6,
            "box {min:?}..{max:?}, expected {expected:?}"
        );
    }
}

const UNITS: MeshUnits = MeshUnits {
    block_size: 0.1,
    step_height: 0.1,
    base: 0.0,
};

fn map(nx: u32, ny: u32, cells: Vec<u16>) -> Heightmap {
    Heightmap::from_cells(nx, ny, cells).unwrap()
}

#[test]
fn single_cell() {
    let m = map(1, 1, vec![3]);
    let mesh = build_mesh(&m, UNITS);
    assert_exact(&m, &[], UNITS, &mesh);
    assert_eq!(mesh.triangles().len(), 12);
    assert_eq!(mesh.vertices().len(), 8);
}

#[test]
fn all_zero_is_empty_and_base_makes_a_slab() {
    let m = map(4, 3, vec![0; 12]);
    assert!(build_mesh(&m, UNITS).is_empty());
    let slab = MeshUnits {
        base: 0.05,
        ..UNITS
    };
    let mesh = build_mesh(&m, slab);
    assert_exact(&m, &[], slab, &mesh);
    assert_eq!(mesh.triangles().len(), 12);
}

#[test]
fn checkerboard_has_saddles_everywhere() {
    let cells = (0..64)
        .map(|i| u16::from((i % 8 + i / 8) % 2 == 0) * 2)
        .collect();
    let m = map(8, 8, cells);
    assert_exact(&m, &[], UNITS, &build_mesh(&m, UNITS));
    let slab = MeshUnits {
        base: 0.02,
        ..UNITS
    };
    assert_exact(&m, &[], slab, &build_mesh(&m, slab));
}

#[test]
fn saddle_with_different_diagonal_heights() {
    let m = map(2, 2, vec![1, 3, 4, 0]);
    assert_exact(&m, &[], UNITS, &build_mesh(&m, UNITS));
    let m = map(3, 3, vec![2, 0, 5, 0, 3, 0, 1, 0, 4]);
    assert_exact(&m, &[], UNITS, &build_mesh(&m, UNITS));
}

#[test]
fn flat_1000_by_1000_is_12_triangles() {
    let m = map(1000, 1000, vec![2; 1_000_000]);
    let mesh = build_mesh(&m, UNITS);
    assert_eq!(mesh.triangles().len(), 12);
    assert_exact(&m, &[], UNITS, &mesh);
}

#[test]
fn a_large_mesh_is_the_same_on_one_thread_and_on_several() {
    // Large enough (about 90,000 faces) to be triangulated in parallel.
    let scheme = Scheme::from_csv("# size: 220x220\ntype,height\nrandom,4\n", None).unwrap();
    let terrain = generate(&scheme, 7, 0);
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| terrain.mesh())
    };
    let one = on(1);
    assert_eq!(one, on(3));
    assert_exact(
        terrain.heightmap(),
        terrain.ramps(),
        terrain.mesh_units(),
        &one,
    );
}

/// The mesh and the box set of three worlds of every sample are exact.
#[test]
fn every_sample_meshes_and_boxes_exactly() {
    for path in sample_paths() {
        let scheme = Scheme::load(&path).unwrap();
        for index in 0..3 {
            let terrain = generate(&scheme, 0, index);
            let units = terrain.mesh_units();
            assert_exact(terrain.heightmap(), terrain.ramps(), units, &terrain.mesh());
            assert_boxes_fill(terrain.heightmap(), units);
        }
    }
}

fn heightmaps() -> impl Strategy<Value = (Heightmap, MeshUnits)> {
    (
        1u32..=9,
        1u32..=9,
        0u16..=4,
        prop::sample::select(vec![0.0, 0.03]),
        prop::sample::select(vec![0.05, 0.1, 0.2]),
    )
        .prop_flat_map(|(nx, ny, top, base, block_size)| {
            let cells = prop::collection::vec(0..=top, (nx * ny) as usize);
            (
                Just((nx, ny)),
                cells,
                Just(MeshUnits {
                    block_size,
                    step_height: 0.05,
                    base,
                }),
            )
        })
        .prop_map(|((nx, ny), cells, units)| (map(nx, ny, cells), units))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn random_heightmaps_mesh_exactly((m, units) in heightmaps()) {
        let mesh = build_mesh(&m, units);
        assert_exact(&m, &[], units, &mesh);
        prop_assert_eq!(build_mesh(&m, units), mesh, "deterministic");
    }
}

/// The union of the boxes is the solid: every box stands on z = 0 with its
/// corners on the grid, no box rises above a cell under it, and over every
/// cell with solid the highest box reaches that cell's top exactly.
fn assert_boxes_fill(map: &Heightmap, units: MeshUnits) {
    let blocks = rse_core::mesh::boxes(map, units);
    let mut highest = vec![f64::NAN; map.cells().len()];
    let top = |x: u32, y: u32| units.base + f64::from(map.get(x, y)) * units.step_height;
    let s = units.block_size;
    for b in &blocks {
        let [x0, y0, x1, y1] = b.cells;
        assert!(
            x0 < x1 && y0 < y1 && x1 <= map.nx() && y1 <= map.ny(),
            "{b:?}"
        );
        assert!(
            (b.center[2] - b.half_size[2]).abs() < 1e-9,
            "boxes stand on z = 0"
        );
        assert!((b.center[0] - b.half_size[0] - f64::from(x0) * s).abs() < 1e-9);
        assert!((b.center[0] + b.half_size[0] - f64::from(x1) * s).abs() < 1e-9);
        assert!((b.center[1] - b.half_size[1] - f64::from(y0) * s).abs() < 1e-9);
        assert!((b.center[1] + b.half_size[1] - f64::from(y1) * s).abs() < 1e-9);
        let roof = b.center[2] + b.half_size[2];
        for y in y0..y1 {
            for x in x0..x1 {
                assert!(roof <= top(x, y) + 1e-9, "{b:?} rises over cell ({x}, {y})");
                let i = (y * map.nx() + x) as usize;
                highest[i] = highest[i].max(roof);
            }
        }
    }
    for y in 0..map.ny() {
        for x in 0..map.nx() {
            let i = (y * map.nx() + x) as usize;
            if map.get(x, y) > 0 || units.base > 0.0 {
                assert!((highest[i] - top(x, y)).abs() < 1e-9, "cell ({x}, {y})");
            } else {
                assert!(highest[i].is_nan(), "a box over empty cell ({x}, {y})");
            }
        }
    }
}

#[test]
fn boxes_merge_equal_heights_and_fill_the_solid() {
    let flat = map(1000, 1000, vec![2; 1_000_000]);
    assert_eq!(rse_core::mesh::boxes(&flat, UNITS).len(), 1);
    assert!(rse_core::mesh::boxes(&map(3, 3, vec![0; 9]), UNITS).is_empty());
    let cells = (0..64)
        .map(|i| u16::from((i % 8 + i / 8) % 2 == 0) * 2)
        .collect();
    assert_boxes_fill(
        &map(8, 8, cells),
        MeshUnits {
            base: 0.02,
            ..UNITS
        },
    );
    let wall = generate(
        &Scheme::load(repo().join("schemes/wall.csv")).unwrap(),
        0,
        0,
    );
    let blocks = wall.boxes();
    let solid = wall.heightmap().cells().iter().filter(|&&h| h > 0).count();
    assert!(
        blocks.len() < solid,
        "{} boxes for {solid} cells: nothing merged",
        blocks.len()
    );
    assert_boxes_fill(wall.heightmap(), wall.mesh_units());
}

/// A tower in a ring: a partition into rectangles of equal height needs
/// five boxes, the cover two (the ring's box runs under the tower).
#[test]
fn boxes_overlap_under_higher_cells() {
    #[rustfmt::skip]
    let ring = map(3, 3, vec![
        1, 1, 1,
        1, 3, 1,
        1, 1, 1,
    ]);
    let blocks = rse_core::mesh::boxes(&ring, UNITS);
    assert_eq!(
        blocks.iter().map(|b| b.cells).collect::<Vec<_>>(),
        [[0, 0, 3, 3], [1, 1, 2, 2]]
    );
    assert_boxes_fill(&ring, UNITS);
}

proptest! {
    #[test]
    fn boxes_fill_random_heightmaps((m, units) in heightmaps()) {
        assert_boxes_fill(&m, units);
    }
}

/// Tops up to 999.9 block sizes over a 30×30 grid (0.01 m steps under
/// 0.1 m blocks): wall triangles 43 m long and a few centimetres wide,
/// whose true corners lie 23 µm off the far edge: within f32's tolerance
/// (`invariants::faults` takes them for T-junctions), exact on the lattice.
#[test]
fn slender_walls_keep_their_corners_on_the_lattice() {
    let scheme = Scheme::from_csv(
        "# size: 30x30\n# step_height: 0.01\ntype,height\nrandom,9999\n",
        None,
    )
    .unwrap();
    let mut f32_false_alarms = 0;
    for index in 0..10 {
        let terrain = generate(&scheme, 0, index);
        let mesh = terrain.mesh();
        assert_eq!(mesh.faults(), [], "world {index}");
        f32_false_alarms +=
            usize::from(!invariants::faults(mesh.vertices(), mesh.triangles()).is_empty());
    }
    assert!(
        f32_false_alarms > 0,
        "the f32 tolerance no longer confuses them: this test no longer shows why the lattice is needed"
    );
}
