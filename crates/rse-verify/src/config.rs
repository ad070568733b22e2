//! What a user gives `check` (ruff's configuration pattern, as
//! `rse_world::BatchConfig`): each setting an `Option` the command line
//! and Python fill with what their user gave, and one
//! [`resolve`](CheckConfig::resolve) that applies the defaults and the
//! checks that need the build or the disk (physics compiled in, a
//! template folder that loads).

use std::path::PathBuf;
use std::sync::Arc;

use rse_world::Templates;

use crate::budget::Budget;
use crate::physics::physics_unavailable;
use crate::world::CheckOptions;

/// `check`'s settings as given: `None` is the default.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CheckConfig {
    /// Drop bodies on each terrain; default no.
    pub physics: Option<bool>,
    /// Fail a world whose files could be compared by hash only; default no.
    pub strict: Option<bool>,
    /// A template folder the worlds were made with; default ours.
    pub template: Option<PathBuf>,
    /// The rebuild budget (parsed and checked by [`Budget`]'s own
    /// constructor, where the user's number is read); default 1.
    pub budget: Option<Budget>,
}

/// Why a check cannot start as configured; each names its setting.
#[derive(Debug, thiserror::Error)]
pub enum CheckConfigError {
    /// Physics asked of a build without it.
    #[error("physics: {0}")]
    NoPhysics(&'static str),
    /// The template folder does not load.
    #[error("template: {0}")]
    Template(#[from] rse_world::Error),
}

impl CheckConfig {
    /// The options a check runs with.
    pub fn resolve(self) -> Result<CheckOptions, CheckConfigError> {
        let physics = self.physics.unwrap_or(false);
        if let Some(why) = physics_unavailable().filter(|_| physics) {
            return Err(CheckConfigError::NoPhysics(why));
        }
        let templates = match &self.template {
            Some(dir) => Some(Arc::new(Templates::with_overrides(dir)?)),
            None => None,
        };
        Ok(CheckOptions {
            physics,
            strict: self.strict.unwrap_or(false),
            templates,
            budget: self.budget.unwrap_or_default(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unset_settings_are_the_defaults() {
        let options = CheckConfig::default().resolve().unwrap();
        assert!(!options.physics && !options.strict && options.templates.is_none());
        assert_eq!(options.budget, Budget::default());
    }

    #[test]
    fn a_template_folder_that_does_not_load_is_named() {
        let config = CheckConfig {
            template: Some(PathBuf::from("/no/such/templates")),
            ..CheckConfig::default()
        };
        let err = config.resolve().unwrap_err().to_string();
        assert!(err.starts_with("template: "), "{err}");
    }

    #[test]
    fn physics_is_refused_only_by_a_build_without_it() {
        let config = CheckConfig {
            physics: Some(true),
            ..CheckConfig::default()
        };
        assert_eq!(config.resolve().is_ok(), crate::PHYSICS);
    }
}
