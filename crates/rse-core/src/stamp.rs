//! How each obstacle changes the heightmap (SPEC §3, paper §3.3).
//!
//! Every obstacle yields a height per cell, quantised to whole steps, which is
//! combined with the map by the maximum rule (raising obstacles) or subtracted
//! with a floor at 0 (pit, long pit).

use crate::heightmap::Heightmap;
use crate::obstacle::{DrawnObstacle, ObstacleKind};
use crate::rng::{ClampedRoundedNormal, WorldRng};

/// Lengths of the grid, in metres.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Units {
    pub block_size: f64,
    pub step_height: f64,
}

/// Applies one drawn obstacle to `map`. Per-cell random values are drawn row
/// by row from `y = 0`, `x` fastest.
pub(crate) fn apply(obstacle: &DrawnObstacle, map: &mut Heightmap, rng: &mut WorldRng, units: Units) {
    let height = obstacle.height;
    match obstacle.kind {
        ObstacleKind::Random => {
            for cell in map.cells_mut() {
                raise(cell, rng.up_to(height));
            }
        }
        ObstacleKind::Gaussian => {
            let sigma = obstacle.sigma.unwrap_or(1.0);
            let normal = ClampedRoundedNormal::new(f64::from(height) / 2.0, sigma, height);
            for cell in map.cells_mut() {
                raise(cell, normal.sample(rng));
            }
        }
        ObstacleKind::Peak | ObstacleKind::Pit | ObstacleKind::Wall | ObstacleKind::LongPit => {
            let from = obstacle.p1.expect("a validated peak, pit, wall or long pit has p1");
            // A peak is a wall whose segment has no length (SPEC §3).
            let to = obstacle.p2.unwrap_or(from);
            let slope = Slope::new(height, obstacle.angle.unwrap_or(90.0), units);
            apply_segment(map, from, to, &slope, obstacle.kind.lowers());
        }
    }
}

#[inline]
fn raise(cell: &mut u16, value: u32) {
    *cell = (*cell).max(value as u16);
}

#[inline]
fn lower(cell: &mut u16, value: u32) {
    *cell = (*cell).saturating_sub(value as u16);
}

/// Height `H` on top, falling off by `tan(a)` with distance (eq. 1).
struct Slope {
    height: u32,
    tan: f64,
    units: Units,
}

impl Slope {
    fn new(height: u32, angle_degrees: f64, units: Units) -> Self {
        // tan(90°) in floating point is finite but huge; make it exact.
        let tan = if angle_degrees >= 90.0 {
            f64::INFINITY
        } else {
            libm::tan(angle_degrees * (std::f64::consts::PI / 180.0))
        };
        Slope { height, tan, units }
    }

    /// Steps of a cell whose centre is `distance` cells away, beyond the top.
    #[inline]
    fn steps_at(&self, distance: f64) -> u32 {
        let d = distance * self.units.block_size;
        let z = f64::from(self.height) * self.units.step_height - d * self.tan;
        if z <= 0.0 {
            return 0;
        }
        // The highest whole step not above the sloped surface (SPEC §3).
        let steps = (z / self.units.step_height + 1e-9).floor();
        (steps as u32).min(self.height)
    }

    /// Cells beyond this distance get 0 steps.
    fn reach(&self) -> f64 {
        let metres = f64::from(self.height) * self.units.step_height / self.tan;
        metres / self.units.block_size
    }
}

/// The wall of Algorithm 1 between `from` and `to` (a peak when they are equal):
/// only cells whose centre projects onto the segment are touched.
fn apply_segment(map: &mut Heightmap, from: [u32; 2], to: [u32; 2], slope: &Slope, lowers: bool) {
    if slope.height == 0 {
        return; // adds nothing under max, removes nothing under subtraction
    }
    let (nx, ny) = (i64::from(map.nx()), i64::from(map.ny()));
    let [x0, y0] = from.map(i64::from);
    let [x1, y1] = to.map(i64::from);
    let (vx, vy) = (x1 - x0, y1 - y0);
    let len2 = vx * vx + vy * vy;
    let len = (len2 as f64).sqrt();

    // Cells farther than `reach` from the segment get 0, which changes nothing;
    // visiting only the box around the segment keeps big maps fast.
    let margin = slope.reach().min(f64::from(u32::MAX)).ceil() as i64 + 1;
    let x_range = (x0.min(x1) - margin).max(0)..=(x0.max(x1) + margin).min(nx - 1);
    let y_range = (y0.min(y1) - margin).max(0)..=(y0.max(y1) + margin).min(ny - 1);

    for y in y_range {
        let row = map.row_mut(y as u32);
        let wy = y - y0;
        for x in x_range.clone() {
            let wx = x - x0;
            let steps = if len2 == 0 {
                // Peak: d = |s − p| (eq. 3); the cell itself is the top.
                let d2 = wx * wx + wy * wy;
                if 2 * d2 <= 1 {
                    slope.height
                } else {
                    slope.steps_at((d2 as f64).sqrt())
                }
            } else {
                let dot = wx * vx + wy * vy;
                if dot < 0 || dot > len2 {
                    continue; // does not project onto the segment
                }
                // d = |v × w| / |v| (eq. 2). `d ≤ √2/2` is tested exactly in
                // integers: cells at exactly √2/2 (beside a 45° wall) are top.
                let cross = vx * wy - vy * wx;
                if 2 * i128::from(cross) * i128::from(cross) <= i128::from(len2) {
                    slope.height
                } else {
                    slope.steps_at(cross.abs() as f64 / len)
                }
            };
            let cell = &mut row[x as usize];
            if lowers {
                lower(cell, steps);
            } else {
                raise(cell, steps);
            }
        }
    }
}
