//! How each obstacle changes the heightmap (docs/schemes.md).
//!
//! Every obstacle yields a height per cell, quantised to whole steps, which is
//! combined with the map by the maximum rule (raising obstacles) or subtracted
//! with a floor at 0 (pit, long pit, pyramid pit).

use crate::globals::Grid;
use crate::heightmap::Heightmap;
use crate::obstacle::{DrawnObstacle, Obstacle, ObstacleKind};
use crate::param::Param;
use crate::rng::{GaussianTables, WorldRng};

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
    tables: &mut GaussianTables,
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
            let normal = tables.get(height, sigma);
            let (mut words, mut values) = ([0u32; CHUNK], [0u32; CHUNK]);
            for cells in map.cells_mut().chunks_mut(CHUNK) {
                let (words, values) = (&mut words[..cells.len()], &mut values[..cells.len()]);
                rng.fill_words(words);
                normal.fill_values(words, values);
                cells
                    .iter_mut()
                    .zip(values.iter())
                    .for_each(|(c, &v)| raise(c, v));
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
        // Laid by `Ramp::stamp`, after every other obstacle and the
        // difficulty: nothing in table order.
        ObstacleKind::Ramp | ObstacleKind::CrossingRamps => {}
        ObstacleKind::Stairs | ObstacleKind::Pyramid | ObstacleKind::PyramidPit => {
            let from = obstacle.p1.expect("validated stairs and pyramids have p1");
            let to = obstacle.p2.expect("validated stairs and pyramids have p2");
            let rect = Rect::new(from, to, map.nx(), map.ny());
            let lowers = obstacle.kind.lowers();
            // A flight's steps, or a pyramid's by its tread.
            let tread = (obstacle.kind != ObstacleKind::Stairs)
                .then(|| obstacle.tread.expect("a validated pyramid has a tread"));
            let steps = |x: u32, y: u32| match tread {
                None => flight_steps(height, from, to, x, y),
                Some(tread) => pyramid_steps(height, tread, rect, x, y),
            };
            // `Rect::new` kept the corners on the grid.
            for y in rect.y0..=rect.y1 {
                let row = map.row_mut(y);
                for x in rect.x0..=rect.x1 {
                    let cell = &mut row[x as usize];
                    if lowers {
                        lower(cell, steps(x, y));
                    } else {
                        raise(cell, steps(x, y));
                    }
                }
            }
        }
    }
}

/// The cells of a stairs' or pyramid's rectangle: its two corners' box,
/// inclusive (the corners lie in the grid: `Scheme::new` checks them).
#[derive(Debug, Clone, Copy)]
struct Rect {
    x0: u32,
    y0: u32,
    x1: u32,
    y1: u32,
}

impl Rect {
    fn new(a: [u32; 2], b: [u32; 2], nx: u32, ny: u32) -> Rect {
        let last = |v: u32, n: u32| v.min(n.saturating_sub(1));
        Rect {
            x0: last(a[0].min(b[0]), nx),
            y0: last(a[1].min(b[1]), ny),
            x1: last(a[0].max(b[0]), nx),
            y1: last(a[1].max(b[1]), ny),
        }
    }
}

/// The steps of cell `(x, y)` of a straight flight of `height` steps over
/// the rectangle of corners `from` and `to`, climbing from `from`'s side to
/// `to`'s along the longer side (along x when they are equal): the `i`-th
/// cell of the run (of `run` cells, from 0 at `from`'s side) has
/// `ceil((i + 1)·H / run)` steps, so the last tread is `H` and each riser
/// is `H / run` steps, rounded.
fn flight_steps(height: u32, from: [u32; 2], to: [u32; 2], x: u32, y: u32) -> u32 {
    let (dx, dy) = (from[0].abs_diff(to[0]), from[1].abs_diff(to[1]));
    let (i, run) = if dx >= dy {
        (x.abs_diff(from[0]), dx + 1)
    } else {
        (y.abs_diff(from[1]), dy + 1)
    };
    // In u64: (i + 1)·H reaches 2³² · 2¹⁶.
    let (i, run, h) = (u64::from(i), u64::from(run), u64::from(height));
    ((i + 1) * h).div_ceil(run) as u32
}

/// The steps of cell `(x, y)` of pyramid stairs of `height` steps over
/// `rect`: rings `tread` cells wide from the rectangle's edge in, the
/// outermost 1 step, each ring a step above the one around it, up to `H`
/// (a plateau at the top where the rectangle is wide enough).
fn pyramid_steps(height: u32, tread: u32, rect: Rect, x: u32, y: u32) -> u32 {
    let ring = (x - rect.x0)
        .min(rect.x1 - x)
        .min(y - rect.y0)
        .min(rect.y1 - y);
    (ring / tread.max(1) + 1).min(height)
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
/// on `grid`: every cell for a random or gaussian field (a gaussian's table
/// is priced with the scheme's, shared: `Scheme::generation_visits`); for a peak, pit,
/// wall or long pit the box around the span of its points widened by the
/// reach of its steepest-to-gentlest slope (highest height, lowest angle),
/// kept to the grid. What `check` budgets before it rebuilds a world.
pub(crate) fn visits(obstacle: &Obstacle, grid: Grid, units: Units) -> u64 {
    let f = obstacle.fields();
    let cells = u64::from(grid.nx) * u64::from(grid.ny);
    let rectangle = obstacle.kind().is_rectangle();
    if let (true, Some(x1), Some(y1), Some(x2), Some(y2)) = (rectangle, f.x1, f.y1, f.x2, f.y2) {
        // Stairs, pyramids and ramps: the box of their corners' ranges.
        let side = |a: Param<u32>, b: Param<u32>, n: u32| {
            let (lo, hi) = (
                a.lo().min(b.lo()),
                a.hi().max(b.hi()).min(n.saturating_sub(1)),
            );
            u64::from(hi.saturating_sub(lo)) + 1
        };
        return side(x1, x2, grid.nx)
            .saturating_mul(side(y1, y2, grid.ny))
            .min(cells);
    }
    let (Some(height), Some(angle), Some(x1), Some(y1)) = (f.height, f.angle, f.x1, f.y1) else {
        return cells; // random
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
            profile.table = Some(profile.table_of(last_key.ceil() as u64 + 1));
        }
        profile
    }

    /// `compute(key)` for every key below `keys`. The steps never grow
    /// with the key (every operation of the formula is monotone: sqrt,
    /// division and multiplication by positive numbers, floor, min), so the
    /// table is a few runs of equal values; the end of each is found by
    /// bisection — a few dozen evaluations instead of one per key, the same
    /// values (tested key by key).
    fn table_of(&self, keys: u64) -> Vec<u16> {
        let mut table = Vec::with_capacity(keys as usize);
        let mut key = 0;
        while key < keys {
            let steps = self.compute(key);
            // compute(lo) == steps; hi is past the run (or the end).
            let (mut lo, mut hi) = (key, keys);
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if self.compute(mid) == steps {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            table.resize(hi as usize, steps as u16);
            key = hi;
        }
        table
    }

    /// The cells of row `wy` (relative to the obstacle's first point) that
    /// can get steps, as a range of `wx`: those whose centre projects onto
    /// the segment and whose key is inside the table. Every other cell gets
    /// 0 steps, which changes nothing, so skipping them changes no result;
    /// a diagonal wall's box is mostly such cells. `None`: no cell.
    /// Without a table, every projecting cell.
    fn row_span(&self, wy: i64, v: (i64, i64), len2: i64) -> Option<(i64, i64)> {
        let (vx, vy) = v;
        let full = (i64::MIN, i64::MAX);
        let keys = self.table.as_ref().map(|t| t.len() as i64);
        if len2 == 0 {
            // key = wx² + wy² < keys.
            let Some(keys) = keys else { return Some(full) };
            let room = keys - 1 - wy * wy;
            let r = u64::try_from(room).ok()?.isqrt() as i64;
            return Some((-r, r));
        }
        // 0 ≤ wx·vx + wy·vy ≤ len2: the centre projects onto the segment.
        let (a0, a1) = multiples_within(vx, -wy * vy, len2 - wy * vy)?;
        let Some(keys) = keys else {
            return Some((a0, a1));
        };
        // key = |vx·wy − vy·wx| < keys.
        let (b0, b1) = multiples_within(vy, vx * wy - (keys - 1), vx * wy + (keys - 1))?;
        let span = (a0.max(b0), a1.min(b1));
        (span.0 <= span.1).then_some(span)
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
        let wy = y - y0;
        let Some((first, last)) = profile.row_span(wy, (vx, vy), len2) else {
            continue;
        };
        let xs = (*x_range.start()).max(x0.saturating_add(first))
            ..=(*x_range.end()).min(x0.saturating_add(last));
        let row = map.row_mut(y as u32);
        for x in xs {
            let wx = x - x0;
            let key = if len2 == 0 {
                (wx * wx + wy * wy) as u64
            } else {
                debug_assert!((0..=len2).contains(&(wx * vx + wy * vy)), "projects");
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

/// The integers `w` with `lo ≤ a·w ≤ hi`, as `(first, last)`: every
/// integer when `a = 0` and `lo ≤ 0 ≤ hi`; `None` when there are none.
fn multiples_within(a: i64, lo: i64, hi: i64) -> Option<(i64, i64)> {
    let (a, lo, hi) = if a < 0 { (-a, -hi, -lo) } else { (a, lo, hi) };
    let (first, last) = if a == 0 {
        if lo > 0 || hi < 0 {
            return None;
        }
        (i64::MIN, i64::MAX)
    } else {
        // ceil(lo / a), floor(hi / a) for a > 0.
        (-(-lo).div_euclid(a), hi.div_euclid(a))
    };
    (first <= last).then_some((first, last))
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
    fn multiples_within_are_exactly_the_solutions() {
        for a in -5i64..=5 {
            for lo in -12i64..=12 {
                for hi in -12i64..=12 {
                    let span = multiples_within(a, lo, hi);
                    for w in -40i64..=40 {
                        let solves = (lo..=hi).contains(&(a * w));
                        let inside = span.is_some_and(|(f, l)| (f..=l).contains(&w));
                        assert_eq!(solves, inside, "a {a}, [{lo}, {hi}], w {w}: {span:?}");
                    }
                }
            }
        }
    }

    /// Every cell a row span leaves out projects off the segment or gets
    /// 0 steps; every cell it keeps projects onto it.
    #[test]
    fn row_spans_keep_every_cell_that_gets_steps() {
        let units = Units {
            block_size: 0.1,
            step_height: 0.05,
        };
        for angle in [5.0, 30.0, 45.0, 70.0, 90.0] {
            let slope = Slope::new(4, angle, units);
            for (vx, vy) in [(0, 0), (1, 0), (0, -3), (4, 4), (3, -7), (-9, 2), (25, 1)] {
                let len2 = vx * vx + vy * vy;
                let profile = Profile::new(&slope, Metric::of(vx, vy));
                for wy in -40i64..=40 {
                    let span = profile.row_span(wy, (vx, vy), len2);
                    for wx in -60i64..=60 {
                        let dot = wx * vx + wy * vy;
                        let projects = len2 == 0 || (0..=len2).contains(&dot);
                        let key = if len2 == 0 {
                            (wx * wx + wy * wy) as u64
                        } else {
                            (vx * wy - vy * wx).unsigned_abs()
                        };
                        let kept = span.is_some_and(|(f, l)| (f..=l).contains(&wx));
                        let case = format!("angle {angle}, v ({vx}, {vy}), w ({wx}, {wy})");
                        if kept {
                            assert!(projects, "{case}");
                        } else {
                            assert!(!projects || profile.compute(key) == 0, "{case}");
                        }
                    }
                }
            }
        }
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
