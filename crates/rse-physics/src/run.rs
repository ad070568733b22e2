//! Stepping: one smoke test's bodies and steps, the timed runs on each
//! terrain model and on the flat control, and what is watched at every
//! step (energy, speed); `judge` gives the verdict on where the bodies end.

use std::time::{Duration, Instant};

use rapier3d::prelude::*;
use rse_core::Terrain;

use crate::SmokeTest;
use crate::bodies::{Body, drop_set};
use crate::judge::{Moved, SPEED_LIMIT, judge};
use crate::model::TerrainModel;
use crate::report::{PhysicsError, PhysicsReport, Problem, TestedCollider};
use crate::scene::scene;

/// Kinetic energy a body may have beyond what its fall gave it, as a height
/// of fall, metres: contact resolution may push a body up a little.
const ENERGY_SLACK_HEIGHT: f64 = 0.02;

/// One smoke test's setting: the terrain, its bodies and steps.
pub(crate) struct Run<'a> {
    terrain: &'a Terrain,
    drops: Vec<Body>,
    rate_hz: f64,
    steps: usize,
}

impl<'a> Run<'a> {
    pub(crate) fn new(terrain: &'a Terrain, test: SmokeTest) -> Self {
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
    pub(crate) fn plane_step_us(&self) -> f64 {
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
    pub(crate) fn report(
        &self,
        model: &TerrainModel,
        file: Option<&str>,
        plane_step_us: f64,
    ) -> PhysicsReport {
        let timed = self.on_model(model);
        self.finish(model, file, timed, plane_step_us)
    }

    /// The report of a model's run, `timed`: its stepping time and errors.
    pub(crate) fn finish(
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
    pub(crate) fn on_model(&self, model: &TerrainModel) -> (Duration, Vec<PhysicsError>) {
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
        let planes = model.kind() == crate::report::ColliderKind::Mesh;
        let mut errors = judge(&world, &handles, &moved, window, drops, terrain, planes);
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
