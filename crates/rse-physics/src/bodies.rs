//! The fixed, seeded set of bodies a smoke test drops: boxes, spheres and
//! capsules of robot-part size over the RSE's footprint.

use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng as _, SeedableRng as _};
use rse_core::{Ramp, Terrain};

/// A body's shape, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// Half sizes.
    Box([f64; 3]),
    /// Radius.
    Sphere(f64),
    /// Along z: half the length of the segment, and the radius.
    Capsule {
        /// Half the segment between the caps' centres.
        half_height: f64,
        /// Radius.
        radius: f64,
    },
}

impl Shape {
    /// `box`, `sphere` or `capsule`.
    pub fn name(self) -> &'static str {
        match self {
            Shape::Box(_) => "box",
            Shape::Sphere(_) => "sphere",
            Shape::Capsule { .. } => "capsule",
        }
    }

    /// Largest distance from the centre to the surface.
    fn reach(self) -> f64 {
        match self {
            Shape::Box(h) => (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt(),
            Shape::Sphere(r) => r,
            Shape::Capsule {
                half_height,
                radius,
            } => half_height + radius,
        }
    }
}

/// A body and where it starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// Box, sphere or capsule, with its sizes.
    pub shape: Shape,
    /// Centre at the start, metres.
    pub start: [f64; 3],
    /// Start orientation as a scaled rotation axis, radians.
    pub rotation: [f64; 3],
    /// Height of the start above the terrain under it, metres.
    pub drop_over: f64,
}

impl Body {
    /// How errors name body `i`: its number, shape and drop point.
    pub fn label(&self, i: usize) -> String {
        format!(
            "body {i} ({}, dropped over ({:.2}, {:.2}))",
            self.shape.name(),
            self.start[0],
            self.start[1]
        )
    }
}

/// `count` bodies over `terrain`: the same draws for every terrain of a
/// size (seed 0), placed in the cells a margin inside the footprint, each
/// starting 5 cm plus its reach above the highest cell within its reach.
pub fn drop_set(terrain: &Terrain, count: usize) -> Vec<Body> {
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let mut uniform =
        |lo: f64, hi: f64| lo + (hi - lo) * (f64::from(rng.next_u32()) / f64::from(u32::MAX));
    let grid = terrain.grid();
    let s = terrain.block_size();
    let size = [f64::from(grid.nx) * s, f64::from(grid.ny) * s];
    (0..count)
        .map(|i| {
            // Robot parts: feet, wheels, links of 5 to 16 cm.
            let shape = match i % 3 {
                0 => Shape::Box([
                    uniform(0.03, 0.08),
                    uniform(0.03, 0.08),
                    uniform(0.025, 0.05),
                ]),
                1 => Shape::Sphere(uniform(0.03, 0.07)),
                _ => Shape::Capsule {
                    half_height: uniform(0.03, 0.06),
                    radius: uniform(0.025, 0.045),
                },
            };
            let margin = s.min(size[0].min(size[1]) / 4.0);
            let x = uniform(margin, size[0] - margin);
            let y = uniform(margin, size[1] - margin);
            let rotation = [uniform(-0.5, 0.5), uniform(-0.5, 0.5), uniform(-3.1, 3.1)];
            // A ball or a capsule dropped on a ramp rolls down it and on
            // across the floor, as it should (nothing in rapier slows a
            // roll): over a ramp, a box as wide stands in for it.
            let shape = match shape {
                Shape::Sphere(r) | Shape::Capsule { radius: r, .. }
                    if over_ramp(terrain, x, y, shape.reach()) =>
                {
                    Shape::Box([r, r, 0.75 * r])
                }
                shape => shape,
            };
            let reach = shape.reach();
            let highest = highest_within(terrain, x, y, reach);
            let drop_over = 0.05 + reach;
            Body {
                shape,
                start: [x, y, highest + drop_over],
                rotation,
                drop_over,
            }
        })
        .collect()
}

/// The cells within `reach` of `(x, y)`, inclusive corners.
fn cells_within(terrain: &Terrain, x: f64, y: f64, reach: f64) -> [u32; 4] {
    let grid = terrain.grid();
    let s = terrain.block_size();
    let cell = |v: f64, n: u32| ((v / s).floor().max(0.0) as u32).min(n - 1);
    [
        cell(x - reach, grid.nx),
        cell(y - reach, grid.ny),
        cell(x + reach, grid.nx),
        cell(y + reach, grid.ny),
    ]
}

/// Whether `ramp` lies under one of `cells` (inclusive corners).
fn overlaps(ramp: &Ramp, [x0, y0, x1, y1]: [u32; 4]) -> bool {
    let [rx0, ry0, rx1, ry1] = ramp.cells;
    rx0 <= x1 && x0 <= rx1 && ry0 <= y1 && y0 <= ry1
}

/// Whether a ramp lies under a cell within `reach` of `(x, y)`.
fn over_ramp(terrain: &Terrain, x: f64, y: f64, reach: f64) -> bool {
    let cells = cells_within(terrain, x, y, reach);
    terrain.ramps().iter().any(|r| overlaps(r, cells))
}

/// The highest top of the cells within `reach` of `(x, y)` (0: the
/// ground), or of a ramp's plane under the disc of that reach.
fn highest_within(terrain: &Terrain, x: f64, y: f64, reach: f64) -> f64 {
    let [x0, y0, x1, y1] = cells_within(terrain, x, y, reach);
    // An empty cell without a slab has elevation 0: the ground.
    let cells = (y0..=y1)
        .flat_map(|cy| (x0..=x1).map(move |cx| terrain.elevation(cx, cy)))
        .fold(0.0, f64::max);
    let s = terrain.block_size();
    terrain
        .highest_plane_under_disc([x / s, y / s], reach / s)
        .map_or(cells, |plane| plane.max(cells))
}
