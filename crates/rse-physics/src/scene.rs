//! The rapier world of one run: the floor, the terrain model (none for the
//! flat control) and the dropped bodies.

use rapier3d::prelude::*;
use rse_core::Terrain;

use crate::bodies::{Body, Shape};
use crate::model::TerrainModel;

/// The floor the pallets stand on, a slab whose top is `z = 0` reaching
/// well past them: its centre and half size.
pub(crate) fn floor(terrain: &Terrain) -> (Vector, Vector) {
    let grid = terrain.grid();
    let size = [grid.nx, grid.ny].map(|n| f64::from(n) * terrain.block_size());
    let half = (size[0].max(size[1]) + 10.0) as f32;
    (
        Vector::new(size[0] as f32 / 2.0, size[1] as f32 / 2.0, -0.5),
        Vector::new(half, half, 0.5),
    )
}

/// A world with a ground plane at `z = 0`, the terrain (none: the flat
/// control) and the bodies.
pub(crate) fn scene(
    model: Option<&TerrainModel>,
    drops: &[Body],
    dt: f32,
    terrain: &Terrain,
) -> (PhysicsWorld, Vec<(RigidBodyHandle, ColliderHandle)>) {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0, -9.81);
    world.integration_parameters.dt = dt;
    let (centre, half) = floor(terrain);
    world.insert(
        RigidBodyBuilder::fixed().translation(centre),
        ColliderBuilder::cuboid(half.x, half.y, half.z).friction(0.8),
    );
    // The flat control (`None`) and an empty terrain: the floor alone.
    match model.filter(|m| !m.is_empty()) {
        None => {}
        Some(TerrainModel::Mesh {
            vertices,
            triangles,
        }) => {
            let points = vertices
                .iter()
                .map(|&[x, y, z]| Vector::new(x, y, z))
                .collect();
            // Fixing internal edges stops bodies sliding over a flat top from
            // catching on the edges between its triangles.
            let collider = ColliderBuilder::trimesh_with_flags(
                points,
                triangles.clone(),
                TriMeshFlags::FIX_INTERNAL_EDGES,
            )
            .expect("a mesh with triangles")
            .friction(0.8);
            world.insert(RigidBodyBuilder::fixed(), collider);
        }
        Some(TerrainModel::Boxes(boxes)) => {
            let body = world.insert_body(RigidBodyBuilder::fixed());
            for &(c, h) in boxes {
                let collider = ColliderBuilder::cuboid(h[0] as f32, h[1] as f32, h[2] as f32)
                    .translation(Vector::new(c[0] as f32, c[1] as f32, c[2] as f32))
                    .friction(0.8);
                world.insert_collider(collider, Some(body));
            }
        }
    }
    let handles = drops
        .iter()
        .map(|b| {
            let [x, y, z] = b.start.map(|v| v as f32);
            let body = RigidBodyBuilder::dynamic()
                .translation(Vector::new(x, y, z))
                .rotation(Vector::from(b.rotation.map(|v| v as f32)))
                // Robot parts stop: without damping a sphere rolls forever.
                .linear_damping(1.0)
                .angular_damping(4.0)
                // A robot on the terrain never sleeps: neither do the test bodies,
                // so both scenes pay for their contacts every step.
                .can_sleep(false);
            let collider = match b.shape {
                Shape::Box(h) => ColliderBuilder::cuboid(h[0] as f32, h[1] as f32, h[2] as f32),
                Shape::Sphere(r) => ColliderBuilder::ball(r as f32),
                Shape::Capsule {
                    half_height,
                    radius,
                } => ColliderBuilder::capsule_z(half_height as f32, radius as f32),
            }
            .density(500.0)
            .friction(0.8)
            // The bodies probe the terrain, not each other: dropped into a
            // small world they would start inside one another and the
            // solver would throw them apart (every fresh world of 5×5
            // blocks of 10 cm failed so).
            .collision_groups(InteractionGroups::new(
                Group::GROUP_2,
                Group::GROUP_1,
                InteractionTestMode::And,
            ));
            world.insert(body, collider)
        })
        .collect();
    (world, handles)
}
