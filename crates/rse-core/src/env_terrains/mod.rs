//! Every parallel environment its own terrain, new every episode (docs/envs.md):
//! the terrains of `num_envs` environments of one scheme, each a pure
//! function of (scheme, seed, global env id, episode, difficulty), and
//! their MuJoCo height-field samples written into one caller's buffer —
//! one slot per environment (a pool of same-shaped height fields, for
//! simulators that route a field per world) or one tile per environment
//! of a single shared field (for those with one terrain for all).
//!
//! This module holds the environments' state and episodes; `options` what
//! they are made with and their errors, `layout` the buffer (slots or
//! tiles, its shape, the writes), `request` what a user asks for, resolved
//! to [`EnvOptions`] with the library's defaults, `copy_out` the slots'
//! fields copied out of the buffer for an adapter's reset.

use rayon::prelude::*;

use crate::difficulty::Difficulty;
use crate::generate::generate_at;
use crate::globals::Grid;
use crate::scheme::Scheme;
use crate::terrain::Terrain;

mod copy_out;
mod layout;
mod mix;
mod options;
mod request;
mod sheet;

use layout::chunks_at;

use options::bad;

pub use copy_out::FieldSamples;
pub use layout::{env_pool_bytes, mix_pool_bytes};
pub use mix::{SchemeMix, check_mixable};
pub use options::{EnvError, EnvLayout, EnvOptions};
pub use request::{DEFAULT_ENV_OVERSAMPLE, ENV_OPTIONS, EnvOptionInfo, EnvRequest, LayoutKind};
pub use sheet::{SheetOptions, SheetTile, contact_sheet, contact_sheet_named, tiles_sheet};

/// Global environment ids and episodes are each below `2^ENV_BITS`: the
/// world index of env `g` at episode `k` is `k·2^32 + g` ([`env_world`]).
pub const ENV_BITS: u32 = 32;

/// The world index (as [`generate_at`] takes it) of global environment
/// `env` at episode `episode`: `episode·2³² + env`. Distinct for every pair,
/// so no two environments, on any process, ever share a terrain, and any
/// episode of any environment can be rebuilt from its global id alone.
/// `None` when either is `2³²` or more.
pub fn env_world(env: u64, episode: u64) -> Option<u64> {
    (env >> ENV_BITS == 0 && episode >> ENV_BITS == 0).then_some((episode << ENV_BITS) | env)
}

/// The terrains of many environments and their height-field samples.
#[derive(Debug, Clone)]
pub struct EnvTerrains {
    /// The first scheme (one a pool of a single scheme).
    scheme: Scheme,
    /// Every scheme of a mix (the first is `scheme`); empty for one.
    mix: Vec<Scheme>,
    /// Each environment's scheme, an index into the mix (all 0 for one).
    drawn: Vec<usize>,
    options: EnvOptions,
    terrains: Vec<Terrain>,
    /// Each environment's spawn point, computed with its terrain.
    origins: Vec<[f64; 3]>,
    episodes: Vec<u64>,
    /// Samples of one environment's field: (rows along y, columns along x).
    env_shape: (usize, usize),
    /// The whole buffer: (slots, rows, columns).
    shape: (usize, usize, usize),
    /// The cells of one slot (or tile): the largest grid of the mix; a
    /// smaller terrain lies in its first cells, ground around it.
    slot: Grid,
    elevation: f64,
}

impl EnvTerrains {
    /// The terrains of episode 0 of every environment. Refused, naming the
    /// argument: no environments, global ids past 2³², an oversample that
    /// gives a field MuJoCo cannot take, a buffer of more than
    /// [`MAX_HFIELD_SAMPLES`](crate::MAX_HFIELD_SAMPLES) per field or 2³² in all, tiles with no column.
    pub fn new(scheme: Scheme, options: EnvOptions) -> Result<Self, EnvError> {
        Self::mixed(vec![scheme], &[1.0], options)
    }

    /// The terrains of episode 0 of every environment, each environment
    /// drawing its scheme from `schemes` by `proportions` ([`SchemeMix`],
    /// from its global id and the seed). The schemes share their block
    /// size; their grids, obstacles, step heights and bases may differ:
    /// every slot fits the largest grid (a smaller terrain in its first
    /// cells, ground around it), the samples are tops in metres on one
    /// scale (the highest top any scheme can have). Refused as [`new`](Self::new)
    /// refuses, and for a mix whose schemes differ there or whose
    /// proportions are not one per scheme, each 0 or more.
    pub fn mixed(
        schemes: Vec<Scheme>,
        proportions: &[f64],
        options: EnvOptions,
    ) -> Result<Self, EnvError> {
        let n = options.num_envs;
        if schemes.len() != proportions.len() {
            return Err(bad(
                "proportions",
                format!(
                    "{} given for {} schemes; give one per scheme",
                    proportions.len(),
                    schemes.len()
                ),
            ));
        }
        mix::check_mixable(&schemes)?;
        let mix = SchemeMix::new(proportions)?;
        if n == 0 {
            return Err(bad("num_envs", "expected 1 or more environments"));
        }
        let last = options.env_offset.checked_add(n as u64 - 1);
        if last.is_none_or(|last| last >> ENV_BITS != 0) {
            return Err(bad(
                "env_offset",
                format!(
                    "{} + {n} environments run past the largest global id, 2^32 - 1",
                    options.env_offset
                ),
            ));
        }
        // Each option's range, as the table declares it (options built by
        // hand, not through `EnvRequest::resolve`, included).
        EnvRequest::given(&options).check_ranges()?;
        // Every slot (or tile) fits the largest grid of the mix.
        let slot = mix::largest_grid(&schemes);
        let layout::Shapes { env_shape, shape } = layout::buffer_shape_of(slot, options)?;
        // One scale for every scheme: the highest top any can have.
        let elevation = schemes.iter().map(Scheme::max_top).fold(0.0, f64::max);
        let drawn = if schemes.len() > 1 {
            mix.schemes_of(options.seed, options.env_offset, n)
        } else {
            vec![0; n]
        };
        let mut schemes = schemes;
        let scheme = schemes.remove(0);
        let mix = if schemes.is_empty() {
            Vec::new()
        } else {
            std::iter::once(scheme.clone()).chain(schemes).collect()
        };
        let mut envs = EnvTerrains {
            elevation,
            scheme,
            mix,
            drawn,
            options,
            terrains: Vec::new(),
            origins: Vec::new(),
            episodes: vec![0; n],
            env_shape,
            shape,
            slot,
        };
        let made: Vec<Made> = (0..n)
            .into_par_iter()
            .map(|e| {
                envs.make(Renewal {
                    env: e,
                    episode: 0,
                    difficulty: options.difficulty,
                })
            })
            .collect();
        (envs.terrains, envs.origins) = made.into_iter().map(|m| (m.terrain, m.origin)).unzip();
        Ok(envs)
    }

    /// Environment `e`'s terrain at `episode`, at `difficulty`, and its
    /// spawn point.
    fn make(
        &self,
        Renewal {
            env: e,
            episode,
            difficulty,
        }: Renewal,
    ) -> Made {
        let world = env_world(self.options.env_offset + e as u64, episode)
            .expect("ids and episodes checked below 2^32");
        let terrain = generate_at(self.scheme_of(e), self.options.seed, world, difficulty);
        let [x, y, z] = terrain.spawn_origin(terrain.region(), self.options.spawn_radius);
        let (x0, y0) = self.tile_origin(e);
        let s = terrain.block_size();
        let origin = [x + f64::from(x0) * s, y + f64::from(y0) * s, z];
        Made { e, terrain, origin }
    }

    /// Keeps what a reset made.
    fn store(&mut self, made: Vec<Made>) {
        for Made { e, terrain, origin } in made {
            self.terrains[e] = terrain;
            self.origins[e] = origin;
        }
    }

    /// The options it was made with.
    pub fn options(&self) -> &EnvOptions {
        &self.options
    }

    /// The scheme every environment draws its terrains from; the first of
    /// a mix.
    pub fn scheme(&self) -> &Scheme {
        &self.scheme
    }

    /// Every scheme of the pool: the one, or a mix's in their order.
    pub fn schemes(&self) -> &[Scheme] {
        if self.mix.is_empty() {
            std::slice::from_ref(&self.scheme)
        } else {
            &self.mix
        }
    }

    /// Environment `e`'s scheme: its index in [`schemes`](Self::schemes).
    pub fn scheme_index(&self, e: usize) -> usize {
        self.drawn[e]
    }

    /// Environment `e`'s scheme.
    pub fn scheme_of(&self, e: usize) -> &Scheme {
        &self.schemes()[self.drawn[e]]
    }

    /// How many environments (ids `0..num_envs` in this process).
    pub fn num_envs(&self) -> usize {
        self.terrains.len()
    }

    /// Environment `e`'s current terrain.
    pub fn terrain(&self, e: usize) -> &Terrain {
        &self.terrains[e]
    }

    /// Environment `e`'s current episode (0 until its first reset).
    pub fn episode(&self, e: usize) -> u64 {
        self.episodes[e]
    }

    /// Environment `e`'s spawn point `[x, y, z]`, metres: the centre of its
    /// terrain on the highest top within the spawn radius, in its slot's
    /// frame (slots) or the map's (tiles).
    pub fn origin(&self, e: usize) -> [f64; 3] {
        self.origins[e]
    }

    /// The top under `(x, y)` of environment `e` (its slot's frame, or the
    /// map's for tiles), metres; NaN off its terrain.
    pub fn height_at(&self, e: usize, x: f64, y: f64) -> f64 {
        let terrain = &self.terrains[e];
        let (x0, y0) = self.tile_origin(e);
        let s = terrain.block_size();
        terrain
            .height_at(x - f64::from(x0) * s, y - f64::from(y0) * s)
            .unwrap_or(f64::NAN)
    }

    /// Checks `envs` (each below `num_envs`) and `difficulty` (one per
    /// named environment, or none).
    fn check_envs(
        &self,
        envs: &[usize],
        difficulty: Option<&[Difficulty]>,
    ) -> Result<(), EnvError> {
        if let Some(&e) = envs.iter().find(|&&e| e >= self.num_envs()) {
            return Err(bad(
                "env_ids",
                format!("{e} is not an environment (0 to {})", self.num_envs() - 1),
            ));
        }
        if let Some(d) = difficulty
            && d.len() != envs.len()
        {
            return Err(bad(
                "difficulty",
                format!("{} values for {} environments", d.len(), envs.len()),
            ));
        }
        Ok(())
    }

    /// Moves each of `envs` to its next episode with a new terrain, at
    /// `difficulty[i]` for `envs[i]`. Other environments are untouched; an
    /// environment named twice moves twice. Nothing changes when an
    /// argument is refused.
    pub fn reset(&mut self, envs: &[usize], difficulty: &[Difficulty]) -> Result<(), EnvError> {
        let jobs = self.advance(envs, difficulty)?;
        let made = jobs.into_par_iter().map(|job| self.make(job)).collect();
        self.store(made);
        Ok(())
    }

    /// [`reset`](Self::reset), then [`write`](Self::write) of the same
    /// environments, fused: each new terrain is written into its slot or
    /// tile by the thread that made it, so the writes (bound by memory)
    /// overlap the generation of other terrains (bound by the CPU) — the
    /// reset of a training step. Nothing changes, in `self` or in `out`,
    /// when an argument is refused.
    pub fn reset_into(
        &mut self,
        envs: &[usize],
        difficulty: &[Difficulty],
        out: &mut [f32],
    ) -> Result<(), EnvError> {
        self.check_out(out)?;
        // `advance` checks the ids and difficulties before it counts.
        let mut jobs = self.advance(envs, difficulty)?;
        jobs.sort_unstable_by_key(|job| job.env);
        let this = &*self;
        let made = match self.options.layout {
            EnvLayout::Slots => {
                let slots = chunks_at(out, this.slot_len(), jobs.iter().map(|job| job.env));
                jobs.into_par_iter()
                    .zip(slots)
                    .map(|(job, slot)| {
                        let made = this.make(job);
                        this.write_slot(&made.terrain, slot);
                        made
                    })
                    .collect()
            }
            EnvLayout::Tiles { cols, .. } => {
                // Tiles of one tile row share its rows of samples: a task
                // per tile row, its terrains made in parallel too.
                let per_row = cols as usize;
                let groups: Vec<&[Renewal]> = jobs
                    .chunk_by(|a, b| a.env / per_row == b.env / per_row)
                    .collect();
                let bands = chunks_at(
                    out,
                    this.band_len(),
                    groups.iter().map(|g| g[0].env / per_row),
                );
                groups
                    .into_par_iter()
                    .zip(bands)
                    .flat_map_iter(|(group, band)| {
                        let made: Vec<Made> = group.par_iter().map(|&job| this.make(job)).collect();
                        for m in &made {
                            this.write_tile(m.e, &m.terrain, band);
                        }
                        made
                    })
                    .collect()
            }
        };
        self.store(made);
        Ok(())
    }

    /// Checks a reset's arguments, then counts each named environment's
    /// episodes (repeats in order) and returns what to make: each env once,
    /// at its last episode and difficulty — the terrains of earlier repeats
    /// would be replaced unseen.
    fn advance(
        &mut self,
        envs: &[usize],
        difficulty: &[Difficulty],
    ) -> Result<Vec<Renewal>, EnvError> {
        self.check_envs(envs, Some(difficulty))?;
        let mut times = vec![0u64; self.num_envs()];
        for &e in envs {
            times[e] += 1;
        }
        if let Some(&e) = envs
            .iter()
            .find(|&&e| (self.episodes[e] + times[e]) >> ENV_BITS != 0)
        {
            return Err(bad(
                "env_ids",
                format!("environment {e} has run 2^32 episodes"),
            ));
        }
        let mut jobs = Vec::with_capacity(envs.len());
        for (&e, &d) in envs.iter().zip(difficulty).rev() {
            if times[e] > 0 {
                self.episodes[e] += times[e];
                times[e] = 0;
                jobs.push(Renewal {
                    env: e,
                    episode: self.episodes[e],
                    difficulty: d,
                });
            }
        }
        Ok(jobs)
    }
}

/// What [`EnvTerrains::make`] makes: environment `e`'s terrain of an
/// episode and its spawn point.
struct Made {
    e: usize,
    terrain: Terrain,
    origin: [f64; 3],
}

/// One environment's new terrain to make: its episode and difficulty.
#[derive(Debug, Clone, Copy)]
struct Renewal {
    env: usize,
    episode: u64,
    difficulty: Difficulty,
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // sentinels and tops compared exactly: both are computed the same way
mod tests {
    use super::*;

    /// Every setting at its one default ([`EnvRequest::resolve`]), one env.
    fn default_options() -> EnvOptions {
        EnvRequest {
            num_envs: 1,
            ..EnvRequest::default()
        }
        .resolve(&scheme())
        .unwrap()
    }

    fn scheme() -> Scheme {
        Scheme::from_csv(
            "# size: 6x5\n# base: 0.05\ntype,height,angle,x1,y1\nrandom,0..3,,,\npeak,2..4,45,1..4,1..3\n",
            None,
        )
        .unwrap()
    }

    fn envs(n: usize, layout: EnvLayout) -> EnvTerrains {
        let options = EnvOptions {
            num_envs: n,
            seed: 7,
            env_offset: 100,
            layout,
            ..default_options()
        };
        EnvTerrains::new(scheme(), options).unwrap()
    }

    fn d(v: f64) -> Difficulty {
        Difficulty::new(v).unwrap()
    }

    #[test]
    fn the_world_index_pairs_env_and_episode() {
        assert_eq!(env_world(5, 0), Some(5));
        assert_eq!(env_world(5, 3), Some(3 * (1 << 32) + 5));
        assert_eq!(env_world(1 << 32, 0), None);
        assert_eq!(env_world(0, 1 << 32), None);
    }

    #[test]
    fn a_terrain_depends_on_its_env_episode_and_difficulty_alone() {
        let mut a = envs(3, EnvLayout::Slots);
        let mut b = envs(3, EnvLayout::Slots);
        a.reset(&[0, 2], &[d(0.5), d(1.0)]).unwrap();
        a.reset(&[1], &[d(0.25)]).unwrap();
        a.reset(&[2], &[d(1.0)]).unwrap();
        b.reset(&[2, 1, 0, 2], &[d(1.0), d(0.25), d(0.5), d(1.0)])
            .unwrap();
        for e in 0..3 {
            assert_eq!(a.episode(e), b.episode(e));
            assert_eq!(
                a.terrain(e).heightmap(),
                b.terrain(e).heightmap(),
                "env {e}"
            );
            let world = env_world(100 + e as u64, a.episode(e)).unwrap();
            let alone = generate_at(&scheme(), 7, world, a.terrain(e).difficulty());
            assert_eq!(a.terrain(e).heightmap(), alone.heightmap());
        }
        assert_eq!([a.episode(0), a.episode(1), a.episode(2)], [1, 1, 2]);
    }

    /// A mix of a 6x5 grid and a 3x4 one (the scheme of `scheme()` and a
    /// smaller), every env's own layout.
    fn mixed_grids(n: usize, layout: EnvLayout) -> EnvTerrains {
        let small = Scheme::from_csv("# size: 3x4\ntype,height\nrandom,1..4\n", None).unwrap();
        let options = EnvOptions {
            num_envs: n,
            seed: 3,
            layout,
            ..default_options()
        };
        EnvTerrains::mixed(vec![scheme(), small], &[1.0, 1.0], options).unwrap()
    }

    #[test]
    fn a_mix_of_grids_puts_a_smaller_terrain_in_its_slots_first_cells_ground_around_it() {
        let e = mixed_grids(6, EnvLayout::Slots);
        let (n, rows, cols) = e.buffer_shape();
        assert_eq!((rows, cols), (10, 12), "the larger grid, oversampled 2");
        assert!((0..n).any(|i| e.scheme_index(i) == 1) && (0..n).any(|i| e.scheme_index(i) == 0));
        let mut out = vec![-1.0f32; n * rows * cols];
        e.write(&(0..n).collect::<Vec<_>>(), &mut out).unwrap();
        let elevation = e.hfield_size()[2];
        for env in 0..n {
            let t = e.terrain(env);
            let (trows, tcols) = (t.grid().ny as usize * 2, t.grid().nx as usize * 2);
            let mut want = vec![0.0f32; trows * tcols];
            t.hfield_into(2, 0.0, elevation, &mut want).unwrap();
            let slot = &out[env * rows * cols..(env + 1) * rows * cols];
            for r in 0..rows {
                for c in 0..cols {
                    let expected = if r < trows && c < tcols {
                        want[r * tcols + c]
                    } else {
                        0.0
                    };
                    assert_eq!(slot[r * cols + c], expected, "env {env} ({r}, {c})");
                }
            }
            // Off the smaller terrain: no top, as off any terrain.
            let s = t.block_size();
            assert!(!e.height_at(env, 0.5 * s, 0.5 * s).is_nan());
            assert!(e.height_at(env, 5.5 * s, 4.5 * s).is_nan() == (e.scheme_index(env) == 1));
        }
        let tiles = mixed_grids(6, EnvLayout::Tiles { cols: 3, border: 1 });
        let (_, rows, cols) = tiles.buffer_shape();
        let mut map = vec![-1.0f32; rows * cols];
        tiles.write(&(0..6).collect::<Vec<_>>(), &mut map).unwrap();
        let small = (0..6).find(|&i| tiles.scheme_index(i) == 1).unwrap();
        let (x0, y0) = tiles.tile_origin(small);
        // The small tile's cells past its terrain are ground, not left as they were.
        let at = |x: u32, y: u32| map[(y as usize * 2) * cols + x as usize * 2];
        assert_eq!(at(x0 + 5, y0), tiles.ground_sample());
        assert_eq!(at(x0 + 1, y0 + 4), tiles.ground_sample());
    }

    #[test]
    fn a_mix_pool_is_priced_by_its_largest_grid() {
        let options = EnvOptions {
            num_envs: 8,
            ..default_options()
        };
        let small = Scheme::from_csv("# size: 3x4\ntype,height\nrandom,1..4\n", None).unwrap();
        let wide = Scheme::from_csv("# size: 9x2\ntype,height\nrandom,1\n", None).unwrap();
        let one = env_pool_bytes(&scheme(), options, 0).unwrap();
        assert_eq!(mix_pool_bytes(&[scheme()], options, 0).unwrap(), one);
        assert_eq!(
            mix_pool_bytes(&[small.clone(), scheme()], options, 0).unwrap(),
            one
        );
        // 9x5 slots: more than either grid alone.
        let both = mix_pool_bytes(&[scheme(), wide.clone()], options, 0).unwrap();
        assert!(both > one && both > env_pool_bytes(&wide, options, 0).unwrap());
    }

    #[test]
    fn slots_hold_each_env_field_and_a_write_touches_only_the_named() {
        let mut e = envs(3, EnvLayout::Slots);
        let (n, rows, cols) = e.buffer_shape();
        assert_eq!((n, rows, cols), (3, 10, 12));
        let mut out = vec![-1.0f32; n * rows * cols];
        e.write(&[0, 1, 2], &mut out).unwrap();
        let elevation = e.hfield_size()[2];
        for env in 0..3 {
            let mut want = vec![0.0f32; rows * cols];
            e.terrain(env)
                .hfield_into(2, 0.0, elevation, &mut want)
                .unwrap();
            assert_eq!(
                &out[env * rows * cols..(env + 1) * rows * cols],
                want.as_slice()
            );
        }
        let before = out.clone();
        e.reset(&[1], &[d(1.0)]).unwrap();
        out[rows * cols..2 * rows * cols].fill(-1.0);
        e.write(&[1], &mut out).unwrap();
        assert_eq!(out[..rows * cols], before[..rows * cols]);
        assert_eq!(out[2 * rows * cols..], before[2 * rows * cols..]);
        assert!(
            out[rows * cols..2 * rows * cols]
                .iter()
                .all(|v| (0.0..=1.0).contains(v))
        );
    }

    #[test]
    fn repeats_count_in_order_and_the_last_terrain_stays() {
        let mut e = envs(4, EnvLayout::Slots);
        e.reset(&[2, 0, 2, 3], &[d(0.2), d(1.0), d(0.7), d(0.5)])
            .unwrap();
        assert_eq!((e.episode(2), e.episode(0), e.episode(1)), (2, 1, 0));
        // Env 2 named twice: its second episode, at the second difficulty.
        let world = env_world(100 + 2, 2).unwrap();
        assert_eq!(
            e.terrain(2).heightmap(),
            generate_at(&e.scheme, 7, world, d(0.7)).heightmap()
        );
    }

    #[test]
    fn tiles_hold_each_env_in_its_tile_and_borders_stay() {
        let e = envs(5, EnvLayout::Tiles { cols: 2, border: 1 });
        let (n, rows, cols) = e.buffer_shape();
        // 3 tile rows of 5 cells and 4 borders, 2 tile columns of 6 and 3 borders; k = 2.
        assert_eq!((n, rows, cols), (1, (3 * 5 + 4) * 2, (2 * 6 + 3) * 2));
        let mut out = vec![-1.0f32; rows * cols];
        e.write(&[0, 1, 2, 3, 4], &mut out).unwrap();
        let elevation = e.hfield_size()[2];
        assert_eq!(e.field_shape(), (10, 12));
        for env in 0..5 {
            let (row0, col0) = e.field_corner(env);
            let mut want = vec![0.0f32; 10 * 12];
            e.terrain(env)
                .hfield_into(2, 0.0, elevation, &mut want)
                .unwrap();
            for r in 0..10 {
                let at = (row0 + r) * cols + col0;
                assert_eq!(
                    &out[at..at + 12],
                    &want[r * 12..(r + 1) * 12],
                    "env {env} row {r}"
                );
            }
            let [x, y, z] = e.origin(env);
            assert!(
                z + 1e-12 >= e.height_at(env, x, y),
                "the origin stands on the highest top near it"
            );
        }
        // The border and the empty sixth tile are untouched.
        assert!(out[..cols * 2].iter().all(|&v| v == -1.0));
        // The sixth tile's first cell: column 1, row 2.
        let (x5, y5) = (1 + 7, 1 + 2 * 6);
        assert!(out[y5 * 2 * cols + x5 * 2] == -1.0);
        // Heights in the map frame: env 3 is tile (1, 1).
        let (x0, y0) = e.tile_origin(3);
        assert_eq!((x0, y0), (8, 7));
        assert_eq!(e.field_corner(3), (14, 16), "in samples, k = 2");
        let s = 0.1;
        assert_eq!(
            e.height_at(3, (f64::from(x0) + 0.5) * s, (f64::from(y0) + 0.5) * s),
            e.terrain(3).height_at(0.05, 0.05).unwrap()
        );
        assert!(e.height_at(3, 0.05, 0.05).is_nan(), "off its tile");
    }

    /// The fused reset makes and writes what a reset then a write would,
    /// in both layouts, whatever order and repeats the ids come in.
    #[test]
    fn reset_into_is_reset_then_write() {
        for layout in [EnvLayout::Slots, EnvLayout::Tiles { cols: 2, border: 1 }] {
            let (mut fused, mut apart) = (envs(5, layout), envs(5, layout));
            let (n, rows, cols) = fused.buffer_shape();
            let mut a = vec![-1.0f32; n * rows * cols];
            let mut b = a.clone();
            let (ids, levels) = ([4, 0, 3, 4, 1], [d(0.3), d(1.0), d(0.6), d(0.9), d(0.1)]);
            fused.reset_into(&ids, &levels, &mut a).unwrap();
            apart.reset(&ids, &levels).unwrap();
            apart.write(&ids, &mut b).unwrap();
            assert_eq!(a, b, "{layout:?}");
            for e in 0..5 {
                assert_eq!(fused.episode(e), apart.episode(e));
                assert_eq!(fused.terrain(e).heightmap(), apart.terrain(e).heightmap());
                assert_eq!(fused.origin(e), apart.origin(e));
            }
            // Env 2 was not named: its slot or tile still holds -1.
            assert!(a.contains(&-1.0));
        }
    }

    #[test]
    fn bad_arguments_are_named() {
        let named = |r: Result<EnvTerrains, EnvError>| match r.unwrap_err() {
            EnvError::Bad { argument, .. } => argument,
            other => panic!("{other}"),
        };
        let with = |o: EnvOptions| EnvTerrains::new(scheme(), o);
        assert_eq!(
            named(with(EnvOptions {
                num_envs: 0,
                ..default_options()
            })),
            "num_envs"
        );
        assert_eq!(
            named(with(EnvOptions {
                num_envs: 2,
                env_offset: u64::from(u32::MAX),
                ..default_options()
            })),
            "env_offset"
        );
        assert_eq!(
            named(with(EnvOptions {
                layout: EnvLayout::Tiles { cols: 0, border: 0 },
                ..default_options()
            })),
            "cols"
        );
        // Its range, as the table of options declares it.
        assert_eq!(
            named(with(EnvOptions {
                oversample: 0,
                ..default_options()
            })),
            "oversample"
        );
        let mut e = envs(2, EnvLayout::Slots);
        let argument = |r: Result<(), EnvError>| match r.unwrap_err() {
            EnvError::Bad { argument, .. } => argument,
            other => panic!("{other}"),
        };
        assert_eq!(argument(e.reset(&[2], &[d(1.0)])), "env_ids");
        assert_eq!(argument(e.reset(&[0, 1], &[d(1.0)])), "difficulty");
        assert_eq!([e.episode(0), e.episode(1)], [0, 0], "nothing changed");
        assert_eq!(argument(e.write(&[0], &mut [0.0; 7])), "out");
        let mut short = [0.5f32; 7];
        assert_eq!(argument(e.reset_into(&[0], &[d(1.0)], &mut short)), "out");
        let (n, rows, cols) = e.buffer_shape();
        let mut whole = vec![0.5f32; n * rows * cols];
        assert_eq!(
            argument(e.reset_into(&[0, 9], &[d(1.0); 2], &mut whole)),
            "env_ids"
        );
        assert_eq!([e.episode(0), e.episode(1)], [0, 0], "nothing changed");
        assert!(
            whole.iter().chain(&short).all(|&v| v == 0.5),
            "nothing written"
        );
    }
}
