//! How each obstacle changes the heightmap (docs/schemes.md).
//!
//! Every obstacle yields a height per cell, quantised to whole steps, which is
//! combined with the map by the maximum rule (raising obstacles) or subtracted
//! with a floor at 0 (pit, long pit).

use crate::globals::Grid;
use crate::heightmap::Heightmap;
use crate::obstacle::{DrawnObstacle, Obstacle, ObstacleKind};
use crate::param::Param;
use crate::rng::{ClampedRoundedNormal, WorldRng};

/// Lengths of the grid, in metres.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Units {
    pub block_size: f64,
    pub step_height: f64,
}

/// Cells drawn per bulk request of random words.
const CHUNK: usize = 1024;

/// Applies one drawn obstacle to `map`. Per-cell random values are drawn row
/// by row from `y = 0`, `x` fastest.
pub(crate) fn apply(
    obstacle: &DrawnObstacle,
    map: &mut Heightmap,
    rng: &mut WorldRng,
    units: Units,
) {
    let height = obstacle.height;
    match obstacle.kind {
        ObstacleKind::Random => {
            let mut values = [0u32; CHUNK];
            for cells in map.cells_mut().chunks_mut(CHUNK) {
                let values = &mut values[..cells.len()];
                rng.fill_up_to(height, values);
                cells
                    .iter_mut()
                    .zip(values.iter())
                    .for_each(|(c, &v)| raise(c, v));
            }
        }
        ObstacleKind::Gaussian => {
            let sigma = obstacle.sigma.expect("a drawn gaussian has its sigma");
            let normal = ClampedRoundedNormal::new(f64::from(height) / 2.0, sigma, height);
            let mut words = [0u32; CHUNK];
            for cells in map.cells_mut().chunks_mut(CHUNK) {
                let words = &mut words[..cells.len()];
                rng.fill_words(words);
                cells
                    .iter_mut()
                    .zip(words.iter())
                    .for_each(|(c, &w)| raise(c, normal.value_of(w)));
            }
        }
        ObstacleKind::Peak | ObstacleKind::Pit | ObstacleKind::Wall | ObstacleKind::LongPit => {
            let from = obstacle
                .p1
                .expect("a validated peak, pit, wall or long pit has p1");
            // A peak is a wall whose segment has no length (docs/schemes.md).
            let to = obstacle.p2.unwrap_or(from);
            let angle = obstacle
                .angle
                .expect("a validated peak, pit, wall or long pit has an angle");
            let slope = Slope::new(height, angle, units);
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
pub(crate) struct Slope {
    height: u32,
    tan: f64,
    units: Units,
}

impl Slope {
    pub(crate) fn new(height: u32, angle_degrees: f64, units: Units) -> Self {
        // tan(90°) in floating point is finite but huge; make it exact.
        // A scheme's `-0` passes the 0..=90 check, and tan(-0) = -0 would
        // make the reach -inf (an empty span: nothing drawn, no cells
        // budgeted, an overflow in debug): -0 is 0.
        let tan = if angle_degrees >= 90.0 {
            f64::INFINITY
        } else {
            libm::tan(angle_degrees * (std::f64::consts::PI / 180.0)).abs()
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
        // The highest whole step not above the sloped surface (docs/schemes.md).
        let steps = (z / self.units.step_height + 1e-9).floor();
        (steps as u32).min(self.height)
    }

    /// Cells beyond this distance get 0 steps.
    pub(crate) fn reach(&self) -> f64 {
        let metres = f64::from(self.height) * self.units.step_height / self.tan;
        metres / self.units.block_size
    }
}

/// At most how many cells [`apply`] visits for any drawing of `obstacle`
/// on `grid`: every cell for a random or gaussian field; for a peak, pit,
/// wall or long pit the box around the span of its points widened by the
/// reach of its steepest-to-gentlest slope (highest height, lowest angle),
/// kept to the grid. What `check` budgets before it rebuilds a world.
pub(crate) fn visits(obstacle: &Obstacle, grid: Grid, units: Units) -> u64 {
    let f = obstacle.fields();
    let cells = u64::from(grid.nx) * u64::from(grid.ny);
    let (Some(height), Some(angle), Some(x1), Some(y1)) = (f.height, f.angle, f.x1, f.y1) else {
        return cells; // random, gaussian
    };
    let reach = Slope::new(height.hi(), angle.lo(), units).reach();
    let margin = reach.min(f64::from(u32::MAX)).ceil() + 1.0;
    let side = |a: Param<u32>, b: Option<Param<u32>>, n: u32| -> u64 {
        let lo = f64::from(b.map_or(a.lo(), |b| b.lo().min(a.lo())));
        let hi = f64::from(b.map_or(a.hi(), |b| b.hi().max(a.hi())));
        let first = (lo - margin).max(0.0);
        let last = (hi + margin).min(f64::from(n) - 1.0);
        if last < first {
            0
        } else {
            (last - first) as u64 + 1
        }
    };
    side(x1, f.x2, grid.nx)
        .saturating_mul(side(y1, f.y2, grid.ny))
        .min(cells)
}

/// Largest slope table worth building; past it, cells are computed directly.
const TABLE_LIMIT: u64 = 4096;

/// How far a cell is from the obstacle, as an exact integer key: the squared
/// distance to a point, or `|v × w|` (the distance to a segment's line
/// times its length).
#[derive(Clone, Copy)]
enum Metric {
    Point,
    Segment { len2: i64, len: f64 },
}

impl Metric {
    /// The metric of a segment with direction `(vx, vy)`; a point when it is 0.
    fn of(vx: i64, vy: i64) -> Self {
        let len2 = vx * vx + vy * vy;
        if len2 == 0 {
            Metric::Point
        } else {
            Metric::Segment {
                len2,
                len: (len2 as f64).sqrt(),
            }
        }
    }
}

/// The steps of a cell by its distance key. Many cells share a key, so the
/// steps of the keys that can be above 0 are computed once into a table; the
/// formula per key is the same either way, so the result is too.
struct Profile<'a> {
    slope: &'a Slope,
    metric: Metric,
    /// `table[key]`; keys past its end are 0. `None` when too many keys can be
    /// above 0 (gentle or unbounded slopes): then every cell is computed.
    table: Option<Vec<u16>>,
}

impl<'a> Profile<'a> {
    fn new(slope: &'a Slope, metric: Metric) -> Self {
        // Past `last_key`, a cell is farther than both the flat top (√2/2) and
        // `reach` (plus a margin far above rounding), so its surface is below 0.
        let reach = slope.reach().max(1.0);
        let last_key = match metric {
            Metric::Point => (reach + 1.0) * (reach + 1.0),
            Metric::Segment { len, .. } => reach * len + 1.0,
        };
        let mut profile = Profile {
            slope,
            metric,
            table: None,
        };
        if last_key.is_finite() && last_key < TABLE_LIMIT as f64 {
            let keys = last_key.ceil() as u64 + 1;
            profile.table = Some((0..keys).map(|k| profile.compute(k) as u16).collect());
        }
        profile
    }

    #[inline]
    fn steps(&self, key: u64) -> u32 {
        match &self.table {
            Some(table) => table.get(key as usize).map_or(0, |&s| u32::from(s)),
            None => self.compute(key),
        }
    }

    fn compute(&self, key: u64) -> u32 {
        match self.metric {
            // The cell itself is the top: d ≤ √2/2 only at distance 0.
            Metric::Point if 2 * key <= 1 => self.slope.height,
            Metric::Point => self.slope.steps_at((key as f64).sqrt()),
            // d = |v × w| / |v| (eq. 2). `d ≤ √2/2` is tested exactly in
            // integers: cells at exactly √2/2 (beside a 45° wall) are top.
            Metric::Segment { len2, .. }
                if 2 * u128::from(key) * u128::from(key) <= len2 as u128 =>
            {
                self.slope.height
            }
            Metric::Segment { len, .. } => self.slope.steps_at(key as f64 / len),
        }
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
    let metric = Metric::of(vx, vy);
    let profile = Profile::new(slope, metric);

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
            let key = if len2 == 0 {
                (wx * wx + wy * wy) as u64
            } else {
                let dot = wx * vx + wy * vy;
                if dot < 0 || dot > len2 {
                    continue; // does not project onto the segment
                }
                (vx * wy - vy * wx).unsigned_abs()
            };
            let steps = profile.steps(key);
            let cell = &mut row[x as usize];
            if lowers {
                lower(cell, steps);
            } else {
                raise(cell, steps);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_angle_of_minus_zero_is_zero() {
        let units = Units {
            block_size: 0.1,
            step_height: 0.05,
        };
        let reach = Slope::new(3, -0.0, units).reach();
        assert!(reach.is_infinite() && reach > 0.0, "{reach}");
        let wall = |angle: &str| {
            let text =
                format!("# size: 8x6\ntype,height,angle,x1,y1,x2,y2\nwall,3,{angle},1,1,6,4\n");
            let scheme = crate::Scheme::from_csv(&text, None).unwrap();
            crate::generate::generate_at(&scheme, 0, 1, crate::Difficulty::new(1.0).unwrap())
        };
        assert_eq!(wall("-0").heightmap(), wall("0").heightmap());
    }

    #[test]
    fn slope_table_gives_what_the_formula_gives_for_every_key() {
        let units = [(0.1, 0.1), (0.1, 0.05), (0.2, 0.025), (0.05, 0.1)];
        let segments = [(0, 0), (1, 0), (4, 4), (3, 7), (40, 1), (25, 25)];
        for (block_size, step_height) in units {
            let units = Units {
                block_size,
                step_height,
            };
            for angle in [0.0, 1.0, 10.0, 30.0, 45.0, 60.0, 89.0, 90.0] {
                for height in [1, 3, 9] {
                    let slope = Slope::new(height, angle, units);
                    for (vx, vy) in segments {
                        let profile = Profile::new(&slope, Metric::of(vx, vy));
                        for key in 0..20_000 {
                            assert_eq!(
                                profile.steps(key),
                                profile.compute(key),
                                "key {key}, angle {angle}, H {height}, v ({vx}, {vy}), {units:?}"
                            );
                        }
                    }
                }
            }
        }
    }
}
