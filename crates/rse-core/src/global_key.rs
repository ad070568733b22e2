//! The global keys of a scheme as one enum: each key's name (in a scheme
//! file, the editor and Python; `--block-size` on the command line), its
//! unit, what its value must be, and one line of documentation. The CSV
//! reader, the patcher, the editor's schema, the command line and Python
//! read them here instead of matching strings of their own.

/// A `# key: value` global of a scheme file (docs/schemes.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum GlobalKey {
    /// `[nx, ny]` in cells.
    Size,
    /// Pallets along x and y, or off.
    Pallets,
    /// Pallet side in cells.
    PalletSize,
    /// Whether every pallet has a frame.
    PalletBoundary,
    /// Cell side, metres.
    BlockSize,
    /// One step, metres.
    StepHeight,
    /// The slab under the grid, metres.
    Base,
    /// Worlds in a batch.
    Amount,
    /// The batch's base seed.
    Seed,
}

impl GlobalKey {
    /// Every key, in the order a scheme file writes them.
    pub const ALL: [GlobalKey; 9] = [
        GlobalKey::Size,
        GlobalKey::Pallets,
        GlobalKey::PalletSize,
        GlobalKey::PalletBoundary,
        GlobalKey::BlockSize,
        GlobalKey::StepHeight,
        GlobalKey::Base,
        GlobalKey::Amount,
        GlobalKey::Seed,
    ];

    /// The key as a scheme file, the editor and Python's keywords spell it.
    pub const fn name(self) -> &'static str {
        match self {
            GlobalKey::Size => "size",
            GlobalKey::Pallets => "pallets",
            GlobalKey::PalletSize => "pallet_size",
            GlobalKey::PalletBoundary => "pallet_boundary",
            GlobalKey::BlockSize => "block_size",
            GlobalKey::StepHeight => "step_height",
            GlobalKey::Base => "base",
            GlobalKey::Amount => "amount",
            GlobalKey::Seed => "seed",
        }
    }

    /// The unit of its value, where it has one the editor shows.
    pub const fn unit(self) -> Option<&'static str> {
        match self {
            GlobalKey::BlockSize | GlobalKey::StepHeight | GlobalKey::Base => Some("m"),
            GlobalKey::Size | GlobalKey::PalletSize => Some("cells"),
            GlobalKey::Pallets => Some("pallets"),
            GlobalKey::Amount => Some("worlds"),
            GlobalKey::PalletBoundary | GlobalKey::Seed => None,
        }
    }

    /// What its text must be, as a parse error says it.
    pub const fn expects(self) -> &'static str {
        match self {
            GlobalKey::Size => "NXxNY, whole numbers of cells",
            GlobalKey::Pallets => "NXxNY pallets, or off",
            GlobalKey::PalletSize => "a whole number of cells",
            GlobalKey::PalletBoundary => "true or false",
            GlobalKey::BlockSize | GlobalKey::StepHeight | GlobalKey::Base => "a length in metres",
            GlobalKey::Amount => "a whole number of worlds",
            GlobalKey::Seed => "a whole number 0..=2^64-1",
        }
    }

    /// One line of documentation: the "value" column of docs/schemes.md's
    /// table of keys, without its backticks (the editor's tooltip; a test
    /// in rse-edit holds the two together).
    pub const fn doc(self) -> &'static str {
        match self {
            GlobalKey::Size => "NXxNY cells, used when pallets are off",
            GlobalKey::Pallets => "PXxPY pallets, or off",
            GlobalKey::PalletSize => "pallet side in cells, inside the frame (needs pallets)",
            GlobalKey::PalletBoundary => {
                "true/false: a 1-cell frame, 1 step high, around every pallet (needs pallets)"
            }
            GlobalKey::BlockSize => "cell side S in metres",
            GlobalKey::StepHeight => "height of one step in metres",
            GlobalKey::Base => "slab under the whole grid, metres",
            GlobalKey::Amount => "worlds in a batch",
            GlobalKey::Seed => "base seed of a batch, 0..2^64-1",
        }
    }

    /// The key spelt `name` in any case.
    pub fn find(name: &str) -> Option<GlobalKey> {
        GlobalKey::ALL
            .into_iter()
            .find(|key| key.name().eq_ignore_ascii_case(name))
    }
}

impl std::fmt::Display for GlobalKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Every key's name, in [`GlobalKey::ALL`] order.
pub const GLOBAL_KEYS: [&str; 9] = {
    let mut names = [""; 9];
    let mut i = 0;
    while i < names.len() {
        names[i] = GlobalKey::ALL[i].name();
        i += 1;
    }
    names
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_found_in_any_case_and_each_is_one_key() {
        for key in GlobalKey::ALL {
            assert_eq!(GlobalKey::find(key.name()), Some(key));
            assert_eq!(GlobalKey::find(&key.name().to_ascii_uppercase()), Some(key));
        }
        assert_eq!(GlobalKey::find("step-height"), None);
        let mut names = GLOBAL_KEYS.to_vec();
        names.dedup();
        assert_eq!(names.len(), GlobalKey::ALL.len());
    }
}
