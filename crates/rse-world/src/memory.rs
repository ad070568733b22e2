//! How much memory the machine has free, and what a world needs while it
//! is built: a batch, an atlas or a single world that could not fit is
//! refused before it starts.

use crate::error::Error;
use crate::record::options::{MujocoCollider, Target, WorldOptions};

/// Memory one world may take while it is built, per cell of its grid:
/// heightmap, mesh, box set and every file in memory. Measured at about
/// 1.4 KiB (single mesh) and 1.8 KiB (blocks) per cell on a 1000×1000
/// random field of height 4 with every target, the worst case there is.
pub const WORLD_BYTES_PER_CELL: u64 = 2048;

/// Refuses to build `at_once` worlds of `cells` cells with `options` at
/// the same time when they need more than the memory available (where
/// that can be read): [`WORLD_BYTES_PER_CELL`] a cell, and a height
/// field's samples (`cells·k²`) where the `MuJoCo` target has one.
pub(crate) fn check_memory_for(
    cells: u64,
    options: &WorldOptions,
    at_once: u64,
) -> Result<(), Error> {
    let Some(available) = available_bytes() else {
        return Ok(());
    };
    let per_world = batch_world_bytes(cells, options);
    let needed = per_world.saturating_mul(at_once);
    if needed > available {
        return Err(Error::TooBig {
            message: format!(
                "a world of {cells} cells with these options needs up to {} MiB while it is built ({WORLD_BYTES_PER_CELL} bytes per cell, and {BYTES_PER_SAMPLE} per height-field sample), {at_once} at once: {} MiB, but {} MiB are available",
                per_world >> 20,
                needed >> 20,
                available >> 20
            ),
        });
    }
    Ok(())
}

/// A height-field sample while a world is built: the float samples and
/// the encoded file.
pub(crate) const BYTES_PER_SAMPLE: u64 = 8;

/// Height-field samples a world of `cells` cells holds (`cells·k²`, the
/// extra row and column aside), when its `MuJoCo` target collides with one.
pub(crate) fn hfield_samples(options: &WorldOptions, cells: u64) -> u64 {
    match options.mujoco_collider {
        MujocoCollider::Hfield { oversample } if options.targets.contains(Target::Mujoco) => {
            let k = u64::from(oversample);
            cells.saturating_mul(k.saturating_mul(k))
        }
        _ => 0,
    }
}

/// The memory one world takes while a batch builds it, before it is
/// generated: [`WORLD_BYTES_PER_CELL`](crate::WORLD_BYTES_PER_CELL) a cell
/// and its height field's samples.
pub(crate) fn batch_world_bytes(cells: u64, options: &WorldOptions) -> u64 {
    cells
        .saturating_mul(WORLD_BYTES_PER_CELL)
        .saturating_add(hfield_samples(options, cells).saturating_mul(BYTES_PER_SAMPLE))
}

/// The memory this process may still take, bytes: `MemAvailable` of
/// `/proc/meminfo`, or less where an address-space limit (`ulimit -v`,
/// `prlimit --as`) leaves less room above what the process maps already
/// (a batch under `--as=1e9` was refused nothing, then aborted in an
/// allocation); `None` where neither can be read (not Linux).
pub fn available_bytes() -> Option<u64> {
    let free = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| parse_meminfo(&text));
    let room = address_space_room();
    match (free, room) {
        (Some(free), Some(room)) => Some(free.min(room)),
        (free, room) => free.or(room),
    }
}

/// What the soft address-space limit leaves above the process's mapped
/// size (`VmSize`), bytes; `None` without a limit or where it cannot be read.
fn address_space_room() -> Option<u64> {
    let limit = parse_address_space_limit(&std::fs::read_to_string("/proc/self/limits").ok()?)?;
    let mapped = parse_vm_size(&std::fs::read_to_string("/proc/self/status").ok()?)?;
    Some(limit.saturating_sub(mapped))
}

/// The soft limit of "Max address space" in `/proc/self/limits`, bytes;
/// `None` when unlimited.
fn parse_address_space_limit(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    line.trim_start_matches("Max address space")
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// `VmSize` of `/proc/self/status`, bytes.
fn parse_vm_size(text: &str) -> Option<u64> {
    kib_field(text, "VmSize:")
}

/// The line of `text` that starts with `key` (`/proc`'s `Key:  N kB`), its
/// number in bytes.
fn kib_field(text: &str, key: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}

fn parse_meminfo(text: &str) -> Option<u64> {
    kib_field(text, "MemAvailable:")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mem_available_is_read_in_bytes() {
        let text = "MemTotal:       24000000 kB\nMemFree:  100 kB\nMemAvailable:   20000000 kB\n";
        assert_eq!(parse_meminfo(text), Some(20_000_000 * 1024));
        assert_eq!(parse_meminfo("MemTotal: 1 kB\n"), None);
    }

    #[test]
    fn an_address_space_limit_and_the_mapped_size_are_read_in_bytes() {
        let limited = "Limit                     Soft Limit           Hard Limit           Units\nMax stack size            8388608              unlimited            bytes\nMax address space         1000000000           unlimited            bytes\n";
        assert_eq!(parse_address_space_limit(limited), Some(1_000_000_000));
        let free = limited.replace("1000000000  ", "unlimited   ");
        assert_eq!(parse_address_space_limit(&free), None);
        assert_eq!(
            parse_vm_size("Name:\trse-gen\nVmPeak:\t  9 kB\nVmSize:\t  2048 kB\n"),
            Some(2048 * 1024)
        );
    }
}
