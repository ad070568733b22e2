//! Generating one world: draw the ranges, apply the obstacles in order, frame the pallets.

use crate::difficulty::{Difficulty, DifficultyRule, unit_offset};
use crate::globals::Grid;
use crate::heightmap::Heightmap;
use crate::limits::DEFAULT_SIGMA;
use crate::obstacle::{DrawnObstacle, Obstacle, ObstacleKind};
use crate::param::Param;
use crate::ramp::Ramp;
use crate::rng::WorldRng;
use crate::scheme::Scheme;
use crate::stamp::{self, Units};
use crate::terrain::Terrain;

/// Generates world `index` of a batch with base seed `seed` (docs/schemes.md).
///
/// The result depends on `(scheme, seed, index)` alone: not on how many worlds
/// are generated, in which order, or on which thread.
///
/// ```
/// let scheme = rse_core::Scheme::from_csv("# size: 5x5\ntype,height,angle,x1,y1\npeak,2,45,2,2\n", None)?;
/// let terrain = rse_core::generate(&scheme, 0, 0);
/// assert_eq!(terrain.heightmap().get(2, 2), 2);
/// assert_eq!(terrain.heightmap().get(3, 2), 1);
/// # Ok::<(), rse_core::SchemeError>(())
/// ```
pub fn generate(scheme: &Scheme, seed: u64, index: u64) -> Terrain {
    generate_at(scheme, seed, index, Difficulty::FULL)
}

/// World `index` of seed `seed` at `difficulty`: the world [`generate`]
/// makes, with every non-frame height `h` scaled to `D·h` and rounded by
/// today's rule ([`DifficultyRule::Drawn`]). The obstacles drawn are the
/// same at every difficulty.
///
/// ```
/// use rse_core::{Difficulty, Scheme, generate_at};
/// let scheme = Scheme::from_csv("# size: 5x5\ntype,height,angle,x1,y1\npeak,4,45,2,2\n", None)?;
/// let half = generate_at(&scheme, 0, 0, Difficulty::new(0.5).unwrap());
/// assert_eq!(half.heightmap().get(2, 2), 2); // 4 steps: 2 at any offset
/// let low = generate_at(&scheme, 0, 0, Difficulty::new(0.01).unwrap());
/// assert_eq!(low.heightmap().get(2, 2), 1); // the highest cell stays
/// # Ok::<(), rse_core::SchemeError>(())
/// ```
pub fn generate_at(scheme: &Scheme, seed: u64, index: u64, difficulty: Difficulty) -> Terrain {
    generate_by(scheme, seed, index, difficulty, DifficultyRule::CURRENT)
}

/// World `index` of seed `seed` at `difficulty`, its heights rounded by
/// `rule`: [`generate_at`] for worlds written today, and for rebuilding a
/// world written by an older rule (its `rse.json` says which).
pub fn generate_by(
    scheme: &Scheme,
    seed: u64,
    index: u64,
    difficulty: Difficulty,
    rule: DifficultyRule,
) -> Terrain {
    let globals = scheme.globals();
    let grid = scheme.grid();
    let units = Units {
        block_size: globals.block_size,
        step_height: globals.step_height,
    };
    let mut rng = WorldRng::new(seed, index);
    let mut heightmap = Heightmap::zeros(grid.nx, grid.ny);
    let mut drawn = Vec::with_capacity(scheme.obstacles().len());
    let mut tables = crate::rng::GaussianTables::default();
    for obstacle in scheme.obstacles() {
        let resolved = draw(obstacle, &mut rng);
        // Ramps are laid after every other obstacle, on the scaled map.
        stamp::apply(&resolved, &mut heightmap, &mut rng, units, &mut tables);
        drawn.push(resolved);
    }
    // Before the frames, which stay one step at any difficulty; the
    // offset the cells were rounded with, which a ramp's rise is too.
    let offset = (!difficulty.is_full()).then(|| match rule {
        DifficultyRule::Nearest => {
            heightmap
                .cells_mut()
                .iter_mut()
                .for_each(|h| *h = difficulty.scale(*h));
            0.5 // `Difficulty::scale`'s
        }
        DifficultyRule::Drawn => {
            // The next draw of the world's stream, after every obstacle's:
            // the same at every difficulty.
            let offset = unit_offset(rng.next_u32());
            scale_drawn(&mut heightmap, &grid, difficulty, offset);
            offset
        }
    });
    // A ramp's rise scales as a cell of its height does (heights are
    // validated to fit a cell), at least a step above D = 0 (a ramp is
    // never flat there, as no world with an obstacle is).
    let scaled = |h: u32| {
        offset.map_or(h, |o| {
            let rise = u32::from(difficulty.scale_offset(h as u16, o));
            if difficulty.get() > 0.0 {
                rise.max(h.min(1))
            } else {
                rise
            }
        })
    };
    let ramps: Vec<Ramp> = drawn
        .iter()
        .filter(|d| d.kind.is_ramp())
        .flat_map(|d| Ramp::of(d, grid, scaled(d.height)))
        .collect();
    for ramp in &ramps {
        ramp.stamp(&mut heightmap);
    }
    if let Some(period) = grid.frame_period {
        // Frames are exactly one step, whatever the obstacles did (docs/schemes.md).
        for y in 0..grid.ny {
            let row = heightmap.row_mut(y);
            if y % period == 0 {
                row.fill(1);
            } else {
                row.iter_mut().step_by(period as usize).for_each(|h| *h = 1);
            }
        }
    }
    Terrain::new(grid, heightmap, globals, (seed, index), difficulty, drawn).with_ramps(ramps)
}

/// [`DifficultyRule::Drawn`]: every cell `floor(D·h + offset)`, and the
/// highest non-frame cell (the first in row order) at least one step when
/// `D > 0`, so a world that has any obstacle is never flat above `D = 0`.
fn scale_drawn(heightmap: &mut Heightmap, grid: &Grid, difficulty: Difficulty, offset: f64) {
    let nx = grid.nx as usize;
    let mut highest: Option<(usize, u16)> = None;
    for (i, h) in heightmap.cells_mut().iter_mut().enumerate() {
        // usize → u32 is exact: the grid's cells are indexed by u32 pairs.
        let (x, y) = ((i % nx) as u32, (i / nx) as u32);
        if *h > 0 && !grid.is_frame(x, y) && highest.is_none_or(|(_, top)| *h > top) {
            highest = Some((i, *h));
        }
        *h = difficulty.scale_offset(*h, offset);
    }
    if let Some((i, _)) = highest
        && difficulty.get() > 0.0
    {
        let cell = &mut heightmap.cells_mut()[i];
        *cell = (*cell).max(1);
    }
}

/// Resolves an obstacle's ranges in the fixed order x1, y1, x2, y2, height,
/// angle, sigma; fixed values draw nothing.
fn draw(obstacle: &Obstacle, rng: &mut WorldRng) -> DrawnObstacle {
    let f = obstacle.fields();
    let mut int = |p: Option<Param<u32>>| {
        p.map(|p| match p {
            Param::Fixed(v) => v,
            Param::Range(lo, hi) => rng.int_in(lo, hi),
        })
    };
    let p1 = int(f.x1).zip(int(f.y1)).map(<[u32; 2]>::from);
    let p2 = int(f.x2).zip(int(f.y2)).map(<[u32; 2]>::from);
    let height = int(f.height).expect("a validated obstacle has a height");
    let mut real = |p: Option<Param<f64>>| {
        p.map(|p| match p {
            Param::Fixed(v) => v,
            Param::Range(lo, hi) => rng.real_in(lo, hi),
        })
    };
    let angle = real(f.angle);
    let kind = obstacle.kind();
    // Only a gaussian may have a sigma (validated); it always gets one here.
    let sigma = real(f.sigma).or((kind == ObstacleKind::Gaussian).then_some(DEFAULT_SIGMA));
    // Drawn last, so the kinds before the stairs draw what they always did.
    let tread = f.tread.map(|p| match p {
        Param::Fixed(v) => v,
        Param::Range(lo, hi) => rng.int_in(lo, hi),
    });
    DrawnObstacle {
        kind,
        height,
        angle,
        p1,
        p2,
        sigma,
        tread,
    }
}
