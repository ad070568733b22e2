//! The physics smoke test of a checked world (feature `physics`, rapier);
//! without the feature, asking for it is a fault that says so.

use rse_core::Terrain;
use rse_world::Manifest;

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

/// The stepping time of the smoke test, microseconds a step, measured by
/// bench/budget.py (20 bodies, 5 s at 1 kHz, 60×60 cells of random steps):
/// the flat-plane reference ~40 µs, and per collider ~70 µs plus ~5 µs for
/// each block a body's reach (~10 cm) spans — `(0.1 / s)²` for blocks of
/// side `s`, no more than the cells there are: 75 µs at 10 cm, 90 at
/// 5 cm, 220 at 2 cm, 575 at 1 cm.
fn step_micros(models: u64, cells: u64, block_size: f64) -> f64 {
    let spanned = (0.1 / block_size.max(1e-6)).powi(2).min(cells as f64);
    40.0 + models as f64 * (70.0 + 5.0 * spanned)
}

/// What the smoke test of a world of `manifest` with `cells` cells of side
/// `block_size` costs, as `(cell visits, bytes)`: 5000 steps of
/// [`step_micros`], and ~8 µs and ~300 bytes a cell for each collider's
/// model. Priced in `check`'s estimate, so the test is held to the budget
/// like the rebuild; it only ever runs on meshes that match their rebuild.
pub(crate) fn cost(manifest: &Manifest, cells: u64, block_size: f64) -> (u64, u64) {
    if !PHYSICS {
        return (0, 0);
    }
    let models = colliders(manifest).len() as u64;
    if models == 0 {
        return (0, 0);
    }
    let visit_ns = rse_world::VISIT_NANOS;
    let steps = 5_000.0;
    let seconds = steps * step_micros(models, cells, block_size) * 1e-6;
    let visits = (seconds * 1e9 / visit_ns) as u64;
    let per_cell_visits = (8_000.0 / visit_ns) as u64;
    (
        visits.saturating_add(models.saturating_mul(cells).saturating_mul(per_cell_visits)),
        (2u64 << 20).saturating_add(models.saturating_mul(cells).saturating_mul(300)),
    )
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
