//! The verdict on a run: where each body ended against the terrain's solid
//! (sank, inside, still moving, left the RSE, not finite), and the limits
//! every error is judged by.

use rapier3d::prelude::*;
use rse_core::Terrain;

use crate::bodies::Body;
use crate::report::{PhysicsError, Problem};
use crate::scene::floor;

/// A body deeper than this inside the solid is a physics error, metres (the
/// tolerance of `tests/python/test_gz_physics.py` for bodies at rest).
pub const PENETRATION_LIMIT: f64 = 0.01;
/// A body faster than this at any step is a physics error, m/s (as in
/// `bench/robots.py`): nothing dropped a few centimetres gets near it.
pub const SPEED_LIMIT: f64 = 10.0;

/// A body below the surface under its centre by more than this is inside
/// the terrain, metres.
const SINK_TOLERANCE: f64 = 0.01;
/// Mean speed over the last second above which a body has not settled,
/// m/s. Measured as displacement, so jitter in place (a body wedged
/// between two walls) is not mistaken for motion. Not lower: rapier 0.36
/// lets a capsule lying on a flat box creep and spin up by itself, to
/// about 0.2 m/s in 5 s, with or without our terrain.
const SETTLED_SPEED: f64 = 0.3;
/// How far a body's centre may go down in the last second and still count
/// as moving without cause, metres. A body that went further is falling or
/// rolling down a step: settling, late. It happens: that creep can nudge a
/// capsule lying on a one-cell tower over its edge after seconds at rest.
const SETTLING_DESCENT: f64 = 0.05;

/// How a body moved in the last second.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Moved {
    /// Straight-line distance, metres.
    pub(crate) distance: f64,
    /// How far its centre went down, metres (negative: up).
    pub(crate) descent: f64,
}

impl Moved {
    /// Moving without cause over `window` seconds: too fast, and not
    /// going down.
    fn unsettled(self, window: f64) -> bool {
        self.distance / window.max(1e-9) > SETTLED_SPEED && self.descent <= SETTLING_DESCENT
    }
}
/// How far past the RSE's edge a box may slide, metres. A ball or a
/// capsule is not held to it: one that rolls off a tower rolls on across
/// the floor (nothing in rapier slows a roll; a 3 cm ball off a 30 cm
/// tower of a 16 × 6 cm terrain went 0.51 m), and one the solver threw is
/// caught by its energy.
const EDGE_MARGIN: f64 = 0.5;
/// The physics errors of the bodies at the end of the run; `moved` is how
/// each moved in the last `window` seconds; `planes` when the model has
/// the ramps' planes (the mesh), not only their staircases (the boxes).
pub(crate) fn judge(
    world: &PhysicsWorld,
    handles: &[(RigidBodyHandle, ColliderHandle)],
    moved: &[Moved],
    window: f64,
    drops: &[Body],
    terrain: &Terrain,
    planes: bool,
) -> Vec<PhysicsError> {
    let solid = Solid::of(terrain, planes);
    let grid = terrain.grid();
    let s = terrain.block_size();
    let size = [f64::from(grid.nx) * s, f64::from(grid.ny) * s];
    let surface = |x: f64, y: f64| {
        let (cx, cy) = ((x / s).floor(), (y / s).floor());
        if cx < 0.0 || cy < 0.0 || cx >= f64::from(grid.nx) || cy >= f64::from(grid.ny) {
            return 0.0;
        }
        // `base + h·step`: 0, the ground, for an empty cell without a slab;
        // a ramp's plane over it where the model has planes (the highest
        // of the cells a point on a line between them touches).
        let cell = terrain.elevation(cx as u32, cy as u32);
        let plane = planes.then(|| terrain.height_at(x, y)).flatten();
        plane.map_or(cell, |z| z.max(cell))
    };
    let mut errors = Vec::new();
    for (i, ((&(handle, collider), drop), &moved)) in
        handles.iter().zip(drops).zip(moved).enumerate()
    {
        let p = world.bodies[handle].translation();
        let [x, y, z] = [p.x, p.y, p.z].map(f64::from);
        let error = |problem| PhysicsError {
            body: drop.label(i),
            problem,
        };
        if ![x, y, z, moved.distance]
            .iter()
            .all(|v: &f64| v.is_finite())
        {
            errors.push(error(Problem::NotFinite));
            continue;
        }
        let under = surface(x, y);
        if z < under - SINK_TOLERANCE {
            errors.push(error(Problem::Sank {
                centre: [x, y, z],
                surface: under,
            }));
        }
        let depth = solid.depth(world, collider);
        if depth > PENETRATION_LIMIT {
            errors.push(error(Problem::Inside {
                depth,
                limit: PENETRATION_LIMIT,
            }));
        }
        if moved.unsettled(window) {
            errors.push(error(Problem::StillMoving {
                distance: moved.distance,
                window,
            }));
        }
        let outside = (-x).max(x - size[0]).max(-y).max(y - size[1]);
        let slides = matches!(drop.shape, crate::bodies::Shape::Box(_));
        if slides && outside > EDGE_MARGIN {
            errors.push(error(Problem::LeftTheRse {
                outside,
                at: [x, y],
            }));
        }
    }
    errors
}

/// The solid a body must stay out of, whatever collider simulated it: the
/// terrain's box set (its union is exactly the solid, so the depth inside
/// any one box never exceeds the depth inside the solid) and the floor.
/// Judging by contacts with the simulated collider would not do: a mesh is
/// a surface, and the contact of a capsule with one of its triangles can
/// be deeper than the capsule is inside the solid (28 mm was seen on a
/// capsule lying across a step edge), and the `dist` cached in rapier's
/// contact manifolds can lag behind (a sphere resting on a top was
/// reported 21 mm deep).
pub(crate) struct Solid {
    parts: Vec<(Pose, SharedShape)>,
}

impl Solid {
    /// The solid of `terrain`'s box set and floor, and its ramps' wedges
    /// when `planes` (a wedge is convex: its hull is exactly its solid).
    pub(crate) fn of(terrain: &Terrain, planes: bool) -> Self {
        let vector = |v: [f64; 3]| Vector::new(v[0] as f32, v[1] as f32, v[2] as f32);
        let cuboid = |c: Vector, h: Vector| {
            (
                Pose::from_translation(c),
                SharedShape::cuboid(h.x, h.y, h.z),
            )
        };
        let (centre, half) = floor(terrain);
        let mut parts = vec![cuboid(centre, half)];
        parts.extend(
            terrain
                .boxes()
                .iter()
                .map(|b| cuboid(vector(b.center), vector(b.half_size))),
        );
        if planes {
            let (s, step, base) = (terrain.block_size(), terrain.step_height(), terrain.base());
            for ramp in terrain.ramps().iter().filter(|r| r.rise > 0) {
                let points: Vec<Vector> = ramp
                    .wedge_corners(s, base, step)
                    .into_iter()
                    .map(vector)
                    .collect();
                if let Some(hull) = SharedShape::convex_hull(&points) {
                    parts.push((Pose::IDENTITY, hull));
                }
            }
        }
        Solid { parts }
    }

    /// How deep `collider` is inside the solid, metres (0: outside).
    pub(crate) fn depth(&self, world: &PhysicsWorld, collider: ColliderHandle) -> f64 {
        let body = &world.colliders[collider];
        let near = body.compute_aabb();
        self.parts
            .iter()
            .filter(|(pose, part)| part.compute_aabb(pose).intersects(&near))
            .filter_map(|(pose, part)| {
                rapier3d::parry::query::contact(pose, &**part, body.position(), body.shape(), 0.0)
                    .ok()
                    .flatten()
            })
            .map(|contact| f64::from(-contact.dist))
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use rapier3d::prelude::*;

    use super::{Moved, Solid};

    /// A ball sunk 3 cm into the solid is 3 cm deep; resting on it, 0.
    #[test]
    fn depth_is_how_far_a_body_is_inside_the_solid() {
        let solid = Solid {
            parts: vec![(Pose::IDENTITY, SharedShape::cuboid(1.0, 1.0, 0.5))],
        };
        let depth_at = |z: f32| {
            let mut world = PhysicsWorld::new();
            let (_, ball) = world.insert(
                RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.0, z)),
                ColliderBuilder::ball(0.1),
            );
            solid.depth(&world, ball)
        };
        assert!((depth_at(0.57) - 0.03).abs() < 1e-4, "{}", depth_at(0.57));
        assert!(depth_at(0.6) < 1e-4);
        assert!(depth_at(0.8) == 0.0);
    }

    #[test]
    fn a_body_is_unsettled_only_when_it_moves_fast_without_going_down() {
        let moved = |distance, descent| Moved { distance, descent };
        assert!(moved(0.4, 0.0).unsettled(1.0), "sliding along");
        assert!(moved(0.4, -0.1).unsettled(1.0), "going up");
        assert!(moved(0.2, 0.0).unsettled(0.5), "a speed, per second");
        assert!(!moved(0.1, 0.0).unsettled(1.0), "creeping");
        assert!(!moved(0.31, 0.2).unsettled(1.0), "falling off a tower");
    }
}
