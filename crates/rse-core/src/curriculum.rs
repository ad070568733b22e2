//! Checking a scheme as a curriculum: per-level statistics of its worlds
//! over many draws, and the levels that teach nothing (all flat, or no
//! higher than the level below). `rse-gen check-curriculum` and
//! `rse.check_curriculum` print and return this (docs/schemes.md,
//! "Checking a curriculum").

use std::collections::HashSet;
use std::hash::{DefaultHasher, Hash, Hasher};

use rayon::prelude::*;

use crate::difficulty::Difficulty;
use crate::generate::generate_at;
use crate::scheme::Scheme;
use crate::terrain::Terrain;

/// Levels of mjlab's terrain curriculum (`num_rows`), the default here.
pub const DEFAULT_LEVELS: u32 = 10;
/// Worlds drawn per level by default: enough for a share of flat worlds
/// to within a few per cent, and seconds for an 80×80 scheme.
pub const DEFAULT_DRAWS: u32 = 50;
/// At most this many levels or draws: a check, not a batch.
pub const MAX_LEVELS: u32 = 1000;
/// See [`MAX_LEVELS`].
pub const MAX_DRAWS: u32 = 100_000;

/// What to check: `levels` evenly spaced difficulties from 0 to 1 (level
/// `l` is `D = l/(levels − 1)`, as mjlab spaces its terrain levels), each
/// over worlds `0..draws` of `seed`: the same draws at every level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CurriculumOptions {
    /// Levels, at least 2.
    pub levels: u32,
    /// Worlds per level, at least 1.
    pub draws: u32,
    /// The base seed of the draws.
    pub seed: u64,
}

/// Seconds to two significant digits below 10 (a small check's estimate is
/// not "0 s"), whole above.
fn seconds_text(seconds: f64) -> String {
    if seconds >= 10.0 {
        format!("{seconds:.0}")
    } else {
        format!(
            "{:.*}",
            (1 - seconds.log10().floor() as i32).clamp(1, 6) as usize,
            seconds
        )
    }
}

/// Options out of range, named as the command line and Python name them.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurriculumOptionsError {
    /// Fewer than 2 levels or more than [`MAX_LEVELS`].
    #[error("levels {0}: expected 2 to {MAX_LEVELS}")]
    Levels(u32),
    /// No draws or more than [`MAX_DRAWS`].
    #[error("draws {0}: expected 1 to {MAX_DRAWS}")]
    Draws(u32),
    /// The check would cost more than its budget (priced before a world
    /// is generated: 1000 levels × 100,000 draws of 300×300 were ~72 h).
    #[error(
        "{levels} levels x {draws} worlds would take some {} s on one core, \
         over the budget of {} s: check fewer levels or draws, or allow more \
         (a budget of {factor:.1}x would do)",
        seconds_text(*.seconds),
        seconds_text(*.budget_seconds)
    )]
    OverBudget {
        /// Levels asked for.
        levels: u32,
        /// Worlds a level.
        draws: u32,
        /// The estimate, seconds on one core.
        seconds: f64,
        /// The budget, seconds on one core.
        budget_seconds: f64,
        /// The budget factor that would let it run.
        factor: f64,
    },
    /// Stopped before the end (Ctrl-C).
    #[error("interrupted")]
    Interrupted,
}

/// The work a curriculum check may cost under its default budget, in cell
/// visits ([`VISIT_NANOS`](crate::VISIT_NANOS) each on one core): the
/// budget of `check`'s rebuild, some 100 s.
pub const CURRICULUM_VISITS: u64 = crate::BUDGET_VISITS;

/// Measuring a generated world (heights, steps, slopes, its digest), per
/// cell: 100 worlds of random steps on 300×300 took 0.14 s in all, some 3
/// visits a cell with their generation (at 4 for the measure alone they
/// were priced twice that).
const STATS_VISITS_PER_CELL: u64 = 1;

impl CurriculumOptions {
    /// The options, refused out of range.
    pub fn validate(self) -> Result<Self, CurriculumOptionsError> {
        if !(2..=MAX_LEVELS).contains(&self.levels) {
            return Err(CurriculumOptionsError::Levels(self.levels));
        }
        if !(1..=MAX_DRAWS).contains(&self.draws) {
            return Err(CurriculumOptionsError::Draws(self.draws));
        }
        Ok(self)
    }

    /// The work of checking `scheme` so, in cell visits: every draw of
    /// every level generated ([`Scheme::generation_visits`]) and measured.
    pub fn visits(&self, scheme: &Scheme) -> u64 {
        let per_world = scheme
            .generation_visits()
            .saturating_add((scheme.grid().cells() as u64).saturating_mul(STATS_VISITS_PER_CELL));
        u64::from(self.levels)
            .saturating_mul(u64::from(self.draws))
            .saturating_mul(per_world)
    }

    /// The difficulty of `level`.
    ///
    /// # Panics
    /// Never: 0 is a difficulty.
    pub fn difficulty(&self, level: u32) -> Difficulty {
        let zero = Difficulty::new(0.0).expect("0 is a difficulty");
        Difficulty::lerp(zero, Difficulty::FULL, level, self.levels)
    }
}

/// One level's worlds, summarised. Heights and steps are in metres;
/// pallet frames are left out of every figure (they are the same at every
/// level).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelStats {
    /// The level, from 0.
    pub level: u32,
    /// Its difficulty.
    pub difficulty: Difficulty,
    /// Share of its worlds with no cell above 0, from 0 to 1.
    pub flat_share: f64,
    /// Mean cell height over every world: the figure that must rise.
    pub mean_height: f64,
    /// Mean height difference between neighbouring cells that differ:
    /// the typical step a robot meets (0 when every world is flat).
    pub mean_step: f64,
    /// Largest height difference between neighbouring cells.
    pub max_step: f64,
    /// Steepest slope between neighbouring cell centres, degrees:
    /// `atan(max_step / block_size)`.
    pub max_slope_deg: f64,
    /// Different heightmaps among the draws.
    pub distinct: u32,
}

/// A level that teaches nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum CurriculumProblem {
    /// Every world is flat even at difficulty 1: nothing to scale.
    #[error("every world is flat at difficulty 1: the scheme has no obstacle to scale")]
    FlatScheme,
    /// A level above 0 whose worlds are all flat.
    #[error("level {0} is dead: every world is flat")]
    Dead(u32),
    /// A level whose mean height is not above the level below's.
    #[error("level {0} is no higher than level {prev} (mean height)", prev = .0 - 1)]
    NotRising(u32),
}

/// The statistics of every level and the problems found.
#[derive(Debug, Clone, PartialEq)]
pub struct CurriculumReport {
    /// The options checked.
    pub options: CurriculumOptions,
    /// One entry per level, level 0 first.
    pub levels: Vec<LevelStats>,
    /// Empty when the curriculum holds.
    pub problems: Vec<CurriculumProblem>,
}

/// Checks `scheme` as a curriculum (see [`CurriculumOptions`]) under the
/// default budget, to the end. The same report on any number of threads.
pub fn check_curriculum(
    scheme: &Scheme,
    options: CurriculumOptions,
) -> Result<CurriculumReport, CurriculumOptionsError> {
    check_curriculum_within(scheme, options, 1.0, &|| false)
}

/// `visits` (what [`CurriculumOptions::visits`] prices: one scheme's, or
/// the sum of several checked in one run) held to `budget` times
/// [`CURRICULUM_VISITS`]: [`CurriculumOptionsError::OverBudget`] naming
/// `options`' levels and draws when it is over.
pub fn within_curriculum_budget(
    visits: u64,
    options: CurriculumOptions,
    budget: f64,
) -> Result<(), CurriculumOptionsError> {
    let allowed = (CURRICULUM_VISITS as f64 * budget).min(u64::MAX as f64);
    if visits as f64 > allowed {
        let seconds = |v: f64| v * crate::VISIT_NANOS * 1e-9;
        return Err(CurriculumOptionsError::OverBudget {
            levels: options.levels,
            draws: options.draws,
            seconds: seconds(visits as f64),
            budget_seconds: seconds(allowed),
            factor: (visits as f64 / CURRICULUM_VISITS as f64 * 10.0).ceil() / 10.0,
        });
    }
    Ok(())
}

/// [`check_curriculum`] held to `budget` times [`CURRICULUM_VISITS`]
/// (refused before a world is generated when the price is over it), and
/// stopped between worlds once `stop` says so. Memory stays one world a
/// thread: each is measured and dropped.
pub fn check_curriculum_within(
    scheme: &Scheme,
    options: CurriculumOptions,
    budget: f64,
    stop: &(dyn Fn() -> bool + Sync),
) -> Result<CurriculumReport, CurriculumOptionsError> {
    let options = options.validate()?;
    within_curriculum_budget(options.visits(scheme), options, budget)?;
    let mut levels = Vec::with_capacity(options.levels as usize);
    for level in 0..options.levels {
        let difficulty = options.difficulty(level);
        let worlds: Option<Vec<WorldStats>> = (0..options.draws)
            .into_par_iter()
            .map(|index| {
                (!stop()).then(|| {
                    WorldStats::of(&generate_at(
                        scheme,
                        options.seed,
                        u64::from(index),
                        difficulty,
                    ))
                })
            })
            .collect();
        let worlds = worlds.ok_or(CurriculumOptionsError::Interrupted)?;
        levels.push(LevelStats::of(level, difficulty, &worlds, scheme.globals()));
    }
    let mut problems = Vec::new();
    if levels.last().is_some_and(|top| top.flat_share >= 1.0) {
        problems.push(CurriculumProblem::FlatScheme);
    } else {
        for pair in levels.windows(2) {
            let (below, level) = (&pair[0], &pair[1]);
            if level.flat_share >= 1.0 {
                problems.push(CurriculumProblem::Dead(level.level));
            } else if level.mean_height <= below.mean_height {
                problems.push(CurriculumProblem::NotRising(level.level));
            }
        }
    }
    Ok(CurriculumReport {
        options,
        levels,
        problems,
    })
}

/// What one world contributes to its level, in steps.
struct WorldStats {
    flat: bool,
    height_sum: u64,
    cells: u64,
    step_sum: u64,
    steps: u64,
    max_step: u16,
    /// The heights' digest: distinct worlds are counted by it, so a level
    /// holds a number per draw, not a copy of every heightmap.
    digest: u64,
}

impl WorldStats {
    fn of(terrain: &Terrain) -> WorldStats {
        let grid = terrain.grid();
        let map = terrain.heightmap();
        // `DefaultHasher::new` has fixed keys: the same digest in every run.
        let mut hasher = DefaultHasher::new();
        map.cells().hash(&mut hasher);
        let mut stats = WorldStats {
            flat: true,
            height_sum: 0,
            cells: 0,
            step_sum: 0,
            steps: 0,
            max_step: 0,
            digest: hasher.finish(),
        };
        // Each non-frame cell, and its pairs with its non-frame neighbours
        // to the right and above (each pair once).
        for y in 0..grid.ny {
            for x in 0..grid.nx {
                if grid.is_frame(x, y) {
                    continue;
                }
                let h = map.get(x, y);
                stats.flat &= h == 0;
                stats.height_sum += u64::from(h);
                stats.cells += 1;
                if x + 1 < grid.nx && !grid.is_frame(x + 1, y) {
                    stats.add_step(h, map.get(x + 1, y));
                }
                if y + 1 < grid.ny && !grid.is_frame(x, y + 1) {
                    stats.add_step(h, map.get(x, y + 1));
                }
            }
        }
        stats
    }

    /// The pair of neighbouring heights `a`, `b`: a step where they differ.
    fn add_step(&mut self, a: u16, b: u16) {
        let d = a.abs_diff(b);
        if d > 0 {
            self.step_sum += u64::from(d);
            self.steps += 1;
            self.max_step = self.max_step.max(d);
        }
    }
}

impl LevelStats {
    fn of(
        level: u32,
        difficulty: Difficulty,
        worlds: &[WorldStats],
        globals: &crate::globals::Globals,
    ) -> LevelStats {
        let sum = |f: fn(&WorldStats) -> u64| worlds.iter().map(f).sum::<u64>() as f64;
        let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
        let step_height = globals.step_height;
        let max_step =
            f64::from(worlds.iter().map(|w| w.max_step).max().unwrap_or(0)) * step_height;
        let distinct: HashSet<u64> = worlds.iter().map(|w| w.digest).collect();
        LevelStats {
            level,
            difficulty,
            flat_share: ratio(
                worlds.iter().filter(|w| w.flat).count() as f64,
                worlds.len() as f64,
            ),
            mean_height: ratio(sum(|w| w.height_sum), sum(|w| w.cells)) * step_height,
            mean_step: ratio(sum(|w| w.step_sum), sum(|w| w.steps)) * step_height,
            max_step,
            max_slope_deg: (max_step / globals.block_size).atan().to_degrees(),
            // At most `draws`, which fits a u32.
            distinct: distinct.len() as u32,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options(levels: u32, draws: u32) -> CurriculumOptions {
        CurriculumOptions {
            levels,
            draws,
            seed: 3,
        }
    }

    #[test]
    fn a_one_step_scheme_has_no_dead_level() {
        let scheme = Scheme::from_csv("# size: 10x10\ntype,height\nrandom,1\n", None).unwrap();
        let report = check_curriculum(&scheme, options(10, 40)).unwrap();
        assert_eq!(report.problems, [], "{:?}", report.levels);
        assert!(report.levels[0].flat_share >= 1.0);
        assert_eq!(report.levels[0].distinct, 1);
        assert!(report.levels[1..].iter().all(|l| l.flat_share <= 0.0));
        assert!((report.levels[9].max_step - 0.1).abs() < 1e-12);
    }

    #[test]
    fn the_half_up_rule_would_fail_the_same_scheme() {
        // What the drawn rule fixes: floor(D·1 + 0.5) is flat below D = 0.5.
        let d = options(10, 1).difficulty(4);
        assert_eq!(d.scale(1), 0);
    }

    #[test]
    fn a_flat_scheme_is_reported() {
        let scheme = Scheme::from_csv("# size: 4x4\ntype,height\n", None).unwrap();
        let report = check_curriculum(&scheme, options(3, 2)).unwrap();
        assert_eq!(report.problems, [CurriculumProblem::FlatScheme]);
    }

    #[test]
    fn options_out_of_range_are_refused() {
        let scheme = Scheme::from_csv("# size: 4x4\ntype,height\n", None).unwrap();
        assert_eq!(
            check_curriculum(&scheme, options(1, 5)),
            Err(CurriculumOptionsError::Levels(1))
        );
        assert_eq!(
            check_curriculum(&scheme, options(5, 0)),
            Err(CurriculumOptionsError::Draws(0))
        );
    }
}
