//! Writing a batch of worlds: in parallel, each world whole or absent, and
//! resumable — a rerun skips the worlds already written and redoes the rest.

use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use rayon::prelude::*;
use rse_core::Scheme;

use crate::error::Error;
use crate::files::place::{
    Lock, Outcome, held_locks, lock_in, lock_in_waiting, place_world, remove_leftovers,
};
use crate::files::write::Created;
use crate::memory::check_memory_for;
use crate::record::options::{Targets, WorldOptions};
use crate::render::templates::Templates;
use crate::render::world::SchemeCsv;

/// Which worlds of a batch this run writes: those with `index % n == k`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    k: u64,
    n: u64,
}

impl Shard {
    /// Shard `k` of `n`; refused unless `0 ≤ k < n` (so `n ≥ 1`).
    pub fn new(k: u64, n: u64) -> Result<Self, Error> {
        if k >= n {
            return Err(Error::BadOption {
                option: "shard",
                message: format!("bad shard {k}/{n}: expected K/N with 0 <= K < N, e.g. 0/4"),
            });
        }
        Ok(Shard { k, n })
    }

    /// This shard, `0 ≤ k < n`.
    pub fn k(&self) -> u64 {
        self.k
    }

    /// The number of shards, at least 1.
    pub fn n(&self) -> u64 {
        self.n
    }

    /// `true` when some world index belongs to both shards: `k ≡ k'`
    /// modulo the greatest common divisor of `n` and `n'` (the Chinese
    /// remainder theorem).
    pub fn overlaps(self, other: Shard) -> bool {
        let (mut a, mut b) = (self.n, other.n);
        while b != 0 {
            (a, b) = (b, a % b);
        }
        self.k % a == other.k % a
    }

    /// How many of a batch of `amount` worlds are this shard's.
    pub fn worlds(&self, amount: u64) -> u64 {
        amount.saturating_sub(self.k).div_ceil(self.n)
    }
}

impl Shard {
    /// This task's shard of a Slurm array job (`--shard auto`): task ids
    /// `MIN, MIN + STEP, …` (`SLURM_ARRAY_TASK_MIN`, `SLURM_ARRAY_TASK_STEP`,
    /// default 1) are shards `0, 1, …` of `SLURM_ARRAY_TASK_COUNT`, this
    /// task's `SLURM_ARRAY_TASK_ID` picks one. `var` reads a variable (the
    /// process environment in the CLI). Outside an array job, or for an
    /// array whose ids are not such a range (`--array=1,5,9`), the error
    /// names the variable and says why.
    pub fn from_slurm_array(var: impl Fn(&str) -> Option<String>) -> Result<Self, Error> {
        let bad = |message: String| Error::BadOption {
            option: "shard",
            message,
        };
        let number = |name: &'static str, default: Option<u64>| -> Result<u64, Error> {
            match var(name) {
                None if default.is_some() => Ok(default.unwrap_or_default()),
                None => Err(bad(format!(
                    "{name} is not set: --shard auto takes this task's shard from a Slurm array job \
                     (sbatch --array=0-N); elsewhere give --shard K/N"
                ))),
                Some(text) => text
                    .trim()
                    .parse()
                    .map_err(|_| bad(format!("{name}={text:?}: expected a whole number"))),
            }
        };
        let id = number("SLURM_ARRAY_TASK_ID", None)?;
        let min = number("SLURM_ARRAY_TASK_MIN", None)?;
        let count = number("SLURM_ARRAY_TASK_COUNT", None)?;
        let step = number("SLURM_ARRAY_TASK_STEP", Some(1))?;
        if count == 0 || step == 0 {
            let (name, value) = if count == 0 {
                ("SLURM_ARRAY_TASK_COUNT", count)
            } else {
                ("SLURM_ARRAY_TASK_STEP", step)
            };
            return Err(bad(format!("{name}={value}: expected at least 1")));
        }
        let offset = id.checked_sub(min).filter(|o| o % step == 0).ok_or_else(|| {
            bad(format!(
                "SLURM_ARRAY_TASK_ID={id} is not one of MIN + k*STEP (SLURM_ARRAY_TASK_MIN={min}, \
                 SLURM_ARRAY_TASK_STEP={step}): --shard auto needs an array of evenly spaced ids \
                 (--array=0-N or 0-N:S); give --shard K/N otherwise"
            ))
        })?;
        let k = offset / step;
        if k >= count {
            return Err(bad(format!(
                "SLURM_ARRAY_TASK_ID={id} is task {k} of SLURM_ARRAY_TASK_COUNT={count}: \
                 the array's ids are not an evenly spaced range (--array=1,5,9?); give --shard K/N"
            )));
        }
        Shard::new(k, count)
    }
}

impl Default for Shard {
    /// The whole batch.
    fn default() -> Self {
        Shard { k: 0, n: 1 }
    }
}

impl FromStr for Shard {
    type Err = Error;

    /// Parses `K/N`, `0 ≤ K < N`.
    fn from_str(s: &str) -> Result<Self, Error> {
        let bad = || Error::BadOption {
            option: "shard",
            message: format!("bad shard {s:?}: expected K/N with 0 <= K < N, e.g. 0/4"),
        };
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (k, n): (u64, u64) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        Shard::new(k, n).map_err(|_| bad())
    }
}

/// A batch: where, how many, which seed, what to write, how.
#[derive(Debug, Clone)]
pub struct BatchOptions {
    /// The output folder; worlds go in `out/world_NNNN/`.
    pub out: PathBuf,
    /// Worlds in the whole batch (all shards).
    pub amount: u64,
    /// Base seed of every world of the batch (world `i` is `(seed, i)`).
    pub seed: u64,
    /// Targets and mesh mode.
    pub world: WorldOptions,
    /// Worker threads; `None`: one per core.
    pub jobs: Option<usize>,
    /// The part of the batch this run writes.
    pub shard: Shard,
    /// Replace world folders that hold something else.
    pub force: bool,
}

impl BatchOptions {
    /// Options with single meshes, all cores, the whole batch, no `--force`.
    pub fn new(out: impl Into<PathBuf>, amount: u64, seed: u64, targets: Targets) -> Self {
        BatchOptions {
            out: out.into(),
            amount,
            seed,
            world: WorldOptions {
                targets,
                ..WorldOptions::default()
            },
            jobs: None,
            shard: Shard::default(),
            force: false,
        }
    }
}

/// A pool of `jobs` worker threads (`None`: one per core); `Some(0)` is
/// refused. Batches, checks and Python's `generate_batch` all use it.
pub fn thread_pool(jobs: Option<usize>) -> Result<rayon::ThreadPool, Error> {
    if jobs == Some(0) {
        return Err(Error::BadOption {
            option: "jobs",
            message: "jobs must be at least 1".to_owned(),
        });
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.unwrap_or(0))
        .build()
        .map_err(|source| Error::Threads {
            jobs: jobs.map_or_else(|| "one per core".to_owned(), |j| j.to_string()),
            source,
        })
}

/// Counts of a finished batch run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Summary {
    /// Worlds written anew.
    pub written: u64,
    /// Worlds found whole and identical.
    pub skipped: u64,
    /// Worlds replaced under `force`.
    pub replaced: u64,
    /// Worlds not started because the run was asked to stop (see
    /// [`write_batch_until`]); a rerun writes them.
    pub not_started: u64,
    /// Bytes written.
    pub bytes: u64,
}

/// The folder name of world `index`: `world_0007`, four digits at least,
/// more only from `world_10000` on. It depends on the index alone: a batch
/// grown from 10,000 worlds to 10,001 keeps its folders (the width once
/// followed the amount, and such a rerun wrote every world again as
/// `world_00000`…). Past 9,999 names no longer sort as text: sort them by
/// length, then text (as `rse-gen check` does).
pub fn world_name(index: u64) -> String {
    format!("world_{index:04}")
}

/// The index of the batch world named `name` (`world_0007` → 7), the
/// inverse of [`world_name`]; `None` for any other name.
pub fn world_index(name: &str) -> Option<u64> {
    let digits = name.strip_prefix("world_")?;
    let index: u64 = digits.parse().ok()?;
    (world_name(index) == name).then_some(index)
}

/// Writes the worlds of `options.shard` into `options.out`, calling
/// `on_world` after each. Stops at the first error (the worlds being written
/// by other threads are finished or cleaned up; none is left half-written).
pub fn write_batch(
    scheme: &Scheme,
    templates: &Templates,
    options: &BatchOptions,
    on_world: &(dyn Fn(Outcome) + Sync),
) -> Result<Summary, Error> {
    write_batch_until(
        scheme,
        templates,
        options,
        on_world,
        &AtomicBool::new(false),
    )
}

/// [`write_batch`], stopping early once `stop` is set (by a Ctrl-C
/// handler, say): worlds being written are finished, no new one is
/// started, and [`Summary::not_started`] counts those left for a rerun.
pub fn write_batch_until(
    scheme: &Scheme,
    templates: &Templates,
    options: &BatchOptions,
    on_world: &(dyn Fn(Outcome) + Sync),
    stop: &AtomicBool,
) -> Result<Summary, Error> {
    if options.amount == 0 {
        return Err(Error::BadOption {
            option: "amount",
            message: "amount is 0: a batch needs at least one world".to_owned(),
        });
    }
    let pool = thread_pool(options.jobs)?;
    check_memory(scheme, options)?;
    let out = &options.out;
    if out.exists() && !out.is_dir() {
        return Err(Error::BadOption {
            option: "out",
            message: format!(
                "{} is a file: worlds go into a folder (made when missing)",
                out.display()
            ),
        });
    }
    // Folders made for the batch are removed again if it fails with no
    // world written (a folder holding finished worlds stays, for a rerun).
    Created::undone_on_error(|made| {
        made.folder_chain(out, None)?;
        write_shard(&pool, scheme, templates, options, on_world, stop)
    })
}

/// [`write_batch_until`] into the existing folder `options.out`: this
/// run's shard, under its lock.
fn write_shard(
    pool: &rayon::ThreadPool,
    scheme: &Scheme,
    templates: &Templates,
    options: &BatchOptions,
    on_world: &(dyn Fn(Outcome) + Sync),
    stop: &AtomicBool,
) -> Result<Summary, Error> {
    let out = &options.out;
    // Held until this function returns; the system drops it if the process dies.
    let _lock = lock_shard(out, options.shard)?;
    // Leftovers of this shard's interrupted runs; other shards' are theirs:
    // they may be running right now into the same folder.
    let Shard { k, n } = options.shard;
    remove_leftovers(out, |world| world_index(world).is_some_and(|i| i % n == k))?;
    let count = options.shard.worlds(options.amount);
    let record = SchemeCsv::new(scheme);
    let [written, skipped, replaced, bytes, not_started] = [(); 5].map(|()| AtomicU64::new(0));
    pool.install(|| {
        (0..count).into_par_iter().try_for_each(|j| {
            if stop.load(Ordering::Relaxed) {
                not_started.fetch_add(1, Ordering::Relaxed);
                return Ok(());
            }
            let index = k + j * n;
            let name = world_name(index);
            let world = record.build_world(options.seed, index, name, &options.world, templates)?;
            let outcome = place_world(out, &world, options.force)?;
            match outcome {
                Outcome::Written(size) => {
                    written.fetch_add(1, Ordering::Relaxed);
                    bytes.fetch_add(size, Ordering::Relaxed);
                }
                Outcome::Skipped => {
                    skipped.fetch_add(1, Ordering::Relaxed);
                }
                Outcome::Replaced(size) => {
                    replaced.fetch_add(1, Ordering::Relaxed);
                    bytes.fetch_add(size, Ordering::Relaxed);
                }
            }
            on_world(outcome);
            Ok::<(), Error>(())
        })
    })?;
    Ok(Summary {
        written: written.into_inner(),
        skipped: skipped.into_inner(),
        replaced: replaced.into_inner(),
        bytes: bytes.into_inner(),
        not_started: not_started.into_inner(),
    })
}

/// The advice a batch too large for the memory ends with (a front end
/// without a worker count, the editor's page, words its own).
pub const FEWER_JOBS: &str = "; use fewer worker threads (jobs) or a smaller grid";

/// Refuses a batch whose worlds, as many at once as it has threads, would
/// need more memory than the machine has available (`MemAvailable` on
/// Linux; elsewhere nothing is refused): better a clear error before
/// starting than an abort half-way.
pub(crate) fn check_memory(scheme: &Scheme, options: &BatchOptions) -> Result<(), Error> {
    let threads = options
        .jobs
        .unwrap_or_else(rayon::current_num_threads)
        .max(1) as u64;
    let at_once = threads.min(options.shard.worlds(options.amount)).max(1);
    check_memory_for(scheme.grid().cells() as u64, &options.world, at_once).map_err(|e| match e {
        Error::TooBig { message } => Error::TooBig {
            message: format!("{message}{FEWER_JOBS}"),
        },
        other => other,
    })
}

/// Locks shard `shard` of the output folder `out` for this run, or says
/// another run holds a shard whose worlds overlap it: two runs writing the
/// same worlds raced (one renamed a world onto the other's and failed with
/// "Directory not empty"), and each removed the other's temporary folders
/// as leftovers. Shards `K/N` and `K'/N'` share a world exactly when
/// `K ≡ K' (mod gcd(N, N'))`, so the whole folder (`0/1`) overlaps every
/// shard, `0/2` and `1/2` none of each other. Each run's lock file records
/// its shard; a short-lived registry lock makes looking at the others and
/// taking one's own a single step. The lock files live in `out` itself and
/// are removed at the end of the run, so a finished output folder holds
/// worlds only (shards still merge into identical trees). Advisory `flock`s:
/// released by the system when the process ends, however it ends; they
/// guard runs on one machine (not several machines writing to one network
/// folder).
fn lock_shard(out: &Path, shard: Shard) -> Result<Lock, Error> {
    let _registry = lock_in_waiting(out, "batch shards")?;
    let busy = |other: Shard| Error::Busy {
        path: out.to_path_buf(),
        shard: format!("{}/{}", other.k, other.n),
    };
    let lock = lock_in(out, &format!("shard-{}-of-{}", shard.k, shard.n), || {
        busy(shard)
    })?;
    for text in held_locks(out, &lock)? {
        let other = text
            .trim()
            .strip_prefix("batch shard ")
            .and_then(|s| s.parse::<Shard>().ok());
        if let Some(other) = other.filter(|other| other.overlaps(shard)) {
            return Err(busy(other));
        }
    }
    lock.record(&format!("batch shard {}/{}\n", shard.k, shard.n))?;
    Ok(lock)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_depend_on_the_index_alone() {
        assert_eq!(world_name(7), "world_0007");
        assert_eq!(world_name(0), "world_0000");
        assert_eq!(world_name(12_345), "world_12345");
    }

    #[test]
    fn no_worker_threads_is_refused_naming_jobs() {
        let err = thread_pool(Some(0)).unwrap_err();
        assert!(
            matches!(err, Error::BadOption { option: "jobs", .. }),
            "{err:?}"
        );
        assert_eq!(thread_pool(Some(2)).unwrap().current_num_threads(), 2);
    }

    /// `Shard::from_slurm_array` over a fixed set of variables.
    fn slurm(vars: &[(&str, &str)]) -> Result<Shard, Error> {
        Shard::from_slurm_array(|name| {
            vars.iter()
                .find(|(n, _)| *n == name)
                .map(|(_, v)| v.to_string())
        })
    }

    #[test]
    fn a_slurm_array_task_is_its_shard() {
        let task = |id, min, count| {
            slurm(&[
                ("SLURM_ARRAY_TASK_ID", id),
                ("SLURM_ARRAY_TASK_MIN", min),
                ("SLURM_ARRAY_TASK_COUNT", count),
            ])
        };
        assert_eq!(task("0", "0", "4").unwrap(), Shard::new(0, 4).unwrap());
        assert_eq!(task("7", "5", "4").unwrap(), Shard::new(2, 4).unwrap());
        let stepped = slurm(&[
            ("SLURM_ARRAY_TASK_ID", "14"),
            ("SLURM_ARRAY_TASK_MIN", "10"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
        ]);
        assert_eq!(stepped.unwrap(), Shard::new(2, 3).unwrap());
    }

    #[test]
    fn outside_an_even_slurm_array_auto_names_the_variable() {
        // (ID, MIN, COUNT) as Slurm would set them (None: unset), and how
        // the message starts or what it says.
        let cases = [
            (None, None, None, "SLURM_ARRAY_TASK_ID is not set"),
            (
                Some("1"),
                Some("0"),
                None,
                "SLURM_ARRAY_TASK_COUNT is not set",
            ),
            (
                Some("one"),
                Some("0"),
                Some("2"),
                "SLURM_ARRAY_TASK_ID=\"one\"",
            ),
            // --array=1,5,9: three tasks, ids not a range.
            (
                Some("9"),
                Some("1"),
                Some("3"),
                "SLURM_ARRAY_TASK_ID=9 is task 8",
            ),
            (
                Some("0"),
                Some("1"),
                Some("3"),
                "SLURM_ARRAY_TASK_ID=0 is not one of",
            ),
            (Some("0"), Some("0"), Some("0"), "SLURM_ARRAY_TASK_COUNT=0"),
        ];
        for (id, min, count, starts) in cases {
            let vars: Vec<(&str, &str)> = [
                ("SLURM_ARRAY_TASK_ID", id),
                ("SLURM_ARRAY_TASK_MIN", min),
                ("SLURM_ARRAY_TASK_COUNT", count),
            ]
            .into_iter()
            .filter_map(|(name, value)| Some((name, value?)))
            .collect();
            let message = slurm(&vars).unwrap_err().to_string();
            assert!(message.starts_with(starts), "{message}");
        }
        let list = slurm(&[
            ("SLURM_ARRAY_TASK_ID", "9"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ]);
        assert!(list.unwrap_err().to_string().contains("evenly spaced"));
    }

    #[test]
    fn shards_overlap_when_they_share_a_world() {
        let s = |k, n| Shard::new(k, n).unwrap();
        for (a, b, shared) in [
            (s(0, 1), s(1, 2), true),
            (s(0, 2), s(1, 2), false),
            (s(1, 2), s(3, 4), true),
            (s(0, 2), s(3, 4), false),
            (s(1, 4), s(2, 6), false),
            (s(1, 4), s(3, 6), true),
        ] {
            assert_eq!(a.overlaps(b), shared, "{a:?} {b:?}");
            assert_eq!(b.overlaps(a), shared);
            // By brute force over enough indices.
            let brute = (0..a.n * b.n).any(|i| i % a.n == a.k && i % b.n == b.k);
            assert_eq!(brute, shared, "{a:?} {b:?}");
        }
    }

    #[test]
    fn shards_parse() {
        assert_eq!("1/4".parse::<Shard>().unwrap(), Shard::new(1, 4).unwrap());
        // Once a panic in div_ceil when built by hand with n = 0.
        assert!(Shard::new(0, 0).is_err());
        assert_eq!(Shard::new(1, 4).unwrap().worlds(10), 3);
    }

    #[test]
    fn one_run_at_a_time_per_output_folder_and_shard() {
        let dir = tempfile::tempdir().unwrap();
        let whole = Shard::default();
        let held = lock_shard(dir.path(), whole).unwrap();
        // flock: a second open file conflicts, even in this process.
        let busy = lock_shard(dir.path(), whole).unwrap_err();
        assert!(matches!(busy, Error::Busy { .. }), "{busy}");
        assert!(busy.to_string().contains("another rse-gen batch"), "{busy}");
        // Every shard overlaps the whole folder.
        let half = Shard::new(1, 2).unwrap();
        let busy = lock_shard(dir.path(), half).unwrap_err();
        assert!(busy.to_string().contains("shard 0/1"), "{busy}");
        // Another folder is free.
        let elsewhere = tempfile::tempdir().unwrap();
        let _there = lock_shard(elsewhere.path(), whole).unwrap();
        drop(held);
        // Disjoint shards run side by side; overlapping ones do not.
        let other = lock_shard(dir.path(), half).unwrap();
        let even = lock_shard(dir.path(), Shard::new(0, 2).unwrap()).unwrap();
        let busy = lock_shard(dir.path(), Shard::new(3, 4).unwrap()).unwrap_err();
        assert!(busy.to_string().contains("shard 1/2"), "{busy}");
        let busy = lock_shard(dir.path(), whole).unwrap_err();
        assert!(matches!(busy, Error::Busy { .. }), "{busy}");
        assert!(lock_shard(dir.path(), Shard::new(1, 3).unwrap()).is_err());
        drop((other, even));
        // Released locks leave nothing behind.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        for bad in ["4/4", "1", "a/2", "1/0", "-1/2"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn world_indices_read_back_from_names() {
        for index in [0, 7, 9999, 12_345] {
            assert_eq!(world_index(&world_name(index)), Some(index));
        }
        for other in ["world_7", "world_x", "atlas", "world_-001", "world_00123"] {
            assert_eq!(world_index(other), None, "{other}");
        }
    }
}
