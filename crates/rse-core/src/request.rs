//! What a user asks of one world: the seed, the index and the difficulty,
//! each optional, resolved against the scheme here, once. The command
//! line, Python and the editor pass what their user gave and `None` for
//! the rest, so "the scheme's `# seed:`" is a rule written in one place.

use crate::difficulty::Difficulty;
use crate::generate::generate_at;
use crate::scheme::Scheme;
use crate::terrain::Terrain;

/// One world as a user names it: `None` is "the default".
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WorldRequest {
    /// Base seed; default the scheme's `# seed:` (0 when it has none).
    pub seed: Option<u64>,
    /// Index in the batch; default 0.
    pub index: Option<u64>,
    /// Difficulty (validated by [`Difficulty::new`] where the user's number
    /// is read); default [`Difficulty::FULL`].
    pub difficulty: Option<Difficulty>,
}

/// A world resolved: which world of which batch, at which difficulty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldAt {
    /// Base seed: the batch this world belongs to.
    pub seed: u64,
    /// Index in the batch.
    pub index: u64,
    /// Difficulty the obstacles are scaled to.
    pub difficulty: Difficulty,
}

impl WorldRequest {
    /// The world `scheme` makes of this request, every unset field given
    /// its default.
    pub fn resolve(&self, scheme: &Scheme) -> WorldAt {
        WorldAt {
            seed: scheme.seed_or(self.seed),
            index: self.index.unwrap_or(0),
            difficulty: self.difficulty.unwrap_or(Difficulty::FULL),
        }
    }

    /// The terrain of this request's world of `scheme`.
    pub fn generate(&self, scheme: &Scheme) -> Terrain {
        let at = self.resolve(scheme);
        generate_at(scheme, at.seed, at.index, at.difficulty)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scheme_seed_rules_unless_a_seed_is_given() {
        let scheme =
            Scheme::from_csv("# size: 6x6\n# seed: 41\ntype,height\nrandom,3\n", None).unwrap();
        let unset = WorldRequest::default().resolve(&scheme);
        assert_eq!((unset.seed, unset.index), (41, 0));
        assert_eq!(unset.difficulty, Difficulty::FULL);
        let given = WorldRequest {
            seed: Some(2),
            index: Some(5),
            difficulty: Some(Difficulty::new(0.5).unwrap()),
        };
        assert_eq!(
            given.generate(&scheme),
            generate_at(&scheme, 2, 5, Difficulty::new(0.5).unwrap())
        );
        assert_eq!(
            WorldRequest::default().generate(&scheme),
            crate::generate(&scheme, 41, 0)
        );
    }
}
