//! What a user gives a world or a batch, as ruff's configuration pattern
//! has it: a `*Config` of `Option`s that each front end (the command line,
//! Python, the editor) fills with what its user gave and nothing else, and
//! one [`resolve`](BatchConfig::resolve) that applies the scheme's values,
//! the defaults and every check. "The user's value, else the scheme's" is
//! written here, once.

use std::path::PathBuf;

use rse_core::{DifficultyRule, Scheme};

use crate::batch::{BatchOptions, Shard};
use crate::error::Error;
use crate::record::options::{MujocoCollider, WorldOptions};
use crate::world_option::{ColliderName, WorldConfig};

/// `WorldConfig::resolve` from the table of world options
/// ([`for_each_world_option`](crate::for_each_world_option)): each
/// recorded option resolved by its entry's `resolve` (`given`, or a method
/// below). Munches the table entry by entry.
macro_rules! declare_resolve {
    (@munch [$($record:ident = $resolve:ident($field:ident);)*]) => {
        impl WorldConfig {
            /// The world options: defaults for what is unset; a value out
            /// of its range, an unknown collider, or an oversample without a
            /// height field, is refused.
            pub fn resolve(self) -> Result<WorldOptions, Error> {
                self.check_ranges()?;
                let defaults = WorldOptions::default();
                let difficulty = self.difficulty.unwrap_or(defaults.difficulty);
                Ok(WorldOptions {
                    difficulty,
                    // Recorded only below 1, so full worlds keep their bytes.
                    difficulty_rule: (!difficulty.is_full()).then_some(DifficultyRule::CURRENT),
                    $($record: resolved!($resolve, self, defaults, $field, $record),)*
                })
            }
        }
    };
    (@munch [$($values:tt)*]
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty {
            record: none,
            $($after:tt)*
        }
        $($rest:tt)*
    ) => {
        declare_resolve!(@munch [$($values)*] $($rest)*);
    };
    (@munch [$($values:tt)*]
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty {
            record: { field: $record:ident: $record_ty:ty, resolve: $resolve:ident, serde: ($($serde:tt)*) },
            $($after:tt)*
        }
        $($rest:tt)*
    ) => {
        declare_resolve!(@munch
            [$($values)* $record = $resolve($field);]
            $($rest)*);
    };
    ($($table:tt)*) => {
        declare_resolve!(@munch [] $($table)*);
    };
}

/// A recorded option's value: `given` (the value given, else the
/// default's), or a method of `WorldConfig` that resolves it.
macro_rules! resolved {
    (given, $config:ident, $defaults:ident, $field:ident, $record:ident) => {
        $config.$field.clone().unwrap_or($defaults.$record)
    };
    ($method:ident, $config:ident, $defaults:ident, $field:ident, $record:ident) => {
        $config.$method()?
    };
}

crate::for_each_world_option!(declare_resolve);

impl WorldConfig {
    /// The `MuJoCo` collider: its name (boxes by default) with the
    /// oversample, which only a height field takes.
    fn resolve_mujoco_collider(&self) -> Result<MujocoCollider, Error> {
        let name = self
            .mujoco_collider
            .as_ref()
            .map_or(MujocoCollider::default().name(), ColliderName::as_str);
        MujocoCollider::parse(name, self.oversample)
    }
}

/// A batch, as given: `None` is the scheme's value or the default.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BatchConfig {
    /// Worlds in the whole batch; default the scheme's `# amount:`.
    pub amount: Option<u64>,
    /// The batch's base seed; default the scheme's `# seed:`.
    pub seed: Option<u64>,
    /// What each world folder holds.
    pub world: WorldConfig,
    /// Worker threads; default one per core (0 is refused).
    pub jobs: Option<usize>,
    /// The part of the batch this run writes; default all of it.
    pub shard: Option<Shard>,
    /// Replace world folders that hold something else; default no.
    pub force: Option<bool>,
}

impl BatchConfig {
    /// The batch of `scheme` into `out`: the user's values, else the
    /// scheme's (`# amount:`, `# seed:`), else the defaults; every option
    /// checked.
    pub fn resolve(self, scheme: &Scheme, out: impl Into<PathBuf>) -> Result<BatchOptions, Error> {
        if self.jobs == Some(0) {
            return Err(Error::BadOption {
                option: "jobs",
                message: "jobs must be at least 1".to_owned(),
            });
        }
        let globals = scheme.globals();
        Ok(BatchOptions {
            out: out.into(),
            amount: self.amount.unwrap_or(globals.amount),
            seed: scheme.seed_or(self.seed),
            world: self.world.resolve()?,
            jobs: self.jobs,
            shard: self.shard.unwrap_or_default(),
            force: self.force.unwrap_or(false),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::options::Targets;
    use crate::world_option::OptionValue as _;

    fn scheme() -> Scheme {
        Scheme::from_csv(
            "# size: 6x6\n# amount: 7\n# seed: 41\ntype,height\nrandom,2\n",
            None,
        )
        .unwrap()
    }

    #[test]
    fn the_users_values_win_then_the_schemes_then_the_defaults() {
        let unset = BatchConfig::default().resolve(&scheme(), "out").unwrap();
        assert_eq!((unset.amount, unset.seed), (7, 41));
        assert_eq!(unset.world, WorldOptions::default());
        assert_eq!(
            (unset.jobs, unset.shard, unset.force),
            (None, Shard::default(), false)
        );
        let given = BatchConfig {
            amount: Some(3),
            seed: Some(2),
            jobs: Some(2),
            force: Some(true),
            world: WorldConfig {
                targets: Some(Targets::all()),
                mujoco_collider: Some(ColliderName::parse_option("hfield").unwrap()),
                ..WorldConfig::default()
            },
            ..BatchConfig::default()
        }
        .resolve(&scheme(), "out")
        .unwrap();
        assert_eq!(
            (given.amount, given.seed, given.jobs, given.force),
            (3, 2, Some(2), true)
        );
        assert_eq!(given.world.targets, Targets::all());
        assert_eq!(
            given.world.mujoco_collider,
            MujocoCollider::Hfield {
                oversample: rse_core::DEFAULT_OVERSAMPLE
            }
        );
    }

    #[test]
    fn bad_options_are_refused_naming_them() {
        let jobs = BatchConfig {
            jobs: Some(0),
            ..BatchConfig::default()
        };
        assert!(
            jobs.resolve(&scheme(), "out")
                .unwrap_err()
                .to_string()
                .contains("jobs")
        );
        let oversample = WorldConfig {
            oversample: Some(2),
            ..WorldConfig::default()
        };
        let err = oversample.resolve().unwrap_err().to_string();
        assert!(err.contains("hfield"), "{err}");
    }
}
