//! How much memory the machine has free, and what a world needs while it
//! is built: a batch, an atlas or a single world that could not fit is
//! refused before it starts.

use crate::error::Error;

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
    options: &crate::options::WorldOptions,
    at_once: u64,
) -> Result<(), Error> {
    let Some(available) = available_bytes() else {
        return Ok(());
    };
    let per_world = crate::cost::batch_world_bytes(cells, options);
    let needed = per_world.saturating_mul(at_once);
    if needed > available {
        return Err(Error::TooBig {
            message: format!(
                "a world of {cells} cells with these options needs up to {} MiB while it is built ({WORLD_BYTES_PER_CELL} bytes per cell, and 8 per height-field sample), {at_once} at once: {} MiB, but {} MiB are available",
                per_world >> 20,
                needed >> 20,
                available >> 20
            ),
        });
    }
    Ok(())
}

/// `MemAvailable` of `/proc/meminfo`, bytes; `None` where it cannot be
/// read (not Linux).
pub fn available_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    parse_meminfo(&text)
}

fn parse_meminfo(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib.saturating_mul(1024))
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
}
