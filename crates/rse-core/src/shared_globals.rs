//! The one rule for what schemes put together must share: the slots of a
//! mix of env terrains, the tiles of an atlas. Written as a destructure
//! of every field of [`Globals`], so a key added to the table stops the
//! build here until someone decides whether schemes put together share it.

use crate::global_key::GlobalKey;
use crate::global_value::GlobalText as _;
use crate::globals::Globals;

/// How schemes are put together.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Together {
    /// The env terrains of a mix: each slot one scheme's terrain, padded to
    /// the largest grid.
    Mix,
    /// An atlas: every scheme's tiles side by side in one terrain.
    Atlas,
}

/// A global that two schemes put together do not share.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unshared {
    /// The key (`size` for the grid, however the schemes make it).
    pub key: GlobalKey,
    /// The other scheme's value, as a scheme file writes it.
    pub found: String,
    /// The first scheme's.
    pub expected: String,
}

/// The first global that `other` does not share with `first` where
/// schemes go `together`, if any. Values compare bit for bit: one
/// sample spacing, one step.
pub fn unshared(first: &Globals, other: &Globals, together: Together) -> Option<Unshared> {
    // Every field, each with its rule: a new one is a compile error here.
    let Globals {
        // One sample spacing: a mix's slots and an atlas's tiles are
        // sampled on one lattice.
        block_size,
        // An atlas is one terrain, of one step and one slab; a mix's
        // terrains each keep their own.
        step_height,
        base,
        // An atlas's tiles sit side by side, one grid each (compared as
        // the grid they make, pallets or not); a mix's slots are padded to
        // the largest.
        size: _,
        pallets: _,
        // Drawn as the first scheme's colours, in either.
        color: _,
        ground_color: _,
        // The batch's, not the terrain's.
        amount: _,
        seed: _,
    } = *first;
    let differs = |key, found: f64, expected: f64| {
        (found.to_bits() != expected.to_bits()).then(|| Unshared {
            key,
            found: found.global_text(),
            expected: expected.global_text(),
        })
    };
    let shared_by_all = differs(GlobalKey::BlockSize, other.block_size, block_size);
    if together == Together::Mix || shared_by_all.is_some() {
        return shared_by_all;
    }
    let (grid, expected_grid) = (other.grid(), first.grid());
    differs(GlobalKey::StepHeight, other.step_height, step_height)
        .or_else(|| differs(GlobalKey::Base, other.base, base))
        .or_else(|| {
            ((grid.nx, grid.ny) != (expected_grid.nx, expected_grid.ny)).then(|| Unshared {
                key: GlobalKey::Size,
                found: format!("{}x{}", grid.nx, grid.ny),
                expected: format!("{}x{}", expected_grid.nx, expected_grid.ny),
            })
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mix_shares_the_block_size_and_an_atlas_the_terrains_units_and_grid() {
        let first = Globals::default();
        let other = |edit: fn(&mut Globals)| {
            let mut g = first;
            edit(&mut g);
            g
        };
        let finer = other(|g| g.block_size = 0.05);
        let steeper = other(|g| g.step_height = 0.2);
        let larger = other(|g| g.size = [12, 10]);
        let painted = other(|g| g.color = crate::Color::LIGHT_GREY);
        for together in [Together::Mix, Together::Atlas] {
            let found = unshared(&first, &finer, together).unwrap();
            assert_eq!(
                (found.key, found.found.as_str()),
                (GlobalKey::BlockSize, "0.05")
            );
            assert_eq!(unshared(&first, &painted, together), None);
        }
        assert_eq!(unshared(&first, &steeper, Together::Mix), None);
        assert_eq!(unshared(&first, &larger, Together::Mix), None);
        let step = unshared(&first, &steeper, Together::Atlas).unwrap();
        assert_eq!(step.key, GlobalKey::StepHeight);
        let grid = unshared(&first, &larger, Together::Atlas).unwrap();
        assert_eq!(
            (grid.key, grid.found.as_str(), grid.expected.as_str()),
            (GlobalKey::Size, "12x10", "10x10")
        );
    }
}
