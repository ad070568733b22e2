//! Many worlds at once: the world folders under the paths given (a folder
//! holding `rse.json` is a world, any other a batch of them), checked in
//! parallel, with the faults of a batch as a whole — folders left by a run
//! that was cut short, and the same world twice.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use rse_world::{Leftover, MANIFEST, Manifest, what_differs};
use serde::Serialize;

use crate::fault::{Fault, FaultKind, NotAWorld};
use crate::world::{CheckOptions, WorldReport, check_world};

/// A whole `check` run.
#[derive(Debug, Clone, Serialize)]
pub struct CheckReport {
    /// One report per world, in the order found (paths as given, each
    /// batch's worlds sorted by name).
    pub worlds: Vec<WorldReport>,
    /// Faults of batches as wholes (leftover temporary folders, duplicate
    /// worlds), with the batch folder in `file`.
    pub batch_faults: Vec<Fault>,
    /// How many world folders were checked (each a world of some batch).
    pub checked: usize,
    /// Worlds with at least one fault.
    pub failed: usize,
    /// Good worlds some of whose files could be compared only with their
    /// hashes (rendered from templates this check did not have).
    pub worlds_hashed_only: usize,
}

impl CheckReport {
    /// `true` when no world and no batch has a fault.
    pub fn ok(&self) -> bool {
        self.failed == 0 && self.batch_faults.is_empty()
    }

    /// `checked N worlds: G good, F failed`, and the batch faults' count
    /// when there are any: the verdict the CLI and the editor print.
    pub fn verdict(&self) -> String {
        let mut line = format!(
            "checked {} {}: {} good",
            self.checked,
            if self.checked == 1 { "world" } else { "worlds" },
            self.checked - self.failed,
        );
        if self.worlds_hashed_only > 0 {
            let _ = write!(line, " ({} only by hash)", self.worlds_hashed_only);
        }
        let _ = write!(line, ", {} failed", self.failed);
        if !self.batch_faults.is_empty() {
            let _ = write!(line, "; {} batch faults", self.batch_faults.len());
        }
        line
    }
}

impl CheckReport {
    /// The first fault found, with its world: batch faults first, then the
    /// worlds in order.
    pub fn first_fault(&self) -> Option<String> {
        if let Some(fault) = self.batch_faults.first() {
            return Some(fault.to_string());
        }
        let world = self.worlds.iter().find(|r| !r.ok)?;
        Some(format!("{}: {}", world.world, world.faults.first()?))
    }
}

/// A path given to `check` that is not a world or a batch of worlds.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DiscoverError {
    /// The path is not a folder.
    #[error("{} is not a folder", .0.display())]
    NotAFolder(PathBuf),
    /// The folder cannot be listed.
    #[error("cannot read {}: {reason}", path.display())]
    Unreadable {
        /// The path the user gave, which is not a folder.
        path: PathBuf,
        /// The system's reason.
        reason: String,
    },
    /// `--physics` was asked of a world the smoke test cannot judge.
    #[error("--physics: {}: {reason}", world.display())]
    PhysicsRefused {
        /// The world.
        world: PathBuf,
        /// Why (its block size, and what to do).
        reason: String,
    },
    /// Neither the folder nor any of its sub-folders holds `rse.json`.
    #[error("{} holds no world (no rse.json in it or in its sub-folders)", .0.display())]
    NoWorld(PathBuf),
}

/// The worlds under `paths`, with the batch faults found on the way. A
/// batch folder is taken whole: each of its sub-folders is a world (holds
/// `rse.json`), a leftover of a run cut short, or a fault — a folder that
/// lost its `rse.json` or never was a world, a link (never followed), a
/// special file. Hidden entries and plain files (a report saved beside the
/// worlds, the batch's lock) are not worlds and are let be.
pub fn discover(paths: &[PathBuf]) -> Result<(Vec<PathBuf>, Vec<Fault>), DiscoverError> {
    let mut worlds = Vec::new();
    let mut faults = Vec::new();
    for path in paths {
        if !path.is_dir() {
            return Err(DiscoverError::NotAFolder(path.clone()));
        }
        if path.join(MANIFEST).exists() {
            // A world named directly: its own leftovers lie beside it.
            faults.extend(leftovers_of_world(path));
            worlds.push(path.clone());
            continue;
        }
        let unreadable = |e: std::io::Error| DiscoverError::Unreadable {
            path: path.clone(),
            reason: e.to_string(),
        };
        let mut found = Vec::new();
        let mut strays: Vec<(String, FaultKind)> = Vec::new();
        for entry in std::fs::read_dir(path).map_err(unreadable)? {
            let entry = entry.map_err(unreadable)?;
            let name = entry.file_name().to_string_lossy().into_owned();
            // The entry itself, never a link's target.
            let kind = entry.file_type().map_err(unreadable)?;
            // A leftover may be a plain file: what `force` moved aside.
            let leftover = Leftover::world_of(&name).is_some();
            if !leftover && (name.starts_with('.') || kind.is_file()) {
                continue; // not a world, and let be
            }
            if leftover {
                strays.push((name, FaultKind::Leftover));
            } else if kind.is_dir() && entry.path().join(MANIFEST).symlink_metadata().is_ok() {
                found.push(entry.path());
            } else if kind.is_dir() {
                strays.push((
                    name,
                    FaultKind::NotAWorld {
                        reason: NotAWorld::NoManifest,
                    },
                ));
            } else if kind.is_symlink() {
                strays.push((
                    name,
                    FaultKind::NotAWorld {
                        reason: NotAWorld::Link,
                    },
                ));
            } else {
                strays.push((name, FaultKind::NotAFile));
            }
        }
        if found.is_empty() && strays.is_empty() {
            return Err(DiscoverError::NoWorld(path.clone()));
        }
        // By length, then text: world_9999 before world_10000.
        found.sort_by_key(|p| (p.as_os_str().len(), p.clone()));
        strays.sort_by(|a, b| a.0.cmp(&b.0));
        faults.extend(
            strays
                .into_iter()
                .map(|(name, kind)| Fault::of(&path.join(name).display().to_string(), kind)),
        );
        worlds.extend(found);
    }
    // A world named twice (directly and inside its batch folder, or a
    // folder given twice) is one world, checked once: never reported as a
    // duplicate of itself, nor a leftover beside it twice.
    let canonical =
        |path: &Path| std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    let mut seen = std::collections::HashSet::new();
    worlds.retain(|world| seen.insert(canonical(world)));
    let mut seen = std::collections::HashSet::new();
    faults.retain(|fault| {
        let at = fault.file.as_deref().map(|f| canonical(Path::new(f)));
        seen.insert((at, fault.message.clone()))
    });
    Ok((worlds, faults))
}

/// The leftover temporary folders of the world folder `world` in its parent
/// (`.atlas.tmp-PID` beside `atlas`), as faults.
fn leftovers_of_world(world: &Path) -> Vec<Fault> {
    let (Some(parent), Some(name)) = (world.parent(), world.file_name().and_then(|n| n.to_str()))
    else {
        return Vec::new();
    };
    let parent = if parent.as_os_str().is_empty() {
        Path::new(".")
    } else {
        parent
    };
    let Ok(entries) = std::fs::read_dir(parent) else {
        return Vec::new();
    };
    let mut found: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .filter(|e| e.file_name().to_str().and_then(Leftover::world_of) == Some(name))
        .map(|e| world.with_file_name(e.file_name()))
        .collect();
    found.sort();
    found
        .into_iter()
        .map(|path| Fault::of(&path.display().to_string(), FaultKind::Leftover))
        .collect()
}

/// Checks every world under `paths` in parallel (on rayon's current pool),
/// calling `progress` after each world.
pub fn check_paths(
    paths: &[PathBuf],
    options: &CheckOptions,
    progress: &(dyn Fn() + Sync),
) -> Result<CheckReport, DiscoverError> {
    let (worlds, mut batch_faults) = discover(paths)?;
    let check_one = |world: &PathBuf| {
        let report = check_world(world, options);
        progress();
        report
    };
    let check_all = || -> Vec<WorldReport> { worlds.par_iter().map(check_one).collect() };
    // Each world's budget is the whole memory available; fewer are
    // checked at once where the threads' worth would not fit in it.
    let at_once = worlds_at_once(&worlds, options);
    let reports = if at_once < rayon::current_num_threads() {
        match rayon::ThreadPoolBuilder::new().num_threads(at_once).build() {
            Ok(pool) => pool.install(check_all),
            Err(_) => worlds.iter().map(check_one).collect(),
        }
    } else {
        check_all()
    };
    // A world physics cannot judge refuses the command, by name: checked
    // without physics it would pass, with it no verdict would be honest.
    if let Some((world, reason)) = worlds
        .iter()
        .zip(&reports)
        .find_map(|(world, r)| Some((world, r.physics_refused.as_ref()?)))
    {
        return Err(DiscoverError::PhysicsRefused {
            world: world.clone(),
            reason: reason.clone(),
        });
    }
    batch_faults.extend(duplicates(&worlds, &reports));
    batch_faults.extend(mixed_recipes(&worlds, &reports));
    let failed = reports.iter().filter(|r| !r.ok).count();
    let worlds_hashed_only = reports
        .iter()
        .filter(|r| r.ok && !r.hashed_only.is_empty())
        .count();
    Ok(CheckReport {
        checked: reports.len(),
        failed,
        worlds_hashed_only,
        worlds: reports,
        batch_faults,
    })
}

/// How many of `worlds` to check at once: one a thread of rayon's current
/// pool, no more than the memory available holds together, the largest
/// first, each priced from its recipe (a world is at least one). Once the
/// budget was the memory divided by the threads: on 128 threads a fresh
/// world failed `check` with 21 GB available.
fn worlds_at_once(worlds: &[PathBuf], options: &CheckOptions) -> usize {
    let threads = rayon::current_num_threads().min(worlds.len());
    if threads <= 1 {
        return 1;
    }
    let bytes: Vec<u64> = worlds
        .par_iter()
        .map(|world| crate::world::recipe_bytes(world, options))
        .collect();
    fitting_at_once(bytes, threads, crate::limits::rebuild_bytes())
}

/// How many of worlds priced `bytes` fit in `available` at once, the
/// largest first: at least 1, at most `threads`.
fn fitting_at_once(mut bytes: Vec<u64>, threads: usize, available: u64) -> usize {
    bytes.sort_unstable_by(|a, b| b.cmp(a));
    let mut held = 0u64;
    let fit = bytes
        .iter()
        .take(threads)
        .take_while(|&&b| {
            held = held.saturating_add(b);
            held <= available
        })
        .count();
    fit.max(1)
}

/// Worlds of one batch folder with the same seed pair: one world written
/// twice (under two names, as a grown batch once did).
fn duplicates(worlds: &[PathBuf], reports: &[WorldReport]) -> Vec<Fault> {
    let mut first: BTreeMap<(Option<&Path>, u64, u64), &Path> = BTreeMap::new();
    let mut faults = Vec::new();
    for (world, report) in worlds.iter().zip(reports) {
        let (Some(seed), Some(index)) = (report.seed, report.index) else {
            continue;
        };
        match first.entry((world.parent(), seed, index)) {
            std::collections::btree_map::Entry::Vacant(slot) => {
                slot.insert(world);
            }
            std::collections::btree_map::Entry::Occupied(slot) => faults.push(Fault::of(
                &world.display().to_string(),
                FaultKind::Duplicate {
                    of: slot.get().display().to_string(),
                },
            )),
        }
    }
    faults
}

/// Worlds of one batch folder made from different recipes (scheme, seed,
/// options, templates, version): shards written with different seeds into
/// one folder, or a world copied in from another batch. Each world unlike
/// the batch's first is named, with the first setting that differs.
fn mixed_recipes(worlds: &[PathBuf], reports: &[WorldReport]) -> Vec<Fault> {
    let mut first: BTreeMap<Option<&Path>, (&Path, &Manifest)> = BTreeMap::new();
    let mut faults = Vec::new();
    for (world, report) in worlds.iter().zip(reports) {
        // An atlas is a world of its own recipe, not one of a batch's; a
        // world with faults of its own is reported for them, its recipe
        // not trusted.
        let manifest = report.manifest.as_deref().filter(|_| report.ok);
        let Some(manifest) = manifest.filter(|m| m.atlas.is_none()) else {
            continue;
        };
        let Some(&(other, theirs)) = first.get(&world.parent()) else {
            first.insert(world.parent(), (world, manifest));
            continue;
        };
        // The index and name are each world's own; everything else is the batch's.
        let mut alike = manifest.clone();
        alike.index = theirs.index;
        alike.world.clone_from(&theirs.world);
        if let Some(difference) = what_differs(theirs, &alike) {
            faults.push(Fault::of(
                &world.display().to_string(),
                FaultKind::MixedRecipes {
                    first: other.display().to_string(),
                    difference,
                },
            ));
        }
    }
    faults
}

#[cfg(test)]
mod tests {
    use super::fitting_at_once;

    /// As many worlds at once as the memory holds, the largest first; one
    /// however large it is, never more than the threads.
    #[test]
    fn as_many_worlds_at_once_as_the_memory_holds() {
        assert_eq!(fitting_at_once(vec![3, 3, 3, 3], 128, 10), 3);
        assert_eq!(fitting_at_once(vec![1, 9, 1, 1], 128, 10), 2);
        assert_eq!(fitting_at_once(vec![1; 100], 8, 1000), 8);
        assert_eq!(fitting_at_once(vec![50], 128, 10), 1);
        assert_eq!(fitting_at_once(vec![u64::MAX, u64::MAX], 2, 10), 1);
    }
}
