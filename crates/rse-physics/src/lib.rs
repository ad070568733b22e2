//! A rapier physics smoke test of a Random Step Environment (issue
//! "`rse-gen check`"): drop a fixed, seeded set of robot-part-sized bodies
//! on the terrain, simulate, and report the mean step time beside the same
//! bodies on a flat plane (the paper's RTF vs control RTF, §4) and every
//! physics error — those `bench/robots.py` counts for robots (a state that
//! is not finite, a body faster than 10 m/s), a body more than 1 cm inside
//! the solid, and a dropped body's own: one that sank
//! into the terrain, one still fast after settling, one that left the RSE
//! without being pushed, one thrown.

mod bodies;
mod report;

use std::time::{Duration, Instant};

use rapier3d::prelude::*;
use rse_core::Terrain;

pub use bodies::{Body, Shape, drop_set};
pub use report::{ColliderKind, PhysicsError, PhysicsReport, Problem, TestedCollider};

/// The terrain as the simulator gets it.
#[derive(Debug, Clone)]
pub enum TerrainModel {
    /// One static triangle mesh (metres, grid frame).
    Mesh {
        /// Vertex positions.
        vertices: Vec<[f32; 3]>,
        /// Triangles, counter-clockwise from outside.
        triangles: Vec<[u32; 3]>,
    },
    /// Static boxes: `(centre, half size)` in metres.
    Boxes(Vec<([f64; 3], [f64; 3])>),
}

/// A body deeper than this inside the solid is a physics error, metres (the
/// tolerance of `tests/python/test_gz_physics.py` for bodies at rest).
pub const PENETRATION_LIMIT: f64 = 0.01;
/// A body faster than this at any step is a physics error, m/s (as in
/// `bench/robots.py`): nothing dropped a few centimetres gets near it.
pub const SPEED_LIMIT: f64 = 10.0;

impl TerrainModel {
    /// Mesh or boxes.
    pub fn kind(&self) -> ColliderKind {
        match self {
            TerrainModel::Mesh { .. } => ColliderKind::Mesh,
            TerrainModel::Boxes(_) => ColliderKind::Boxes,
        }
    }

    /// The single mesh of `terrain`.
    pub fn mesh_of(terrain: &Terrain) -> Self {
        let mesh = terrain.mesh();
        TerrainModel::Mesh {
            vertices: mesh.vertices().to_vec(),
            triangles: mesh.triangles().to_vec(),
        }
    }

    /// `true` for a terrain with nothing in it.
    pub fn is_empty(&self) -> bool {
        match self {
            TerrainModel::Mesh { triangles, .. } => triangles.is_empty(),
            TerrainModel::Boxes(boxes) => boxes.is_empty(),
        }
    }

    /// The box set of `terrain`.
    pub fn boxes_of(terrain: &Terrain) -> Self {
        TerrainModel::Boxes(
            terrain
                .boxes()
                .iter()
                .map(|b| (b.center, b.half_size))
                .collect(),
        )
    }
}

/// How long and how finely to simulate, and with how many bodies.
#[derive(Debug, Clone, Copy)]
pub struct SmokeTest {
    /// Bodies dropped (boxes, spheres and capsules in turn).
    pub bodies: usize,
    /// Simulated time, seconds.
    pub seconds: f64,
    /// Steps per simulated second.
    pub rate_hz: f64,
}

impl Default for SmokeTest {
    /// 20 bodies, 5 s at 1 kHz.
    fn default() -> Self {
        SmokeTest {
            bodies: 20,
            seconds: 5.0,
            rate_hz: 1000.0,
        }
    }
}

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
struct Moved {
    /// Straight-line distance, metres.
    distance: f64,
    /// How far its centre went down, metres (negative: up).
    descent: f64,
}

impl Moved {
    /// Moving without cause over `window` seconds: too fast, and not
    /// going down.
    fn unsettled(self, window: f64) -> bool {
        self.distance / window.max(1e-9) > SETTLED_SPEED && self.descent <= SETTLING_DESCENT
    }
}
/// How far past the RSE's edge a body may roll or slide, metres.
const EDGE_MARGIN: f64 = 0.5;
/// Kinetic energy a body may have beyond what its fall gave it, as a height
/// of fall, metres: contact resolution may push a body up a little.
const ENERGY_SLACK_HEIGHT: f64 = 0.02;

/// Runs the smoke test of `model`, the terrain of `terrain`; the report
/// names the world file the model was read from, `file`, when there is one.
pub fn smoke_test(
    model: &TerrainModel,
    file: Option<&str>,
    terrain: &Terrain,
    test: SmokeTest,
) -> PhysicsReport {
    let run = Run::new(terrain, test);
    run.report(model, file, run.plane_step_us())
}

/// Runs the smoke test of each of `models` (each with the world file it was
/// read from, if any), all models of the one terrain `terrain`: one report
/// each, in order. The flat-plane reference drops the same bodies on the
/// same floor whatever the model, so it is simulated once for all of them
/// (a third of the work of a world checked with two colliders).
pub fn smoke_tests(
    models: &[(&TerrainModel, Option<&str>)],
    terrain: &Terrain,
    test: SmokeTest,
) -> Vec<PhysicsReport> {
    if models.is_empty() {
        return Vec::new();
    }
    let run = Run::new(terrain, test);
    let timed: Vec<(Duration, Vec<PhysicsError>)> = models
        .iter()
        .map(|(model, _)| run.on_model(model))
        .collect();
    let plane_step_us = run.plane_step_us();
    models
        .iter()
        .zip(timed)
        .map(|(&(model, file), timed)| run.finish(model, file, timed, plane_step_us))
        .collect()
}

/// One smoke test's setting: the terrain, its bodies and steps.
struct Run<'a> {
    terrain: &'a Terrain,
    drops: Vec<Body>,
    rate_hz: f64,
    steps: usize,
}

impl<'a> Run<'a> {
    fn new(terrain: &'a Terrain, test: SmokeTest) -> Self {
        Run {
            terrain,
            drops: drop_set(terrain, test.bodies),
            rate_hz: test.rate_hz,
            steps: (test.seconds * test.rate_hz).round() as usize,
        }
    }

    fn dt(&self) -> f32 {
        (1.0 / self.rate_hz) as f32
    }

    /// Microseconds per step, from the time of the whole run.
    fn per_step(&self, t: Duration) -> f64 {
        t.as_secs_f64() * 1e6 / self.steps.max(1) as f64
    }

    /// The mean step time of the same bodies dropped on the floor alone,
    /// each from its height over its cell.
    fn plane_step_us(&self) -> f64 {
        let flat: Vec<Body> = self
            .drops
            .iter()
            .map(|b| Body {
                start: [b.start[0], b.start[1], b.drop_over],
                ..*b
            })
            .collect();
        let (mut plane, _) = scene(None, &flat, self.dt(), self.terrain);
        self.per_step(simulate(&mut plane, self.steps, &mut |_| {}))
    }

    /// The report of `model` alone.
    fn report(
        &self,
        model: &TerrainModel,
        file: Option<&str>,
        plane_step_us: f64,
    ) -> PhysicsReport {
        let timed = self.on_model(model);
        self.finish(model, file, timed, plane_step_us)
    }

    /// The report of a model's run, `timed`: its stepping time and errors.
    fn finish(
        &self,
        model: &TerrainModel,
        file: Option<&str>,
        (rse_time, errors): (Duration, Vec<PhysicsError>),
        plane_step_us: f64,
    ) -> PhysicsReport {
        // Timings are noisy well above these roundings.
        let round = |v: f64, unit: f64| (v / unit).round() * unit;
        let rse_step_us = self.per_step(rse_time);
        PhysicsReport {
            collider: TestedCollider {
                kind: model.kind(),
                file: file.map(str::to_owned),
            },
            rse_step_us: round(rse_step_us, 0.01),
            plane_step_us: round(plane_step_us, 0.01),
            ratio: round(rse_step_us / plane_step_us.max(1e-9), 0.001),
            bodies: self.drops.len(),
            steps: self.steps,
            errors,
        }
    }

    /// Drops the bodies on `model`: the time spent stepping, and the
    /// physics errors found.
    fn on_model(&self, model: &TerrainModel) -> (Duration, Vec<PhysicsError>) {
        let (terrain, drops, rate_hz, steps) =
            (self.terrain, &self.drops[..], self.rate_hz, self.steps);
        let (mut world, handles) = scene(Some(model), drops, self.dt(), terrain);
        let last_second = (rate_hz.round() as usize).min(steps);
        // Energy no body may exceed: what it had at the start plus what it
        // gained by falling. A solver that throws a body out breaks this.
        let mut gain = vec![0.0f64; handles.len()];
        let mut top_speed = vec![0.0f64; handles.len()];
        let mut watch_energy = |world: &PhysicsWorld| {
            for (i, (&(h, _), drop)) in handles.iter().zip(drops).enumerate() {
                let body = &world.bodies[h];
                let fallen = drop.start[2] - f64::from(body.translation().z);
                let budget = f64::from(body.mass()) * 9.81 * (fallen + ENERGY_SLACK_HEIGHT);
                gain[i] = gain[i].max(f64::from(body.kinetic_energy()) - budget);
                top_speed[i] = top_speed[i].max(f64::from(body.linvel().length()));
            }
        };
        let mut rse_time = simulate(&mut world, steps - last_second, &mut watch_energy);
        let before: Vec<Vector> = handles
            .iter()
            .map(|&(h, _)| world.bodies[h].translation())
            .collect();
        rse_time += simulate(&mut world, last_second, &mut watch_energy);
        let moved: Vec<Moved> = handles
            .iter()
            .zip(&before)
            .map(|(&(h, _), &p)| {
                let d = world.bodies[h].translation() - p;
                Moved {
                    distance: f64::from(d.length()),
                    descent: f64::from(-d.z),
                }
            })
            .collect();
        let window = last_second as f64 / rate_hz;
        let mut errors = judge(&world, &handles, &moved, window, drops, terrain);
        for (i, drop) in drops.iter().enumerate() {
            if gain[i] > 0.0 {
                errors.push(PhysicsError {
                    body: drop.label(i),
                    problem: Problem::Thrown { joules: gain[i] },
                });
            }
            if top_speed[i] > SPEED_LIMIT {
                errors.push(PhysicsError {
                    body: drop.label(i),
                    problem: Problem::TooFast {
                        speed: top_speed[i],
                        limit: SPEED_LIMIT,
                    },
                });
            }
        }
        (rse_time, errors)
    }
}

/// The floor the pallets stand on, a slab whose top is `z = 0` reaching
/// well past them: its centre and half size.
fn floor(terrain: &Terrain) -> (Vector, Vector) {
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
fn scene(
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
            .friction(0.8);
            world.insert(body, collider)
        })
        .collect();
    (world, handles)
}

/// Steps `world` `steps` times, calling `after` after each step; the time
/// spent stepping alone.
fn simulate(
    world: &mut PhysicsWorld,
    steps: usize,
    after: &mut dyn FnMut(&PhysicsWorld),
) -> Duration {
    let mut spent = Duration::ZERO;
    for _ in 0..steps {
        let start = Instant::now();
        world.step();
        spent += start.elapsed();
        after(world);
    }
    spent
}

/// The physics errors of the bodies at the end of the run; `moved` is how
/// each moved in the last `window` seconds.
fn judge(
    world: &PhysicsWorld,
    handles: &[(RigidBodyHandle, ColliderHandle)],
    moved: &[Moved],
    window: f64,
    drops: &[Body],
    terrain: &Terrain,
) -> Vec<PhysicsError> {
    let solid = Solid::of(terrain);
    let grid = terrain.grid();
    let s = terrain.block_size();
    let size = [f64::from(grid.nx) * s, f64::from(grid.ny) * s];
    let surface = |x: f64, y: f64| {
        let (cx, cy) = ((x / s).floor(), (y / s).floor());
        if cx < 0.0 || cy < 0.0 || cx >= f64::from(grid.nx) || cy >= f64::from(grid.ny) {
            return 0.0;
        }
        // `base + h·step`: 0, the ground, for an empty cell without a slab.
        terrain.elevation(cx as u32, cy as u32)
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
        if outside > EDGE_MARGIN {
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
struct Solid {
    parts: Vec<(Pose, Cuboid)>,
}

impl Solid {
    fn of(terrain: &Terrain) -> Self {
        let cuboid = |c: Vector, h: Vector| (Pose::from_translation(c), Cuboid::new(h));
        let (centre, half) = floor(terrain);
        let mut parts = vec![cuboid(centre, half)];
        parts.extend(terrain.boxes().iter().map(|b| {
            let [c, h] =
                [b.center, b.half_size].map(|v| Vector::new(v[0] as f32, v[1] as f32, v[2] as f32));
            cuboid(c, h)
        }));
        Solid { parts }
    }

    /// How deep `collider` is inside the solid, metres (0: outside).
    fn depth(&self, world: &PhysicsWorld, collider: ColliderHandle) -> f64 {
        let body = &world.colliders[collider];
        let near = body.compute_aabb();
        self.parts
            .iter()
            .filter(|(pose, part)| part.aabb(pose).intersects(&near))
            .filter_map(|(pose, part)| {
                rapier3d::parry::query::contact(pose, part, body.position(), body.shape(), 0.0)
                    .ok()
                    .flatten()
            })
            .map(|contact| f64::from(-contact.dist))
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::{Moved, SmokeTest, Solid, TerrainModel, smoke_test, smoke_tests};
    use rapier3d::prelude::*;
    use rse_core::{Scheme, generate};

    /// Several models of one terrain share one plane run, and each report
    /// is the one its model gets alone (rapier is deterministic).
    #[test]
    fn models_of_one_terrain_share_the_plane_and_keep_their_verdicts() {
        let scheme = Scheme::from_csv("# size: 6x6\ntype,height\nrandom,3\n", None).unwrap();
        let terrain = generate(&scheme, 0, 0);
        let test = SmokeTest {
            bodies: 4,
            seconds: 1.0,
            rate_hz: 500.0,
        };
        let (mesh, boxes) = (
            TerrainModel::mesh_of(&terrain),
            TerrainModel::boxes_of(&terrain),
        );
        let both = smoke_tests(&[(&mesh, Some("m.obj")), (&boxes, None)], &terrain, test);
        assert_eq!(both.len(), 2);
        assert_eq!(
            both[0].plane_step_us.to_bits(),
            both[1].plane_step_us.to_bits()
        );
        assert_eq!(both[0].collider.file.as_deref(), Some("m.obj"));
        for (report, model) in both.iter().zip([&mesh, &boxes]) {
            let alone = smoke_test(model, None, &terrain, test);
            assert_eq!(report.collider.kind, model.kind());
            assert_eq!((report.bodies, report.steps), (4, 500));
            assert_eq!(
                format!("{:?}", report.errors),
                format!("{:?}", alone.errors)
            );
        }
        assert!(smoke_tests(&[], &terrain, test).is_empty());
    }

    /// A ball sunk 3 cm into the solid is 3 cm deep; resting on it, 0.
    #[test]
    fn depth_is_how_far_a_body_is_inside_the_solid() {
        let solid = Solid {
            parts: vec![(Pose::IDENTITY, Cuboid::new(Vector::new(1.0, 1.0, 0.5)))],
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
