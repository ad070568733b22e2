//! A rapier physics smoke test of a Random Step Environment (what
//! `rse-gen check --physics` runs): drop a fixed, seeded set of robot-part-sized bodies
//! on the terrain, simulate, and report the mean step time beside the same
//! bodies on a flat plane (the paper's RTF vs control RTF, §4) and every
//! physics error — those `bench/robots.py` counts for robots (a state that
//! is not finite, a body faster than 10 m/s), a body more than 1 cm inside
//! the solid, and a dropped body's own: one that sank
//! into the terrain, one still fast after settling, a box that slid off
//! the RSE without being pushed (a ball rolls on), one thrown.

mod bodies;
mod judge;
mod model;
mod report;
mod run;
mod scene;

use std::time::Duration;

use rse_core::Terrain;

pub use bodies::{Body, Shape, drop_set};
pub use judge::{PENETRATION_LIMIT, SPEED_LIMIT};
pub use model::TerrainModel;
pub use report::{ColliderKind, PhysicsError, PhysicsReport, Problem, TestedCollider};

use run::Run;

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

#[cfg(test)]
mod tests {
    use super::{SmokeTest, TerrainModel, smoke_test, smoke_tests};
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
}
