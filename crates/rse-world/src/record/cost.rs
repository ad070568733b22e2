//! What rebuilding a world costs `check` — peak memory and work — modelled
//! on measured figures (`bench/budget.py` prints each estimate beside what
//! it measures, over a table of ordinary and hostile worlds). Estimated in
//! two steps, each before the work it prices: from the recipe alone
//! ([`before_generating`]: generation, obstacles, height-field samples,
//! flat patches), then from the generated terrain ([`after_generating`]:
//! the files, whose size follows the mesh's triangles and the box count,
//! not the grid). `rebuild::Recipe` calls them with what it parsed once.

use rse_core::{AtlasOptions, Scheme, Terrain, Walls};

use crate::memory::{BYTES_PER_SAMPLE, hfield_samples};
use crate::record::options::{Collider, WorldOptions};
use crate::render::templates::{Templates, render_bytes, render_visits};

/// What rebuilding and checking a world costs, estimated before it is done.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RebuildCost {
    /// Cells of the world's grid (an atlas's whole map).
    pub cells: u64,
    /// Memory at the peak, bytes.
    pub bytes: u64,
    /// Work, in cell visits ([`VISIT_NANOS`] each on one core).
    pub visits: u64,
    /// The mesh's triangles and the box set's boxes, once the terrain is
    /// generated and they are counted (`None` before): what a physics
    /// engine is given, and so what its test costs.
    pub models: Option<ModelCounts>,
}

/// The sizes of a world's collision models, counted after generating.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ModelCounts {
    /// Triangles of the single mesh (0 when no file holds it).
    pub triangles: u64,
    /// Boxes of the box set (0 when no target collides with it and no
    /// user's template counts them).
    pub boxes: u64,
}

impl RebuildCost {
    /// The work as seconds on one core of the development machine.
    pub fn seconds(&self) -> f64 {
        self.visits as f64 * VISIT_NANOS * 1e-9
    }
}

/// One cell visit of the generator, nanoseconds on one core of the
/// development machine: the unit every other cost is counted in (rse-core
/// prices generation in it).
pub use rse_core::VISIT_NANOS;

/// The process and its fixed buffers, bytes.
const BASE_BYTES: u64 = 8 << 20;
/// Per cell: the heights, the height-map CSV and the preview (each built,
/// then read back), the flat-patch and spawn fields.
const BYTES_PER_CELL: u64 = 48;
/// Per cell: the height-map CSV and preview written and compared, the
/// walls counted (`rse-gen heightmap` and `preview` take 20–30 ns a cell
/// of a 1000×1000 field, a flat world's whole check 70 ns; once 100 visits,
/// a flat world was priced 4.8 times what it took).
const VISITS_PER_CELL: u64 = 12;

/// A file's bytes are held three times at the peak: rebuilt, read from
/// the folder, and parsed (meshes, XML).
const FILE_COPIES: u64 = 3;
/// Bytes of a mesh file (OBJ, USD) per triangle: measured 32–41.
const MESH_FILE_BYTES_PER_TRIANGLE: u64 = 40;
/// Bytes of a box list (MJCF 118, URDF 310, SDF and USD between) per box.
const BOX_FILE_BYTES_PER_BOX: u64 = 220;
/// The mesh in memory per triangle: ours, and the OBJ reader's.
const MESH_BYTES_PER_TRIANGLE: u64 = 96;
/// Checking one mesh (read, closed, oriented, volume, no T-junction) per
/// triangle, for walls one step high: measured 3.3 µs a triangle on a
/// 300×300 field of random steps of height 1.
const MESH_CHECK_VISITS_PER_TRIANGLE: u64 = 600;
/// ... and per triangle for each doubling of the mean wall (in steps): the
/// T-junction search walks more of its buckets along tall walls (measured
/// 3.7, 4.4, 5.2, 6.6 and 9.0 µs a triangle for heights 4, 16, 64, 256
/// and 1000, a mean wall of a third of that).
const MESH_CHECK_VISITS_PER_WALL_DOUBLING: f64 = 120.0;
/// The most triangles a cell's share of a mesh has (measured 8.7 on a
/// field of random steps of height 1000, 6 of height 4).
const MAX_TRIANGLES_PER_CELL: u64 = 12;
/// Building the mesh, per triangle (measured 0.8 µs).
const MESH_BUILD_VISITS_PER_TRIANGLE: u64 = 160;
/// Building and comparing one more mesh file, per triangle.
const MESH_FILE_VISITS_PER_TRIANGLE: u64 = 24;
/// Building, comparing and checking the references of one box list, per box.
const BOX_FILE_VISITS_PER_BOX: u64 = 800;

/// Sampling, encoding and comparing one height-field sample.
const VISITS_PER_SAMPLE: u64 = 4;
/// Per sample of a height field under a ramp, written again over its
/// plane: 200 ramps over a 300×300 field at k = 4 (288 million samples)
/// took 1.3 s of its check's 1.54.
const VISITS_PER_RAMP_SAMPLE: u64 = 1;

/// An obstacle of the recipe: parsed from `rse.json` and drawn.
const BYTES_PER_OBSTACLE: u64 = 640;
/// Parsing, drawing and recording one obstacle (its stamp is counted
/// apart, by [`Scheme::generation_visits`]): bench/budget.py's 200,000
/// obstacles on 10×10 take ~1.2 µs each, stamp included (at 600 visits,
/// 3 µs, that row was priced 2.9 times its measure).
const VISITS_PER_OBSTACLE: u64 = 200;

/// A flat patch of an atlas, as found and as written in `atlas.json`.
const BYTES_PER_PATCH: u64 = 150;
/// Finding (counted apart by [`AtlasOptions::visits`]), writing and
/// comparing one flat patch: an atlas of 10x10 NIST hills listing 115,600
/// took 0.44 s in all (at 800 visits a patch it was priced 2.4 times that).
const VISITS_PER_PATCH: u64 = 300;

/// What the recipe alone says of a world: its grid, its generation, and
/// what its options ask beside the files.
#[derive(Debug)]
pub(crate) struct RecipeSize {
    cells: u64,
    /// What building the block model holds (every world builds it, for
    /// its box lists or to know the terrain is empty).
    boxes_bytes: u64,
    generation: u64,
    obstacles: u64,
    patches: u64,
    /// Cells under ramps, whose height-field samples are written again
    /// over the plane ([`Scheme::ramp_cells`]).
    ramp_cells: u64,
}

impl RecipeSize {
    /// A world of `scheme`.
    pub(crate) fn of_scheme(scheme: &Scheme) -> Self {
        let grid = scheme.grid();
        RecipeSize {
            cells: grid.cells() as u64,
            boxes_bytes: rse_core::mesh::boxes_bytes(grid.nx, grid.ny),
            generation: scheme.generation_visits(),
            obstacles: scheme.obstacles().len() as u64,
            patches: 0,
            ramp_cells: scheme.ramp_cells(),
        }
    }

    /// An atlas of `schemes` with `options`.
    pub(crate) fn of_atlas(schemes: &[Scheme], options: &AtlasOptions) -> Self {
        let Some(first) = schemes.first() else {
            return RecipeSize {
                cells: 0,
                boxes_bytes: 0,
                generation: 0,
                obstacles: 0,
                patches: 0,
                ramp_cells: 0,
            };
        };
        let [nx, ny] = options.map_cells([first.grid().nx, first.grid().ny]);
        let tiles = u64::from(options.rows).saturating_mul(u64::from(options.cols));
        let obstacles = schemes.iter().map(|s| s.obstacles().len() as u64).max();
        RecipeSize {
            cells: nx.saturating_mul(ny),
            boxes_bytes: u32::try_from(nx)
                .ok()
                .zip(u32::try_from(ny).ok())
                .map_or(u64::MAX, |(nx, ny)| rse_core::mesh::boxes_bytes(nx, ny)),
            generation: options.visits(schemes),
            obstacles: obstacles.unwrap_or(0).saturating_mul(tiles),
            patches: patches(options, first).saturating_mul(tiles),
            ramp_cells: schemes
                .iter()
                .map(Scheme::ramp_cells)
                .max()
                .unwrap_or(0)
                .saturating_mul(tiles),
        }
    }
}

/// What rebuilding a world of `size` with `options` would cost, from its
/// recipe alone (nothing is generated): the generation, the obstacles, the
/// height field's samples (cells·k²), the flat patches, and the mesh and
/// boxes at their most per cell, which [`after_generating`] builds to
/// count, and a user's `templates` at their fuel for a box a cell. The
/// files come after, from that count.
pub(crate) fn before_generating(
    size: &RecipeSize,
    options: &WorldOptions,
    templates: &Templates,
) -> RebuildCost {
    let recipe = recipe_part(size, options, BlockModel::at_most(size));
    // Counting the mesh and boxes (`after_generating`) builds them: priced
    // here at their most per cell, so that step is bounded too (the boxes
    // are in the recipe's part: every world builds them).
    let (mut bytes, mut visits) = (0u64, 0u64);
    if options.mesh_files().any() {
        let triangles = size.cells.saturating_mul(MAX_TRIANGLES_PER_CELL);
        bytes = triangles.saturating_mul(MESH_BYTES_PER_TRIANGLE);
        visits = triangles.saturating_mul(MESH_BUILD_VISITS_PER_TRIANGLE);
    }
    // A user's files, their templates at their fuel for as many boxes as
    // cells.
    let users = UsersFiles::of(templates, options, size.cells);
    RebuildCost {
        cells: size.cells,
        bytes: recipe
            .bytes
            .saturating_add(bytes)
            .saturating_add(users.bytes),
        visits: recipe
            .visits
            .saturating_add(visits)
            .saturating_add(users.visits),
        models: None,
    }
}

/// What a user's files cost a world: their templates at their fuel (in
/// time and in the bytes it lets them create), and the files copied as
/// they are, held as every file is ([`FILE_COPIES`]) and compared.
#[derive(Debug, Clone, Copy)]
struct UsersFiles {
    bytes: u64,
    visits: u64,
}

/// Cloning, reading back and comparing a byte of a file copied from a
/// user's folder: a 200 MB file took 0.97 s of its world's check.
const VISITS_PER_COPIED_BYTE: u64 = 1;

impl UsersFiles {
    /// For a world of `boxes` boxes.
    fn of(templates: &Templates, options: &WorldOptions, boxes: u64) -> Self {
        let rendered = templates.user_templates(&options.targets);
        let copied = templates.copied_bytes(&options.targets);
        UsersFiles {
            bytes: render_bytes(rendered, boxes).saturating_add(copied.saturating_mul(FILE_COPIES)),
            visits: render_visits(rendered, boxes)
                .saturating_add(copied.saturating_mul(VISITS_PER_COPIED_BYTE)),
        }
    }
}

/// What building the block model holds and takes.
#[derive(Debug, Clone, Copy)]
struct BlockModel {
    bytes: u64,
    visits: u64,
}

impl BlockModel {
    /// At its most for the grid: a box a cell, a random field's work a
    /// cell (before generating).
    fn at_most(size: &RecipeSize) -> Self {
        BlockModel {
            bytes: size.boxes_bytes,
            visits: size
                .cells
                .saturating_mul(rse_core::mesh::BOXES_VISITS_PER_CELL),
        }
    }

    /// For the generated heights: its indexes a cell, its work and boxes
    /// by the walls (a flat field's cover is next to free).
    fn of(terrain: &Terrain, walls: Walls) -> Self {
        let grid = terrain.grid();
        let cells = grid.cells() as u64;
        BlockModel {
            bytes: rse_core::mesh::counted_boxes_bytes(grid.nx, grid.ny, walls),
            visits: cells
                .saturating_mul(rse_core::mesh::BOXES_VISITS_PER_INDEXED_CELL)
                .saturating_add(
                    walls
                        .count
                        .saturating_mul(rse_core::mesh::BOXES_VISITS_PER_WALL),
                ),
        }
    }
}

/// What each target collides with.
fn colliders(options: &WorldOptions) -> Vec<Collider> {
    options
        .targets
        .iter()
        .map(|t| Collider::of(t, options.mesh, options.mujoco_collider))
        .collect()
}

/// The recipe's part of the cost, nothing of the files: with the block
/// model, which every world builds (a cone's cover was once unpriced and
/// took 155 s on 1000×1000).
fn recipe_part(size: &RecipeSize, options: &WorldOptions, blocks: BlockModel) -> RebuildCost {
    let samples = hfield_samples(options, size.cells);
    // Each ramp's samples are written again, over its plane.
    let ramp_samples = hfield_samples(options, size.ramp_cells);
    RebuildCost {
        cells: size.cells,
        bytes: BASE_BYTES
            .saturating_add(blocks.bytes)
            .saturating_add(size.cells.saturating_mul(BYTES_PER_CELL))
            .saturating_add(samples.saturating_mul(BYTES_PER_SAMPLE))
            .saturating_add(size.obstacles.saturating_mul(BYTES_PER_OBSTACLE))
            .saturating_add(size.patches.saturating_mul(BYTES_PER_PATCH)),
        visits: size
            .generation
            .saturating_add(size.cells.saturating_mul(VISITS_PER_CELL))
            .saturating_add(blocks.visits)
            .saturating_add(samples.saturating_mul(VISITS_PER_SAMPLE))
            .saturating_add(ramp_samples.saturating_mul(VISITS_PER_RAMP_SAMPLE))
            .saturating_add(size.obstacles.saturating_mul(VISITS_PER_OBSTACLE))
            .saturating_add(size.patches.saturating_mul(VISITS_PER_PATCH)),
        models: None,
    }
}

/// [`before_generating`] and the files, once the terrain is generated
/// (what `before_generating` priced, held to a budget first): its mesh and
/// boxes counted, since a world's files grow with them (a field of tall
/// random steps has twice the triangles a cell of a low one has, a flat
/// atlas next to none), and a user's `templates` at their fuel for those
/// boxes.
pub(crate) fn after_generating(
    size: &RecipeSize,
    options: &WorldOptions,
    terrain: &Terrain,
    templates: &Templates,
) -> RebuildCost {
    let walls = terrain.heightmap().walls();
    let blocks = BlockModel::of(terrain, walls);
    let recipe_cost = recipe_part(size, options, blocks);
    let colliders = colliders(options);
    // The mesh is built, written and checked wherever a file holds it: a
    // target colliding it, and MuJoCo and Gazebo classic drawing it over
    // their box sets (once unpriced: 23x under on a 300x300 field).
    let mesh_files = options.mesh_files();
    let triangles = if mesh_files.any() {
        terrain.mesh().triangles().len() as u64
    } else {
        0
    };
    // The boxes are counted once, for the box lists and a user's
    // templates' fuel alike.
    let user_templates = templates.user_templates(&options.targets);
    let has_box_lists = colliders.contains(&Collider::Boxes);
    let counted = if has_box_lists || user_templates > 0 {
        terrain.boxes().len() as u64
    } else {
        0
    };
    let boxes = if has_box_lists { counted } else { 0 };
    // Each mesh file (every OBJ copy, the USD), and each box list.
    let meshes = mesh_files.objs() + u64::from(mesh_files.usd);
    let box_lists = colliders.iter().filter(|c| **c == Collider::Boxes).count() as u64;
    let file_bytes = triangles
        .saturating_mul(MESH_FILE_BYTES_PER_TRIANGLE)
        .saturating_mul(meshes)
        .saturating_add(
            boxes
                .saturating_mul(BOX_FILE_BYTES_PER_BOX)
                .saturating_mul(box_lists),
        );
    let visits = triangles
        .saturating_mul(MESH_FILE_VISITS_PER_TRIANGLE)
        .saturating_mul(meshes)
        .saturating_add(
            boxes
                .saturating_mul(BOX_FILE_VISITS_PER_BOX)
                .saturating_mul(box_lists),
        );
    // Copies of one mesh are checked once.
    let per_triangle = MESH_CHECK_VISITS_PER_TRIANGLE as f64
        + MESH_CHECK_VISITS_PER_WALL_DOUBLING * (1.0 + walls.mean()).log2();
    let mesh_check = (triangles as f64 * per_triangle) as u64;
    // A user's files, their templates at their fuel for this world's
    // boxes, and the count of them (a cover more than the rebuild's own,
    // priced alike).
    let users = UsersFiles::of(templates, options, counted);
    let count = if user_templates > 0 { blocks.visits } else { 0 };
    RebuildCost {
        cells: recipe_cost.cells,
        bytes: recipe_cost
            .bytes
            .saturating_add(file_bytes.saturating_mul(FILE_COPIES))
            .saturating_add(triangles.saturating_mul(MESH_BYTES_PER_TRIANGLE))
            .saturating_add(users.bytes),
        visits: recipe_cost
            .visits
            .saturating_add(visits)
            .saturating_add(mesh_check)
            .saturating_add(count)
            .saturating_add(users.visits),
        models: Some(ModelCounts {
            triangles,
            boxes: counted,
        }),
    }
}

/// Flat patches one atlas tile lists at most: its count, and no more than
/// one a cell.
fn patches(options: &AtlasOptions, scheme: &Scheme) -> u64 {
    u64::from(options.patches.count).min(scheme.grid().cells() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::memory::batch_world_bytes;
    use crate::record::atlas_record::NamedScheme;
    use crate::record::manifest::Manifest;
    use crate::record::options::Targets;
    use crate::record::options::{MujocoCollider, WorldOptions};
    use crate::record::rebuild::Recipe;
    use crate::render::templates::Templates;
    use crate::render::world::build_world;

    /// The cost from the recipe alone.
    fn before(manifest: &Manifest) -> RebuildCost {
        Recipe::of(manifest).unwrap().cost(&Templates::builtin())
    }

    /// The cost once the terrain is generated.
    fn after(manifest: &Manifest) -> RebuildCost {
        Recipe::of(manifest)
            .unwrap()
            .generate()
            .unwrap()
            .cost(&Templates::builtin())
    }

    /// The manifest of world 0 of `csv` with every target.
    fn manifest_of(csv: &str, options: &WorldOptions) -> Manifest {
        let scheme = Scheme::from_csv(csv, None).unwrap();
        let world = build_world(
            &scheme,
            0,
            0,
            "world_0000".to_owned(),
            options,
            &Templates::builtin(),
        )
        .unwrap();
        Manifest::from_json(std::str::from_utf8(&world.files["rse.json"]).unwrap()).unwrap()
    }

    fn every_target() -> WorldOptions {
        WorldOptions {
            targets: Targets::all(),
            ..WorldOptions::default()
        }
    }

    /// A 10×10 world whose manifest asks a height field of oversample
    /// 1158 was estimated at 200 KiB and peaked at 1 GB: its samples
    /// (cells·k²) are priced from the recipe, before anything is built.
    #[test]
    fn height_field_samples_are_priced_from_the_recipe() {
        let mut manifest = manifest_of("# size: 10x10\ntype,height\nrandom,3\n", &every_target());
        let plain = before(&manifest);
        manifest.options.mujoco_collider = MujocoCollider::Hfield { oversample: 1158 };
        let forged = before(&manifest);
        assert!(plain.bytes < 16 << 20, "{plain:?}");
        assert!(forged.bytes > 1_000_000_000, "{forged:?}");
        assert!(forged.seconds() > 1.0, "{forged:?}");
    }

    /// A height field writes each ramp's samples again over its plane: 200
    /// ramps over a 300×300 field at k = 4 took 1.5 s against an estimate
    /// of 0.2 s before they were priced.
    #[test]
    fn a_height_fields_ramp_samples_are_priced() {
        let rows = "ramp,20,,0,0,99,99\n".repeat(200);
        let ramps = format!("# size: 100x100\ntype,height,angle,x1,y1,x2,y2\n{rows}");
        let cost = |csv: &str| {
            let mut manifest = manifest_of(csv, &every_target());
            manifest.options.mujoco_collider = MujocoCollider::Hfield { oversample: 4 };
            before(&manifest).visits
        };
        let flat = cost("# size: 100x100\ntype,height\nrandom,0\n");
        let samples = 200 * 100 * 100 * 16;
        assert!(
            cost(&ramps) >= flat + samples * VISITS_PER_RAMP_SAMPLE,
            "{flat}"
        );
    }

    /// 900k obstacles on a 10×10 grid used 532 MB against an estimate of
    /// none: each obstacle is priced.
    #[test]
    fn obstacles_are_priced() {
        let csv = format!(
            "# size: 10x10\ntype,height\n{}",
            "random,1\n".repeat(20_000)
        );
        let cost = before(&manifest_of(&csv, &every_target()));
        assert!(cost.bytes >= 20_000 * BYTES_PER_OBSTACLE, "{cost:?}");
        assert!(cost.visits >= 20_000 * VISITS_PER_OBSTACLE, "{cost:?}");
    }

    /// A field of tall random steps costs more than a low one of the same
    /// grid (a 300×300 `random,1000` world was estimated at half its
    /// memory and a hundredth of its time): the files follow the mesh, and
    /// the mesh check the walls.
    #[test]
    fn tall_walls_cost_more_than_low_ones_of_the_same_grid() {
        let cost = |h: u32| {
            let csv = format!("# size: 40x40\ntype,height\nrandom,{h}\n");
            after(&manifest_of(&csv, &every_target()))
        };
        let (low, tall, flat) = (cost(1), cost(1000), cost(0));
        assert!(
            tall.visits as f64 > 1.5 * low.visits as f64,
            "{low:?} {tall:?}"
        );
        assert!(
            tall.bytes > low.bytes && low.bytes > flat.bytes,
            "{flat:?} {low:?}"
        );
        // The recipe alone cannot tell them apart; the terrain can.
        assert_eq!(
            before(&manifest_of(
                "# size: 40x40\ntype,height\nrandom,1\n",
                &every_target()
            ))
            .bytes,
            before(&manifest_of(
                "# size: 40x40\ntype,height\nrandom,1000\n",
                &every_target()
            ))
            .bytes
        );
    }

    /// An atlas with 10⁶ flat patches took 9.7 s against an estimate of a
    /// second: its patches are priced, up to one a cell of each tile.
    #[test]
    fn an_atlas_prices_its_flat_patches() {
        let scheme = Scheme::from_csv("# size: 30x30\ntype,height\n", None).unwrap();
        let schemes = [NamedScheme {
            name: "flat".to_owned(),
            scheme,
        }];
        let cost = |count: u32| {
            let options = AtlasOptions {
                rows: 2,
                cols: 2,
                patches: rse_core::PatchOptions {
                    count,
                    ..AtlasOptions::default().patches
                },
                ..AtlasOptions::default()
            };
            let (world, _) = crate::atlas::build_atlas_world(
                &schemes,
                &options,
                "atlas".to_owned(),
                &every_target(),
                &Templates::builtin(),
            )
            .unwrap();
            after(
                &Manifest::from_json(std::str::from_utf8(&world.files["rse.json"]).unwrap())
                    .unwrap(),
            )
        };
        let (none, all) = (cost(0), cost(1_000_000));
        assert!(
            all.bytes >= none.bytes + 4 * 900 * BYTES_PER_PATCH,
            "{none:?} {all:?}"
        );
        assert!(all.visits >= none.visits + 4 * 900 * VISITS_PER_PATCH);
    }

    /// Every world builds its block model (its box lists, or only to know
    /// whether the terrain is empty), yet an OBJ-only world priced none of
    /// it: a cone of radius 500 took 155 s against an estimate of 7.7 s.
    /// The cover's indexes and boxes are priced for every target: from the
    /// grid at their most, then from the walls of the generated terrain.
    #[test]
    fn the_block_model_is_priced_for_every_target() {
        let csv = "# size: 60x40\ntype,height,angle,x1,y1\npeak,20,45,30,20\n";
        let scheme = Scheme::from_csv(csv, None).unwrap();
        let walls = rse_core::generate(&scheme, 0, 0).heightmap().walls();
        assert!(walls.count > 100, "{walls:?}");
        for target in ["obj", "urdf", "mujoco", "usd"] {
            let options = WorldOptions {
                targets: Targets::parse(target).unwrap(),
                ..WorldOptions::default()
            };
            let manifest = manifest_of(csv, &options);
            let before = before(&manifest);
            assert!(
                before.visits >= 2400 * (VISITS_PER_CELL + rse_core::mesh::BOXES_VISITS_PER_CELL),
                "{target}: {before:?}"
            );
            assert!(
                before.bytes >= BASE_BYTES + rse_core::mesh::boxes_bytes(60, 40),
                "{target}: {before:?}"
            );
            let after = after(&manifest);
            assert!(
                after.visits >= walls.count * rse_core::mesh::BOXES_VISITS_PER_WALL,
                "{target}: {after:?}"
            );
            assert!(
                after.bytes >= BASE_BYTES + rse_core::mesh::counted_boxes_bytes(60, 40, walls),
                "{target}: {after:?}"
            );
        }
    }

    /// A flat 1000×1000 world was priced 0.91 s and 127 MiB, and took
    /// 0.19 s and 52 MiB: its block model was priced as a random field's,
    /// a box and a random field's work a cell. Generated, a world is priced
    /// by its walls: the flat one at a fraction of a field of steps.
    #[test]
    fn a_flat_world_is_priced_by_its_walls_not_its_cells() {
        let cost = |csv: &str| after(&manifest_of(csv, &WorldOptions::default()));
        let flat = cost("# size: 300x300\ntype,height\n");
        let steps = cost("# size: 300x300\ntype,height\nrandom,1\n");
        assert!(flat.visits * 10 < steps.visits, "{flat:?} {steps:?}");
        assert!(flat.bytes * 2 < steps.bytes, "{flat:?} {steps:?}");
        let cells = 90_000;
        assert!(flat.visits < cells * 40, "{flat:?}");
    }

    /// MuJoCo and Gazebo classic collide boxes but draw the mesh, which
    /// `check` rebuilds and mesh-checks: once unpriced (a 300×300 field of
    /// height 1000: 0.40 s estimated, 9.2 s measured). Their cost holds the
    /// mesh's triangles as a mesh target's does, and a target that writes
    /// no mesh (URDF in block mode) has none of it.
    #[test]
    fn the_drawn_mesh_is_priced() {
        let csv = "# size: 40x40\ntype,height\nrandom,20\n";
        let cost = |target: &str| {
            let options = WorldOptions {
                targets: Targets::parse(target).unwrap(),
                ..WorldOptions::default()
            };
            after(&manifest_of(csv, &options))
        };
        let scheme = Scheme::from_csv(csv, None).unwrap();
        let triangles = rse_core::generate(&scheme, 0, 0).mesh().triangles().len() as u64;
        let mesh_part = triangles * MESH_CHECK_VISITS_PER_TRIANGLE;
        let urdf = cost("urdf");
        for drawn in ["mujoco", "gazebo-classic"] {
            let with_mesh = cost(drawn);
            assert!(
                with_mesh.visits >= urdf.visits + mesh_part,
                "{drawn}: {with_mesh:?} against urdf {urdf:?} ({triangles} triangles)"
            );
            assert!(
                with_mesh.bytes >= urdf.bytes + triangles * MESH_BYTES_PER_TRIANGLE,
                "{drawn}: {with_mesh:?}"
            );
        }
    }

    /// `batch --oversample` had the same blind spot: a batch's memory
    /// check prices the samples of its height fields too.
    #[test]
    fn a_batch_prices_height_field_samples() {
        let mut options = every_target();
        assert!(batch_world_bytes(100, &options) < 1 << 20);
        options.mujoco_collider = MujocoCollider::Hfield { oversample: 1158 };
        assert!(batch_world_bytes(100, &options) > 1_000_000_000);
    }
}
