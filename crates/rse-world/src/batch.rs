//! Writing a batch of worlds: in parallel, each world whole or absent, and
//! resumable — a rerun skips the worlds already written and redoes the rest.

use std::collections::BTreeSet;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::atomic::{AtomicU64, Ordering};

use rayon::prelude::*;
use rse_core::Scheme;

use crate::error::Error;
use crate::target::Targets;
use crate::templates::Templates;
use crate::tree::list_files;
use crate::world::{WorldFiles, WorldOptions, build_world};

/// Which worlds of a batch this run writes: those with `index % n == k`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0 ≤ k < n`.
    pub k: u64,
    /// The number of shards.
    pub n: u64,
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
        let bad = || {
            Error::Usage(format!(
                "bad shard {s:?}: expected K/N with 0 <= K < N, e.g. 0/4"
            ))
        };
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (k, n): (u64, u64) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if k >= n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}

/// A batch: where, how many, which seed, what to write, how.
#[derive(Debug, Clone)]
pub struct BatchOptions {
    /// The output folder; worlds go in `out/world_NNNN/`.
    pub out: PathBuf,
    /// Worlds in the whole batch (all shards).
    pub amount: u64,
    /// Base seed.
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

/// What happened to one world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Written anew; with its size in bytes.
    Written(u64),
    /// Already there, identical: left alone.
    Skipped,
    /// Held something else and `force` was set; with the new size in bytes.
    Replaced(u64),
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
    /// Bytes written.
    pub bytes: u64,
}

/// The folder name of world `index` in a batch of `amount`: `world_0007`,
/// with at least four digits and as many as the largest index needs, so
/// names sort in order.
pub fn world_name(index: u64, amount: u64) -> String {
    let digits = amount.saturating_sub(1).max(1).ilog10() as usize + 1;
    format!("world_{index:0width$}", width = digits.max(4))
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
    let out = &options.out;
    std::fs::create_dir_all(out).map_err(Error::io("create", out))?;
    remove_leftovers(out, options)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.unwrap_or(0))
        .build()
        .map_err(|e| {
            Error::Usage(format!(
                "cannot start {:?} worker threads: {e}",
                options.jobs
            ))
        })?;
    let Shard { k, n } = options.shard;
    let count = options.amount.saturating_sub(k).div_ceil(n);
    let [written, skipped, replaced, bytes] = [(); 4].map(|()| AtomicU64::new(0));
    pool.install(|| {
        (0..count).into_par_iter().try_for_each(|j| {
            let index = k + j * n;
            let name = world_name(index, options.amount);
            let world = build_world(scheme, options.seed, index, name, &options.world, templates)?;
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
    })
}

/// Puts `world` at `out/<name>`: written into a temporary folder, then
/// renamed into place, so that the folder appears whole or not at all.
fn place_world(out: &Path, world: &WorldFiles, force: bool) -> Result<Outcome, Error> {
    let dest = out.join(&world.name);
    let existing = match std::fs::symlink_metadata(&dest) {
        Ok(_) => true,
        Err(e) if e.kind() == ErrorKind::NotFound => false,
        Err(e) => return Err(Error::io("read", &dest)(e)),
    };
    if existing {
        match difference(&dest, world)? {
            None => return Ok(Outcome::Skipped),
            Some(reason) if !force => return Err(Error::Conflict { path: dest, reason }),
            Some(_) => {}
        }
    }
    let pid = std::process::id();
    let temp = out.join(format!(".{}.tmp-{pid}", world.name));
    if let Err(e) = write_tree(&temp, world) {
        // Best effort: the error being reported matters more.
        let _ = std::fs::remove_dir_all(&temp);
        return Err(e);
    }
    let size = world.bytes();
    if !existing {
        std::fs::rename(&temp, &dest).map_err(Error::io("rename into place", &dest))?;
        return Ok(Outcome::Written(size));
    }
    // Replace: move the old folder aside first, since a folder cannot be
    // renamed over a non-empty one. A crash in between leaves the world
    // absent (and the leftovers are removed by the next run), never mixed.
    let old = out.join(format!(".{}.old-{pid}", world.name));
    std::fs::rename(&dest, &old).map_err(Error::io("move aside", &dest))?;
    std::fs::rename(&temp, &dest).map_err(Error::io("rename into place", &dest))?;
    std::fs::remove_dir_all(&old).map_err(Error::io("remove", &old))?;
    Ok(Outcome::Replaced(size))
}

/// Writes every file of `world` under `root`.
fn write_tree(root: &Path, world: &WorldFiles) -> Result<(), Error> {
    std::fs::create_dir(root).map_err(Error::io("create", root))?;
    let mut made = BTreeSet::new();
    for (relative, bytes) in &world.files {
        let path = root.join(relative);
        if let Some(parent) = Path::new(relative).parent()
            && !parent.as_os_str().is_empty()
            && made.insert(parent.to_owned())
        {
            let dir = root.join(parent);
            std::fs::create_dir_all(&dir).map_err(Error::io("create", &dir))?;
        }
        std::fs::write(&path, bytes).map_err(Error::io("write", &path))?;
    }
    Ok(())
}

/// How the folder `dest` differs from `world`, or `None` if it holds
/// exactly its files with exactly their bytes.
fn difference(dest: &Path, world: &WorldFiles) -> Result<Option<String>, Error> {
    if !dest.is_dir() {
        return Ok(Some("not a folder".to_owned()));
    }
    for path in &list_files(dest).map_err(Error::io("read", dest))? {
        if !world.files.contains_key(path) {
            return Ok(Some(format!("unexpected file {path}")));
        }
    }
    for (path, bytes) in &world.files {
        let file = dest.join(path);
        match std::fs::read(&file) {
            Ok(on_disk) if on_disk == *bytes => {}
            Ok(_) => return Ok(Some(format!("{path} differs"))),
            Err(e) if e.kind() == ErrorKind::NotFound => {
                return Ok(Some(format!("{path} is missing")));
            }
            Err(e) => return Err(Error::io("read", file)(e)),
        }
    }
    Ok(None)
}

/// Removes the temporary folders an interrupted run of this shard left
/// (`.world_0007.tmp-PID`, `.world_0007.old-PID`). Other shards' leftovers
/// are theirs: they may be running right now into the same folder.
fn remove_leftovers(out: &Path, options: &BatchOptions) -> Result<(), Error> {
    for entry in std::fs::read_dir(out).map_err(Error::io("read", out))? {
        let entry = entry.map_err(Error::io("read", out))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(index) = leftover_index(&name) else {
            continue;
        };
        if index % options.shard.n == options.shard.k {
            let path = entry.path();
            std::fs::remove_dir_all(&path).map_err(Error::io("remove", &path))?;
        }
    }
    Ok(())
}

/// The world index of the name of a temporary folder a batch writes in
/// (`.world_0007.tmp-PID`, `.world_0007.old-PID`); `None` for any other
/// name. One left behind is what a cut-short run leaves.
pub fn leftover_index(name: &str) -> Option<u64> {
    let rest = name.strip_prefix(".world_")?;
    let (index, kind) = rest.split_once('.')?;
    (kind.starts_with("tmp-") || kind.starts_with("old-"))
        .then(|| index.parse().ok())
        .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_have_at_least_four_digits_and_sort() {
        assert_eq!(world_name(7, 1), "world_0007");
        assert_eq!(world_name(7, 10_000), "world_0007");
        assert_eq!(world_name(7, 10_001), "world_00007");
        assert_eq!(world_name(0, 0), "world_0000");
    }

    #[test]
    fn shards_parse() {
        assert_eq!("1/4".parse::<Shard>().unwrap(), Shard { k: 1, n: 4 });
        for bad in ["4/4", "1", "a/2", "1/0", "-1/2"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn leftovers_are_recognised() {
        assert_eq!(leftover_index(".world_0007.tmp-123"), Some(7));
        assert_eq!(leftover_index(".world_0012.old-9"), Some(12));
        assert_eq!(leftover_index("world_0007"), None);
        assert_eq!(leftover_index(".world_x.tmp-1"), None);
    }
}
