//! What a smoke test reports: the collider it ran on and each physics
//! error, as types (the CLI groups runs by collider kind, Python reads the
//! fields); both serialise to the text they display, so `check --json`
//! keeps its shape.

use std::fmt;

use serde::{Serialize, Serializer};

/// What one smoke test found.
#[derive(Debug, Clone, Serialize)]
pub struct PhysicsReport {
    /// The collider tested (`mesh FILE` in a world, or `boxes`).
    pub collider: TestedCollider,
    /// Mean wall time of one step with the RSE, microseconds.
    pub rse_step_us: f64,
    /// Mean wall time of one step with the same bodies on a plane.
    pub plane_step_us: f64,
    /// `rse_step_us / plane_step_us`: how much the terrain slows physics.
    pub ratio: f64,
    /// Bodies dropped.
    pub bodies: usize,
    /// Steps simulated.
    pub steps: usize,
    /// Every physics error; empty when the terrain is sound.
    pub errors: Vec<PhysicsError>,
}

/// The kind of collider a smoke test ran on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ColliderKind {
    /// A triangle mesh.
    Mesh,
    /// The box set.
    Boxes,
}

impl ColliderKind {
    /// `mesh` or `boxes`.
    pub fn name(self) -> &'static str {
        match self {
            ColliderKind::Mesh => "mesh",
            ColliderKind::Boxes => "boxes",
        }
    }
}

impl fmt::Display for ColliderKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The collider a smoke test ran on: its kind, and the world file it was
/// read from when there is one.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct TestedCollider {
    /// Mesh or boxes.
    pub kind: ColliderKind,
    /// The world-relative file of a mesh (`meshes/terrain.obj`).
    pub file: Option<String>,
}

impl fmt::Display for TestedCollider {
    /// `mesh meshes/terrain.obj`, `mesh` or `boxes`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(file) => write!(f, "{} {file}", self.kind),
            None => write!(f, "{}", self.kind),
        }
    }
}

impl Serialize for TestedCollider {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// One body's physics error: which body, and what went wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct PhysicsError {
    /// The body, as the drop set names it (`body 3 (box, dropped over (1.20, 0.40))`).
    pub body: String,
    /// What went wrong.
    pub problem: Problem,
}

/// What went wrong with a body, with the figures that show it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Problem {
    /// Its position or motion is NaN or infinite.
    NotFinite,
    /// Its centre ended more than 1 cm under the surface under it.
    Sank {
        /// Its centre, metres.
        centre: [f64; 3],
        /// The top under it, metres.
        surface: f64,
    },
    /// It ended deeper inside the solid than the limit.
    Inside {
        /// How deep, metres.
        depth: f64,
        /// The limit, metres.
        limit: f64,
    },
    /// It still moved in the last window of the run.
    StillMoving {
        /// How far, metres.
        distance: f64,
        /// The window, seconds.
        window: f64,
    },
    /// It ended past the RSE's edge without being pushed.
    LeftTheRse {
        /// How far past, metres.
        outside: f64,
        /// Where, metres.
        at: [f64; 2],
    },
    /// It gained more kinetic energy than its fall gives.
    Thrown {
        /// The excess, joules.
        joules: f64,
    },
    /// It went faster than a dropped body can.
    TooFast {
        /// Its top speed, m/s.
        speed: f64,
        /// The limit, m/s.
        limit: f64,
    },
}

impl fmt::Display for PhysicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = &self.body;
        match self.problem {
            Problem::NotFinite => write!(f, "{name}: its state is not finite"),
            Problem::Sank {
                centre: [x, y, z],
                surface,
            } => write!(
                f,
                "{name}: sank into the terrain: centre at ({x:.3}, {y:.3}, {z:.3}) m under a surface at {surface:.3} m"
            ),
            Problem::Inside { depth, limit } => write!(
                f,
                "{name}: {:.1} mm inside the solid (limit {:.0} mm)",
                depth * 1e3,
                limit * 1e3
            ),
            Problem::StillMoving { distance, window } => write!(
                f,
                "{name}: still moving after settling: {distance:.2} m in the last {window:.1} s"
            ),
            Problem::LeftTheRse {
                outside,
                at: [x, y],
            } => write!(
                f,
                "{name}: left the RSE: {outside:.2} m past its edge at ({x:.2}, {y:.2})"
            ),
            Problem::Thrown { joules } => write!(
                f,
                "{name}: gained {joules:.3} J more kinetic energy than its fall gives (thrown by the solver)"
            ),
            Problem::TooFast { speed, limit } => {
                write!(f, "{name}: reached {speed:.1} m/s (limit {limit} m/s)")
            }
        }
    }
}

impl Serialize for PhysicsError {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}
