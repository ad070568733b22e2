//! The disk a batch needs, and the disk free where it goes: the editor
//! refuses a batch that could not fit before it writes a world (one of
//! 2⁶⁴ − 1 worlds asked from the page once wrote until the disk was full).

use std::path::Path;

use rse_core::Scheme;

use crate::batch::BatchOptions;
use crate::error::Error;
use crate::render::templates::Templates;
use crate::render::world::build_world;

/// What a folder and its entry take on disk beside the bytes of its files
/// (an inode and a directory block, rounded up).
const BYTES_PER_FILE: u64 = 4096;

/// Worlds built in memory to price a batch: its first ones, the largest
/// counted for every world (worlds of one scheme differ by their draws).
const SAMPLED_WORLDS: u64 = 2;

/// The bytes `options`' batch of `scheme` would write (every world of its
/// shard, none skipped): its first worlds built in memory, the largest
/// times the worlds, each file rounded up to a disk block. A batch that
/// would not fit in memory is refused first, as `write_batch` refuses it.
pub fn batch_disk_bytes(
    scheme: &Scheme,
    templates: &Templates,
    options: &BatchOptions,
) -> Result<u64, Error> {
    // Built here only if the batch would fit in memory (it is refused
    // otherwise, naming what to reduce).
    crate::batch::check_memory(scheme, options)?;
    let worlds = options.shard.worlds(options.amount);
    let mut largest = 0u64;
    let shard = options.shard;
    let first = (0..SAMPLED_WORLDS)
        .map(|i| shard.k().saturating_add(i.saturating_mul(shard.n())))
        .filter(|&index| index < options.amount);
    for index in first {
        let world = build_world(
            scheme,
            options.seed,
            index,
            crate::batch::world_name(index),
            &options.world,
            templates,
        )?;
        let bytes = world
            .files
            .values()
            .map(|bytes| (bytes.len() as u64).div_ceil(BYTES_PER_FILE) * BYTES_PER_FILE)
            .fold(BYTES_PER_FILE, u64::saturating_add);
        largest = largest.max(bytes);
    }
    Ok(largest.saturating_mul(worlds))
}

/// The bytes free to this user on the file system that holds `path` (or
/// the nearest folder above it that exists); `None` where that cannot be
/// read.
pub fn free_disk_bytes(path: &Path) -> Option<u64> {
    let mut at = Some(path);
    while let Some(here) = at {
        if here.exists() {
            let stat = rustix::fs::statvfs(here).ok()?;
            return Some(stat.f_bavail.saturating_mul(stat.f_frsize));
        }
        at = here.parent().filter(|p| !p.as_os_str().is_empty());
    }
    let stat = rustix::fs::statvfs(".").ok()?;
    Some(stat.f_bavail.saturating_mul(stat.f_frsize))
}
