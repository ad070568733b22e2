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
    use std::collections::BTreeSet;

    use rse_physics::{SmokeTest, TerrainModel, smoke_tests};
    use rse_world::Collider;

    let colliders: BTreeSet<Collider> = manifest
        .options
        .targets
        .iter()
        .map(|t| Collider::of(t, manifest.options.mesh, manifest.options.mujoco_collider))
        .collect();
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
