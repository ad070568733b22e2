//! The physics smoke test of a checked world (feature `physics`, rapier);
//! without the feature, asking for it is a fault that says so.

use rse_core::Terrain;
use rse_world::{Manifest, RebuildCost};

use crate::fault::{Fault, FaultKind};
use crate::terrain::ObjMesh;

/// `true` when this build runs the physics smoke test (feature `physics`).
pub const PHYSICS: bool = cfg!(feature = "physics");

/// Why this build cannot drop bodies, when it cannot: the one refusal the
/// command line (`--physics`) and Python (`physics=True`) give before a
/// check starts, in their own words around it, and the fault a check asked
/// for physics anyway reports.
pub fn physics_unavailable() -> Option<&'static str> {
    (!PHYSICS)
        .then_some("this build has no physics smoke test (built without the `physics` feature)")
}

/// The colliders the smoke test drops bodies on for a world of `manifest`:
/// the mesh where a target collides it, the box set where one collides boxes.
fn colliders(manifest: &Manifest) -> std::collections::BTreeSet<rse_world::Collider> {
    manifest
        .options
        .targets
        .iter()
        .map(|t| {
            rse_world::Collider::of(t, manifest.options.mesh, manifest.options.mujoco_collider)
        })
        .filter(|c| matches!(c, rse_world::Collider::Mesh | rse_world::Collider::Boxes))
        .collect()
}

/// The smallest block the smoke test judges, metres. Its bodies are robot
/// parts of 5 to 16 cm: on smaller blocks each touches hundreds of boxes
/// or triangles, rapier's contacts stop conserving energy (every fresh
/// world of 5 mm blocks "gained" energy) and a step costs up to 100 ms.
/// `check --physics` refuses such worlds up front, by name.
pub const MIN_PHYSICS_BLOCK: f64 = 0.01;

/// Why the smoke test cannot judge a world of `block_size` blocks, if it
/// cannot.
pub fn physics_refusal(block_size: f64) -> Option<String> {
    (block_size < MIN_PHYSICS_BLOCK).then(|| {
        format!(
            "its blocks of {block_size} m are smaller than the physics smoke test judges \
             ({MIN_PHYSICS_BLOCK} m and up: robot parts of 5-16 cm on smaller blocks touch \
             hundreds of boxes each); check it without the smoke test"
        )
    })
}

/// Triangles a cell of a random field's mesh has (6.0 on random fields of
/// height 4, 60×60 to 300×300) and boxes a cell of its box set (0.45):
/// the fields the smoke test's prices below were measured on.
const RANDOM_TRIANGLES_PER_CELL: f64 = 6.0;
const RANDOM_BOXES_PER_CELL: f64 = 0.45;

/// The stepping time of the smoke test, microseconds a step, measured by
/// bench/budget.py (20 bodies, 5 s at 1 kHz, 60×60 cells of random steps):
/// the flat-plane reference ~40 µs, and per collider ~70 µs plus ~5 µs for
/// each block a body's reach (~10 cm) spans — `(0.1 / s)²` for blocks of
/// side `s`, no more than the cells there are: 75 µs at 10 cm, 90 at
/// 5 cm, 220 at 2 cm, 575 at 1 cm — on a random field. A model with fewer
/// primitives a cell than a random field's (`density` below 1: a flat
/// 1000×1000 world's mesh is 12 triangles) gives a body fewer to touch.
fn step_micros(densities: &[f64], cells: u64, block_size: f64) -> f64 {
    let spanned = (0.1 / block_size.max(1e-6)).powi(2).min(cells as f64);
    40.0 + densities
        .iter()
        .map(|d| 70.0 + 5.0 * spanned * d)
        .sum::<f64>()
}

/// What the smoke test of a world of `manifest` costs, as `(cell visits,
/// bytes)`, once its terrain is generated and its models counted (`cost`'s
/// [`rse_world::ModelCounts`]; nothing before: the test runs only after
/// the rebuild, which the price without it allowed). Per collider's model:
/// 5000 steps of [`step_micros`], and building it, ~1.3 µs and ~50 bytes a
/// triangle of the mesh, ~18 µs and ~660 bytes a box (8 µs and 300 bytes a
/// cell of a random field), and the judge's box set. Priced in `check`'s
/// estimate, so the test is held to the budget like the rebuild; it only
/// ever runs on meshes that match their rebuild.
pub(crate) fn cost(manifest: &Manifest, cost: &RebuildCost, block_size: f64) -> (u64, u64) {
    let Some(counts) = cost.models else {
        return (0, 0);
    };
    if !PHYSICS {
        return (0, 0);
    }
    let models = colliders(manifest);
    if models.is_empty() {
        return (0, 0);
    }
    let cells = cost.cells.max(1) as f64;
    // The judge measures depth against the box set, whatever the model:
    // counted where a target collides with it, else a random field's share
    // of the mesh's triangles.
    let boxes = if counts.boxes > 0 {
        counts.boxes as f64
    } else {
        counts.triangles as f64 * RANDOM_BOXES_PER_CELL / RANDOM_TRIANGLES_PER_CELL
    };
    let mut densities = Vec::new();
    let (mut build_ns, mut bytes) = (0.0, (2u64 << 20) as f64 + 100.0 * boxes);
    for model in &models {
        let (density, ns, held) = match model {
            rse_world::Collider::Mesh => (
                counts.triangles as f64 / cells / RANDOM_TRIANGLES_PER_CELL,
                1_300.0 * counts.triangles as f64,
                50.0 * counts.triangles as f64,
            ),
            _ => (
                boxes / cells / RANDOM_BOXES_PER_CELL,
                18_000.0 * boxes,
                660.0 * boxes,
            ),
        };
        densities.push(density);
        build_ns += ns;
        bytes += held;
    }
    let steps = 5_000.0;
    let seconds = steps * step_micros(&densities, cost.cells, block_size) * 1e-6;
    let visits = (seconds * 1e9 + build_ns) / rse_world::VISIT_NANOS;
    (visits as u64, bytes as u64)
}

#[cfg(feature = "physics")]
/// The physics smoke test of each exact collider the world's targets load:
/// each distinct mesh file (`meshes` holds one of each set of copies) where
/// a target collides the mesh, the box set where one collides boxes.
/// `MuJoCo`'s height field is approximate by design: not tested here.
/// Returns each collider's report; its errors are also pushed on `faults`.
pub(crate) fn run(
    manifest: &Manifest,
    meshes: Vec<(&str, ObjMesh)>,
    terrain: &Terrain,
    faults: &mut Vec<Fault>,
) -> Vec<rse_physics::PhysicsReport> {
    use rse_physics::{SmokeTest, TerrainModel, smoke_tests};
    use rse_world::Collider;

    let colliders = colliders(manifest);
    let mut runs: Vec<(Option<&str>, TerrainModel)> = Vec::new();
    if colliders.contains(&Collider::Mesh) {
        if meshes.is_empty() {
            // An empty terrain: no mesh file, the floor alone.
            runs.push((None, TerrainModel::mesh_of(terrain)));
        }
        for (path, mesh) in meshes {
            runs.push((
                Some(path),
                TerrainModel::Mesh {
                    vertices: mesh.vertices,
                    triangles: mesh.triangles,
                },
            ));
        }
    }
    if colliders.contains(&Collider::Boxes) {
        runs.push((None, TerrainModel::boxes_of(terrain)));
    }
    let models: Vec<(&TerrainModel, Option<&str>)> =
        runs.iter().map(|(path, model)| (model, *path)).collect();
    let reports = smoke_tests(&models, terrain, SmokeTest::default());
    for physics in &reports {
        let path = physics.collider.file.as_deref();
        let kind = physics.collider.kind;
        faults.extend(physics.errors.iter().map(|error| {
            Fault::new(
                path,
                FaultKind::Physics {
                    error: format!("{kind}: {error}"),
                },
            )
        }));
    }
    reports
}

#[cfg(not(feature = "physics"))]
pub(crate) fn run(_: &Manifest, _: Vec<(&str, ObjMesh)>, _: &Terrain, faults: &mut Vec<Fault>) {
    faults.push(Fault::new(
        None,
        FaultKind::Physics {
            error: physics_unavailable()
                .expect("built without physics")
                .to_owned(),
        },
    ));
}
