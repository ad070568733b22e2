//! Ramps: inclined planes over rectangles of cells, wedges lying on the
//! terrain (docs/schemes.md, "Ramps"). Their plane for height fields, the
//! staircase they leave in the heightmap for box sets, and their closed
//! wedge for the single mesh.
//!
//! A ramp is laid after every other obstacle (its row still fixes when its
//! corners are drawn), so pits never dig into it, as a plywood ramp laid on
//! a stepfield: the heightmap takes its inscribed staircase by the maximum
//! rule, and the targets that can draw a plane draw it over that staircase.

use serde::{Deserialize, Serialize};

use crate::globals::Grid;
use crate::heightmap::Heightmap;
use crate::obstacle::{DrawnObstacle, ObstacleKind};

/// One inclined plane of a world, as generated: its cells, which way it
/// climbs, and its rise after the difficulty.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Ramp {
    /// The cells it covers, inclusive corners `[x0, y0, x1, y1]`.
    pub cells: [u32; 4],
    /// Climbs along y (else along x).
    pub along_y: bool,
    /// Climbs toward larger coordinates (else toward smaller).
    pub ascending: bool,
    /// Steps from its foot to its top edge.
    pub rise: u32,
}

impl Ramp {
    /// The ramps of one drawn ramp obstacle on `grid`, rising `rise` steps
    /// (its height after the difficulty): one for a ramp, two for crossing
    /// ramps (the rectangle halved along its run, the first half climbing
    /// from the first corner's side, the second toward it; a rectangle one
    /// cell wide is one ramp). A ramp climbs from the first corner's side
    /// along the rectangle's longer side (along x when they are equal), as
    /// a flight of stairs does.
    ///
    /// # Panics
    /// If `obstacle` is no ramp or lacks its corners (validated schemes
    /// always have them).
    pub(crate) fn of(obstacle: &DrawnObstacle, grid: Grid, rise: u32) -> Vec<Ramp> {
        let (from, to) = (
            obstacle.p1.expect("a validated ramp has p1"),
            obstacle.p2.expect("a validated ramp has p2"),
        );
        let last = |v: u32, n: u32| v.min(n.saturating_sub(1));
        let cells = [
            last(from[0].min(to[0]), grid.nx),
            last(from[1].min(to[1]), grid.ny),
            last(from[0].max(to[0]), grid.nx),
            last(from[1].max(to[1]), grid.ny),
        ];
        let along_y = from[1].abs_diff(to[1]) > from[0].abs_diff(to[0]);
        let axis = usize::from(along_y);
        let ascending = to[axis] >= from[axis];
        let ramp = Ramp {
            cells,
            along_y,
            ascending,
            rise,
        };
        match obstacle.kind {
            ObstacleKind::Ramp => vec![ramp],
            ObstacleKind::CrossingRamps => {
                // Across the run: the other axis's cells, split in two.
                let across = 1 - axis;
                let (lo, hi) = (cells[across], cells[across + 2]);
                if hi == lo {
                    return vec![ramp];
                }
                // The first half the larger by a cell when they cannot be equal.
                let split = lo + (hi - lo) / 2 + 1;
                let (mut first, mut second) = (ramp, ramp);
                first.cells[across + 2] = split - 1;
                second.cells[across] = split;
                second.ascending = !ascending;
                vec![first, second]
            }
            other => panic!("{other} is no ramp"),
        }
    }

    /// Cells along its climb.
    pub fn run(&self) -> u32 {
        let axis = usize::from(self.along_y);
        self.cells[axis + 2] - self.cells[axis] + 1
    }

    /// Cell `(x, y)`'s place along the climb: 0 at the foot's row of cells.
    fn index(&self, x: u32, y: u32) -> u32 {
        let axis = usize::from(self.along_y);
        let at = [x, y][axis];
        if self.ascending {
            at - self.cells[axis]
        } else {
            self.cells[axis + 2] - at
        }
    }

    /// Cells it covers.
    pub fn cell_count(&self) -> u64 {
        let [x0, y0, x1, y1] = self.cells;
        u64::from(x1 - x0 + 1) * u64::from(y1 - y0 + 1)
    }

    /// Whether cell `(x, y)` lies under it.
    pub fn covers(&self, x: u32, y: u32) -> bool {
        let [x0, y0, x1, y1] = self.cells;
        (x0..=x1).contains(&x) && (y0..=y1).contains(&y)
    }

    /// The steps it leaves in cell `(x, y)` of its rectangle: the highest
    /// whole step not above its plane anywhere on the cell,
    /// `floor(i·rise / run)` for the `i`-th cell from the foot, so the
    /// staircase of a box set lies under the plane, never through it.
    pub fn steps_at(&self, x: u32, y: u32) -> u32 {
        let (i, run, rise) = (
            u64::from(self.index(x, y)),
            u64::from(self.run()),
            u64::from(self.rise),
        );
        // In u64: i·rise reaches 2³² · 2¹⁶.
        (i * rise / run) as u32
    }

    /// Raises the cells it covers to its staircase (the maximum rule).
    pub(crate) fn stamp(&self, map: &mut Heightmap) {
        let [x0, y0, x1, y1] = self.cells;
        for y in y0..=y1 {
            let row = map.row_mut(y);
            for x in x0..=x1 {
                let cell = &mut row[x as usize];
                *cell = (*cell).max(self.steps_at(x, y) as u16);
            }
        }
    }

    /// The fraction of its rise its plane has at a point `(u, v)` in cell
    /// units (the grid's frame divided by the block size), 0 at the foot
    /// edge and 1 at the top edge; the point lies over its rectangle.
    pub fn fraction_at(&self, u: f64, v: f64) -> f64 {
        let axis = usize::from(self.along_y);
        let at = [u, v][axis];
        let (lo, hi) = (
            f64::from(self.cells[axis]),
            f64::from(self.cells[axis + 2]) + 1.0,
        );
        let t = if self.ascending { at - lo } else { hi - at };
        (t / f64::from(self.run())).clamp(0.0, 1.0)
    }

    /// Its plane's height in metres at `(u, v)` (cell units), over a
    /// terrain of `base` and `step_height`.
    pub fn height_at(&self, u: f64, v: f64, base: f64, step_height: f64) -> f64 {
        base + f64::from(self.rise) * step_height * self.fraction_at(u, v)
    }

    /// Its wedge's corners in metres, for blocks of `block_size` on a
    /// terrain of `base` and `step_height`: its rectangle's four on the
    /// ground, then those on its plane above the ground. A convex solid:
    /// their hull is the wedge.
    pub fn wedge_corners(&self, block_size: f64, base: f64, step_height: f64) -> Vec<[f64; 3]> {
        let [x0, y0, x1, y1] = self.cells.map(f64::from);
        let corners = [
            (x0, y0),
            (x1 + 1.0, y0),
            (x1 + 1.0, y1 + 1.0),
            (x0, y1 + 1.0),
        ];
        let ground = corners.map(|(u, v)| [u * block_size, v * block_size, 0.0]);
        let plane = corners.into_iter().filter_map(|(u, v)| {
            let z = self.height_at(u, v, base, step_height);
            (z > 0.0).then_some([u * block_size, v * block_size, z])
        });
        ground.into_iter().chain(plane).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn drawn(kind: ObstacleKind, p1: [u32; 2], p2: [u32; 2]) -> DrawnObstacle {
        DrawnObstacle {
            kind,
            height: 4,
            angle: None,
            p1: Some(p1),
            p2: Some(p2),
            sigma: None,
            tread: None,
        }
    }

    const GRID: Grid = Grid {
        nx: 10,
        ny: 10,
        frame_period: None,
    };

    #[test]
    fn a_ramp_climbs_from_its_first_corner_along_the_longer_side() {
        let [r] = Ramp::of(&drawn(ObstacleKind::Ramp, [7, 1], [0, 2]), GRID, 4)[..] else {
            panic!("one ramp");
        };
        assert_eq!(r.cells, [0, 1, 7, 2]);
        assert!(!r.along_y && !r.ascending);
        assert_eq!(r.run(), 8);
        // From x = 7 (the foot) down to x = 0: floor(i·4/8).
        let steps: Vec<u32> = (0..8).rev().map(|x| r.steps_at(x, 1)).collect();
        assert_eq!(steps, [0, 0, 1, 1, 2, 2, 3, 3]);
        assert!((r.fraction_at(8.0, 1.5)).abs() < 1e-12);
        assert!((r.fraction_at(0.0, 1.5) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn crossing_ramps_halve_the_rectangle_and_climb_opposite_ways() {
        let ramps = Ramp::of(&drawn(ObstacleKind::CrossingRamps, [2, 0], [4, 9]), GRID, 3);
        assert_eq!(ramps.len(), 2);
        assert_eq!(ramps[0].cells, [2, 0, 3, 9]);
        assert_eq!(ramps[1].cells, [4, 0, 4, 9]);
        assert!(ramps[0].along_y && ramps[0].ascending && !ramps[1].ascending);
        let one = Ramp::of(&drawn(ObstacleKind::CrossingRamps, [2, 0], [2, 9]), GRID, 3);
        assert_eq!(one.len(), 1, "a rectangle one cell wide is one ramp");
    }
}
