//! Where a robot may start on a heightmap: the highest top under a disc
//! (spawn origins) and discs that are flat within a few steps (flat
//! patches, after Isaac Lab's `FlatPatchSamplingCfg`). Everything here is
//! in cell units: cell `(x, y)` covers `[x, x+1] × [y, y+1]`.

use crate::heightmap::Heightmap;
use crate::terrain::Terrain;

/// How far, in cells, a disc may miss a cell and still touch it, or poke out
/// of a region and still be inside: radii come in metres, and 0.25 m / 0.1 m
/// is 2.4999999999999996 cells in f64, so a disc meant to reach a cell's
/// edge exactly would otherwise miss it.
const RADIUS_SLACK_CELLS: f64 = 1e-9;

/// The radius, metres, of the disc whose highest top a spawn origin stands
/// on when the user names none (an atlas's tiles, every environment of
/// [`EnvTerrains`](crate::EnvTerrains), `Terrain.spawn_origin` in Python):
/// the footprint of a quadruped the size of a Unitree Go1.
pub const DEFAULT_SPAWN_RADIUS: f64 = 0.3;

/// The radius, metres, of a flat patch when the user names none.
pub const DEFAULT_PATCH_RADIUS: f64 = 0.3;

/// The radius rule, for every radius a user gives (spawn origins, flat
/// patches; the command line, Python, atlases and env pools): a finite
/// length of 0 m or more. The error says what it must be.
pub fn check_radius(radius: f64) -> Result<f64, String> {
    if radius.is_finite() && radius >= 0.0 {
        Ok(radius)
    } else {
        Err(format!("must be a length of 0 m or more, got {radius}"))
    }
}

/// [`check_radius`] as a range of the option tables (`spawn_radius`).
#[derive(Debug, Clone, Copy)]
pub struct Radius;

impl crate::global_range::GlobalRange<f64> for Radius {
    fn check(&self, value: &f64) -> Result<(), String> {
        check_radius(*value).map(|_| ())
    }
}

impl crate::global_range::RangeText for Radius {
    fn describe(&self) -> &'static str {
        "a length of 0 m or more"
    }

    fn outside(&self) -> Option<&'static str> {
        Some("-1")
    }
}

impl Terrain {
    /// Every cell of the terrain as a region.
    pub fn region(&self) -> Region {
        let grid = self.grid();
        Region {
            x0: 0,
            y0: 0,
            nx: grid.nx,
            ny: grid.ny,
        }
    }

    /// A spawn point `[x, y, z]` in metres for `region`: its centre, on
    /// the highest top within `radius` metres of it, so a body whose
    /// footprint fits in that disc starts inside no block.
    pub fn spawn_origin(&self, region: Region, radius: f64) -> [f64; 3] {
        let s = self.block_size();
        let centre = region.centre();
        let top = highest_under_disc(self.heightmap(), centre, radius / s);
        [
            centre[0] * s,
            centre[1] * s,
            self.top_under(top, centre, radius / s),
        ]
    }

    /// Up to `count` flat patches of `region` ([`flat_patches`]) as
    /// `[x, y, z]` in metres, z the highest top under each disc of `radius`
    /// metres.
    pub fn flat_patches(
        &self,
        region: Region,
        count: u32,
        radius: f64,
        max_step: u16,
    ) -> Vec<[f64; 3]> {
        let s = self.block_size();
        flat_patches(self.heightmap(), region, count, radius / s, max_step)
            .into_iter()
            .map(|p| {
                [
                    p.at[0] * s,
                    p.at[1] * s,
                    self.top_under(p.top, p.at, radius / s),
                ]
            })
            .collect()
    }

    /// The highest point of a ramp's plane over the disc of radius `r`
    /// around `p` (both in cells), metres; `None` where no ramp lies under
    /// it. Planes are highest at the disc's farthest point along a climb,
    /// kept to the ramp's rectangle.
    pub fn highest_plane_under_disc(&self, p: [f64; 2], r: f64) -> Option<f64> {
        self.ramps()
            .iter()
            .filter(|ramp| {
                let [x0, y0, x1, y1] = ramp.cells.map(f64::from);
                // The rectangle [x0, x1 + 1] × [y0, y1 + 1] meets the disc.
                let dx = (x0 - p[0]).max(p[0] - (x1 + 1.0)).max(0.0);
                let dy = (y0 - p[1]).max(p[1] - (y1 + 1.0)).max(0.0);
                dx * dx + dy * dy < r * r || (dx == 0.0 && dy == 0.0)
            })
            .map(|ramp| {
                let axis = usize::from(ramp.along_y);
                let mut far = p;
                far[axis] += if ramp.ascending { r } else { -r };
                let [x0, y0, x1, y1] = ramp.cells.map(f64::from);
                let far = [far[0].clamp(x0, x1 + 1.0), far[1].clamp(y0, y1 + 1.0)];
                ramp.height_at(far[0], far[1], self.base(), self.step_height())
            })
            .reduce(f64::max)
    }

    /// The top of a cell of `h` steps, metres, or a ramp's plane where it
    /// is higher under the disc of radius `r` around `p` (cells): a body
    /// set there starts inside no block and no ramp.
    fn top_under(&self, h: u16, p: [f64; 2], r: f64) -> f64 {
        let cells = self.base() + f64::from(h) * self.step_height();
        self.highest_plane_under_disc(p, r)
            .map_or(cells, |plane| plane.max(cells))
    }
}

/// A rectangle of cells: `x0 ≤ x < x0 + nx`, `y0 ≤ y < y0 + ny`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// Columns.
    pub nx: u32,
    /// Rows.
    pub ny: u32,
}

impl Region {
    /// The centre, in cell units.
    pub fn centre(&self) -> [f64; 2] {
        [
            f64::from(self.x0) + f64::from(self.nx) / 2.0,
            f64::from(self.y0) + f64::from(self.ny) / 2.0,
        ]
    }
}

/// A point of a flat patch: its position in cell units and the highest
/// height (steps) under its disc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Patch {
    /// x, y in cell units.
    pub at: [f64; 2],
    /// The highest cell under the disc, in steps.
    pub top: u16,
}

/// The cells of the map that a disc of radius `r` around `p` touches
/// (boundary included: a disc of radius 0 on a cell corner touches the four
/// cells that meet there), as `(y, x_first, x_last)` per row.
fn disc_rows(map: &Heightmap, p: [f64; 2], r: f64) -> impl Iterator<Item = (u32, u32, u32)> {
    // The whole map, not a tile: a disc on a tile's edge touches its
    // neighbour's cells too, and a body there stands on both.
    let (nx, ny) = (map.nx(), map.ny());
    let r = r + RADIUS_SLACK_CELLS;
    // Index of the first and last cell whose band [i, i+1] meets [lo, hi],
    // kept to the map.
    let span = |lo: f64, hi: f64, first: u32, n: u32| -> (u32, u32) {
        let a = ((lo.ceil() - 1.0).max(f64::from(first))) as u32;
        let b = (hi.floor().max(0.0) as u32).min(first + n - 1);
        (a, b)
    };
    let (y_first, y_last) = span(p[1] - r, p[1] + r, 0, ny);
    (y_first..=y_last).filter_map(move |y| {
        // Distance from p to the row's band [y, y+1] along y.
        let dy = (f64::from(y) - p[1]).max(p[1] - f64::from(y + 1)).max(0.0);
        let left = r * r - dy * dy;
        if left < 0.0 {
            return None;
        }
        let half = left.sqrt();
        let (x_first, x_last) = span(p[0] - half, p[0] + half, 0, nx);
        (x_first <= x_last).then_some((y, x_first, x_last))
    })
}

/// The highest cell touched by the disc of radius `r` (cells)
/// around `p`: a body whose footprint fits in the disc, set on this top,
/// starts inside no block.
pub fn highest_under_disc(map: &Heightmap, p: [f64; 2], r: f64) -> u16 {
    disc_rows(map, p, r)
        .flat_map(|(y, x_lo, x_hi)| map.row(y)[x_lo as usize..=x_hi as usize].iter().copied())
        .max()
        .unwrap_or(0)
}

/// Lowest and highest cell under the disc, stopping early once they are
/// more than `max_step` apart (`None` then).
fn flat_under_disc(map: &Heightmap, p: [f64; 2], r: f64, max_step: u16) -> Option<u16> {
    let (mut lo, mut hi) = (u16::MAX, 0u16);
    for (y, x_lo, x_hi) in disc_rows(map, p, r) {
        for &h in &map.row(y)[x_lo as usize..=x_hi as usize] {
            lo = lo.min(h);
            hi = hi.max(h);
            if hi - lo > max_step {
                return None;
            }
        }
    }
    Some(hi)
}

/// Up to `count` flat patches in `region`: centres of cells whose disc of
/// radius `r` (cells) lies inside the region and touches only cells within
/// `max_step` steps of each other.
///
/// Deterministic and spread out: the first is the candidate nearest the
/// region's centre, each next the candidate farthest from those already
/// chosen (ties go to the first in row order, y then x). A region with
/// fewer candidates gives fewer patches.
pub fn flat_patches(
    map: &Heightmap,
    region: Region,
    count: u32,
    r: f64,
    max_step: u16,
) -> Vec<Patch> {
    if count == 0 || region.nx == 0 || region.ny == 0 {
        return Vec::new();
    }
    let mut candidates = Vec::new();
    for y in region.y0..region.y0 + region.ny {
        for x in region.x0..region.x0 + region.nx {
            let p = [f64::from(x) + 0.5, f64::from(y) + 0.5];
            let fits = r - RADIUS_SLACK_CELLS;
            let inside = p[0] - fits >= f64::from(region.x0)
                && p[0] + fits <= f64::from(region.x0 + region.nx)
                && p[1] - fits >= f64::from(region.y0)
                && p[1] + fits <= f64::from(region.y0 + region.ny);
            if !inside {
                continue;
            }
            if let Some(top) = flat_under_disc(map, p, r, max_step) {
                candidates.push(Patch { at: p, top });
            }
        }
    }
    farthest_points(&candidates, region, region.centre(), count as usize)
}

/// Greedy farthest-point sampling of `n` of `candidates` (cell centres of
/// `region`, in row order), starting from the one nearest `start`; ties go
/// to the earlier candidate.
///
/// The plain algorithm rescans every candidate after each pick: `n ×
/// candidates`, a minute for 10⁶ patches asked of a 400×400 tile. This one
/// gives the same picks in the same order, in about `candidates × log n`:
/// after a pick at distance² `S` from the others, only candidates nearer
/// it than `√S` can get closer to the chosen set (every other is at most
/// `S` from it already), so only the square of cells around the pick is
/// visited; the next pick comes off a max-heap of (score, earliest index)
/// whose stale entries are skipped. Every distance² is exact in `f64`
/// (coordinates are halves), so the comparisons are those of the plain
/// algorithm.
fn farthest_points(candidates: &[Patch], region: Region, start: [f64; 2], n: usize) -> Vec<Patch> {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;

    let n = n.min(candidates.len());
    let dist2 = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
    let mut chosen: Vec<Patch> = Vec::with_capacity(n);
    if n == 0 {
        return chosen;
    }
    // The first pick: nearest `start`, the earliest of equals.
    let first = (0..candidates.len())
        .min_by(|&i, &j| dist2(candidates[i].at, start).total_cmp(&dist2(candidates[j].at, start)))
        .expect("there are candidates");
    // Each region cell's candidate, to visit the square around a pick.
    let cell = |p: &Patch| {
        let (x, y) = (p.at[0] as u32 - region.x0, p.at[1] as u32 - region.y0);
        (y as usize) * region.nx as usize + x as usize
    };
    let mut at_cell = vec![u32::MAX; region.nx as usize * region.ny as usize];
    for (i, c) in candidates.iter().enumerate() {
        at_cell[cell(c)] = i as u32;
    }
    // Distance² to the nearest chosen point; exact integers after the
    // first pick, so their bits order them.
    let pick = candidates[first];
    let mut score: Vec<f64> = candidates.iter().map(|c| dist2(c.at, pick.at)).collect();
    let mut taken = vec![false; candidates.len()];
    taken[first] = true;
    chosen.push(pick);
    let key = |s: f64| s.to_bits();
    let mut heap: BinaryHeap<(u64, Reverse<u32>)> = score
        .iter()
        .enumerate()
        .filter(|&(i, _)| !taken[i])
        .map(|(i, &s)| (key(s), Reverse(i as u32)))
        .collect();
    while chosen.len() < n {
        let Some((k, Reverse(i))) = heap.pop() else {
            break;
        };
        let i = i as usize;
        if taken[i] || k != key(score[i]) {
            continue; // picked already, or a score since lowered
        }
        taken[i] = true;
        let pick = candidates[i];
        chosen.push(pick);
        let reach = score[i].sqrt().ceil() as i64;
        let (px, py) = (
            i64::from(pick.at[0] as u32 - region.x0),
            i64::from(pick.at[1] as u32 - region.y0),
        );
        let (nx, ny) = (i64::from(region.nx), i64::from(region.ny));
        for y in (py - reach).max(0)..=(py + reach).min(ny - 1) {
            for x in (px - reach).max(0)..=(px + reach).min(nx - 1) {
                let j = at_cell[(y * nx + x) as usize];
                if j == u32::MAX || taken[j as usize] {
                    continue;
                }
                let j = j as usize;
                let d = dist2(candidates[j].at, pick.at);
                if d < score[j] {
                    score[j] = d;
                    heap.push((key(d), Reverse(j as u32)));
                }
            }
        }
    }
    chosen
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // cell centres are exact halves
mod tests {
    use super::*;

    fn map(rows: &[&[u16]]) -> Heightmap {
        let text: String = rows
            .iter()
            .map(|r| r.iter().map(u16::to_string).collect::<Vec<_>>().join(",") + "\n")
            .collect();
        Heightmap::from_csv(&text).unwrap()
    }

    const ALL: Region = Region {
        x0: 0,
        y0: 0,
        nx: 4,
        ny: 4,
    };

    #[test]
    fn a_point_disc_on_a_corner_touches_its_four_cells() {
        let m = map(&[&[0, 0, 0, 0], &[0, 1, 2, 0], &[0, 3, 4, 0], &[0, 0, 0, 9]]);
        assert_eq!(highest_under_disc(&m, [2.0, 2.0], 0.0), 4);
        assert_eq!(highest_under_disc(&m, [1.5, 1.5], 0.4), 1);
        // Radius 1 from the centre of (1, 1) reaches (2, 2)'s corner? No:
        // its nearest point is (2, 2), √0.5 ≈ 0.71 away — yes, it does.
        assert_eq!(highest_under_disc(&m, [1.5, 1.5], 1.0), 4);
        assert_eq!(highest_under_disc(&m, [1.5, 1.5], 0.7), 3);
    }

    #[test]
    fn patches_are_flat_inside_and_spread() {
        let m = map(&[&[0, 0, 0, 5], &[0, 0, 0, 5], &[0, 0, 0, 5], &[1, 0, 0, 5]]);
        let patches = flat_patches(&m, ALL, 10, 0.5, 0);
        assert!(!patches.is_empty());
        for p in &patches {
            let (x, y) = (p.at[0] as usize, p.at[1] as usize);
            assert!(x < 3 && !(x == 0 && y == 3), "{p:?}");
            assert_eq!(p.top, 0);
        }
        // Nearest the centre first, then the farthest from it.
        assert_eq!(patches[0].at, [1.5, 1.5]);
        let with_step = flat_patches(&m, ALL, 100, 0.5, 1);
        assert!(with_step.iter().any(|p| p.at == [0.5, 3.5]));
        assert!(with_step.iter().all(|p| p.at[0] < 3.0));
    }

    /// The plain greedy farthest-point sampling, the reference the fast
    /// one must match pick for pick.
    fn farthest_points_plain(candidates: &[Patch], start: [f64; 2], n: usize) -> Vec<Patch> {
        let dist2 = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
        let mut chosen: Vec<Patch> = Vec::new();
        let mut taken = vec![false; candidates.len()];
        let mut score: Vec<f64> = candidates.iter().map(|c| -dist2(c.at, start)).collect();
        while chosen.len() < n {
            let mut best: Option<usize> = None;
            for (i, &s) in score.iter().enumerate() {
                if !taken[i] && best.is_none_or(|b| s > score[b]) {
                    best = Some(i);
                }
            }
            let Some(i) = best else { break };
            taken[i] = true;
            let pick = candidates[i];
            for (c, s) in candidates.iter().zip(score.iter_mut()) {
                let d = dist2(c.at, pick.at);
                *s = if chosen.is_empty() { d } else { s.min(d) };
            }
            chosen.push(pick);
        }
        chosen
    }

    #[test]
    fn the_fast_sampling_picks_what_the_plain_one_picks() {
        // Candidates with holes, in regions of odd and even sides, offset.
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            seed >> 33
        };
        for (x0, y0, nx, ny) in [(0, 0, 7, 5), (3, 2, 16, 16), (1, 4, 31, 9), (0, 0, 1, 1)] {
            let region = Region { x0, y0, nx, ny };
            for density in [1, 2, 4] {
                let candidates: Vec<Patch> = (y0..y0 + ny)
                    .flat_map(|y| (x0..x0 + nx).map(move |x| (x, y)))
                    .filter(|_| next() % density == 0)
                    .map(|(x, y)| Patch {
                        at: [f64::from(x) + 0.5, f64::from(y) + 0.5],
                        top: 0,
                    })
                    .collect();
                for n in [0, 1, 2, 5, 40, 10_000] {
                    let fast = farthest_points(&candidates, region, region.centre(), n);
                    let plain = farthest_points_plain(&candidates, region.centre(), n);
                    assert_eq!(fast, plain, "{region:?} density {density} n {n}");
                }
            }
        }
    }

    #[test]
    fn a_disc_larger_than_the_region_gives_nothing() {
        let m = map(&[&[0, 0], &[0, 0]]);
        let region = Region {
            x0: 0,
            y0: 0,
            nx: 2,
            ny: 2,
        };
        assert!(flat_patches(&m, region, 3, 1.5, 0).is_empty());
        assert_eq!(flat_patches(&m, region, 9, 0.5, 0).len(), 4);
    }

    #[test]
    fn a_spawn_on_a_ramp_stands_on_its_plane_not_its_staircase() {
        // 10 cells rising 5 steps of 0.1 m along x: 0.05 m a cell.
        let scheme = crate::Scheme::from_csv(
            "# size: 10x10\ntype,height,angle,x1,y1,x2,y2\nramp,5,,0,0,9,9\n",
            None,
        )
        .unwrap();
        let terrain = crate::generate(&scheme, 0, 0);
        let region = terrain.region();
        // The centre (x = 5 cells), a disc of 0.1 m: its far point 6 cells along.
        let [x, _, z] = terrain.spawn_origin(region, 0.1);
        assert!((x - 0.5).abs() < 1e-12);
        assert!((z - 0.3).abs() < 1e-12, "{z}");
        // Without a radius, the plane under the centre.
        let [_, _, z] = terrain.spawn_origin(region, 0.0);
        assert!((z - 0.25).abs() < 1e-12, "{z}");
    }
}
