//! Global parameters as a user gives them — a scheme file's `# key: value`
//! lines, command-line flags, Python keywords, the editor's fields — and the
//! one set of rules that turns them into [`Globals`] (the pallet rules live
//! here and nowhere else).

use crate::error::{SchemeError, SchemeErrorKind};
use crate::for_each_global_key;
use crate::global_key::GlobalKey;
use crate::globals::{self, Globals, Pallets};
use crate::limits::DEFAULT_PALLET_SIZE;

/// [`GlobalsPatch`], its `set_key`, `combine` and `given`, from the table
/// of [`for_each_global_key`].
macro_rules! declare_globals_patch {
    ($(
        $(#[doc = $what:literal])*
        $variant:ident {
            name: $name:literal,
            field: $field:ident: $ty:ty,
            unit: $unit:expr,
            expects: $expects:literal,
            doc: $doc:literal,
            flag: $flag:tt,
        }
    )*) => {
        /// Global parameters, each `None` when not given. Every skin fills
        /// one in and [`apply`](GlobalsPatch::apply)s it onto the globals it
        /// starts from (the defaults for a new scheme, the file's for
        /// command-line overrides, the scheme's own for Python's `replace`).
        #[derive(Debug, Clone, Copy, Default, PartialEq)]
        pub struct GlobalsPatch {
            $($(#[doc = $what])* pub $field: Option<$ty>,)*
        }

        impl GlobalsPatch {
            /// Sets `key` from its text as a scheme file writes it; the
            /// error's `field` names the key.
            pub fn set_key(&mut self, key: GlobalKey, text: &str) -> Result<(), SchemeError> {
                let expects = key.expects();
                let parsed = match key {
                    $(GlobalKey::$variant => {
                        <$ty as ParseGlobal>::parse_global(text, expects)
                            .map(|value| self.$field = Some(value))
                    })*
                };
                parsed.map_err(|reason: String| {
                    SchemeError::new(SchemeErrorKind::BadGlobal {
                        value: text.to_owned(),
                        reason,
                    })
                    .with_field(key.name())
                })
            }

            /// `self`'s values, each unset one taken from `other` (ruff's
            /// `combine`: the first given wins).
            #[must_use]
            pub fn combine(self, other: GlobalsPatch) -> GlobalsPatch {
                GlobalsPatch {
                    $($field: self.$field.or(other.$field),)*
                }
            }

            /// The keys given, in [`GlobalKey::ALL`] order.
            pub fn given(&self) -> Vec<GlobalKey> {
                let mut keys = Vec::new();
                $(if self.$field.is_some() {
                    keys.push(GlobalKey::$variant);
                })*
                keys
            }
        }
    };
}

for_each_global_key!(declare_globals_patch);

impl GlobalsPatch {
    /// Sets `key` (any case) from its text as a scheme file writes it. The
    /// error's `field` names the key. Returns the key.
    pub fn set(&mut self, key: &str, text: &str) -> Result<GlobalKey, SchemeError> {
        let Some(found) = GlobalKey::find(key) else {
            let kind = match globals::nearest_global(key) {
                Some(near) => SchemeErrorKind::NearGlobal {
                    found: key.to_owned(),
                    near,
                },
                None => SchemeErrorKind::UnknownGlobal(key.to_owned()),
            };
            return Err(SchemeError::new(kind).with_field(key));
        };
        self.set_key(found, text).map(|()| found)
    }

    /// `true` when nothing is given.
    pub fn is_empty(&self) -> bool {
        *self == GlobalsPatch::default()
    }

    /// `onto` with the given values. Pallets turned on keep the size and
    /// frame they had (else [`DEFAULT_PALLET_SIZE`] and a frame); a pallet
    /// setting with pallets off is refused (error field: its key) unless it
    /// is what pallets off means anyway (`pallet_boundary: false`, no frame).
    /// Domains and the grid size are checked by [`Globals::validate`], as
    /// every scheme is built.
    pub fn apply(&self, onto: &Globals) -> Result<Globals, SchemeError> {
        // Every field by name (no `..`): a key added to the table does not
        // compile until it is applied here.
        let GlobalsPatch {
            size,
            pallets,
            pallet_size,
            pallet_boundary,
            block_size,
            step_height,
            base,
            amount,
            seed,
        } = *self;
        let mut g = *onto;
        g.size = size.unwrap_or(g.size);
        match pallets {
            None => {}
            Some(None) => g.pallets = None,
            Some(Some(count)) => {
                g.pallets = Some(Pallets {
                    size: onto.pallets.map_or(DEFAULT_PALLET_SIZE, |p| p.size),
                    count,
                    boundary: onto.pallets.is_none_or(|p| p.boundary),
                });
            }
        }
        if let Some(p) = g.pallets.as_mut() {
            p.size = pallet_size.unwrap_or(p.size);
            p.boundary = pallet_boundary.unwrap_or(p.boundary);
        } else {
            let off = |key: GlobalKey| {
                Err(SchemeError::new(SchemeErrorKind::PalletsOff).with_field(key.name()))
            };
            if pallet_size.is_some() {
                return off(GlobalKey::PalletSize);
            }
            if pallet_boundary == Some(true) {
                return off(GlobalKey::PalletBoundary);
            }
        }
        g.block_size = block_size.unwrap_or(g.block_size);
        g.step_height = step_height.unwrap_or(g.step_height);
        g.base = base.unwrap_or(g.base);
        g.amount = amount.unwrap_or(g.amount);
        g.seed = seed.unwrap_or(g.seed);
        Ok(g)
    }
}

impl Globals {
    /// What `key` is when a user leaves it out, as its text: the default
    /// globals' value, and for the pallet keys what turning pallets on
    /// gives (the rule of [`GlobalsPatch::apply`]); `pallets` is `off`.
    ///
    /// # Panics
    /// Never: one pallet is a layout the rules always accept.
    pub fn default_text(key: GlobalKey) -> String {
        let defaults = Globals::default();
        let turned_on = || {
            GlobalsPatch {
                pallets: Some(Some([1, 1])),
                ..GlobalsPatch::default()
            }
            .apply(&defaults)
            .ok()
            .and_then(|g| g.pallets)
            .expect("one pallet is a valid layout")
        };
        match key {
            GlobalKey::Size => globals::format_dims(defaults.size),
            GlobalKey::Pallets => "off".to_owned(),
            GlobalKey::PalletSize => turned_on().size.to_string(),
            GlobalKey::PalletBoundary => turned_on().boundary.to_string(),
            GlobalKey::BlockSize => defaults.block_size.to_string(),
            GlobalKey::StepHeight => defaults.step_height.to_string(),
            GlobalKey::Base => defaults.base.to_string(),
            GlobalKey::Amount => defaults.amount.to_string(),
            GlobalKey::Seed => defaults.seed.to_string(),
        }
    }

    /// The `(key, text)` of each global a canonical scheme file writes, in
    /// [`GlobalKey::ALL`] order; [`GlobalsPatch::set`] reads each text back to
    /// the same value. Values equal to the defaults are left out where a
    /// reader would not miss them (`base`, `amount`, `seed`; `size` under
    /// pallets, which define the grid).
    pub fn cells(&self) -> Vec<(GlobalKey, String)> {
        let defaults = Globals::default();
        let unless_default = |differs: bool, text: String| differs.then_some(text);
        GlobalKey::ALL
            .into_iter()
            .filter_map(|key| {
                let text = match key {
                    GlobalKey::Size => unless_default(
                        self.pallets.is_none() || self.size != defaults.size,
                        globals::format_dims(self.size),
                    ),
                    GlobalKey::Pallets => self.pallets.map(|p| globals::format_dims(p.count)),
                    GlobalKey::PalletSize => self.pallets.map(|p| p.size.to_string()),
                    GlobalKey::PalletBoundary => self.pallets.map(|p| p.boundary.to_string()),
                    GlobalKey::BlockSize => Some(self.block_size.to_string()),
                    GlobalKey::StepHeight => Some(self.step_height.to_string()),
                    GlobalKey::Base => unless_default(
                        self.base.to_bits() != defaults.base.to_bits(),
                        self.base.to_string(),
                    ),
                    GlobalKey::Amount => {
                        unless_default(self.amount != defaults.amount, self.amount.to_string())
                    }
                    GlobalKey::Seed => {
                        unless_default(self.seed != defaults.seed, self.seed.to_string())
                    }
                };
                text.map(|text| (key, text))
            })
            .collect()
    }
}

/// A global's value read from its text, the parser picked by the value's
/// type (each key's type in the table is its own).
trait ParseGlobal: Sized {
    /// The value of `text`; `expects` says what it must be.
    fn parse_global(text: &str, expects: &str) -> Result<Self, String>;
}

/// `size`: `NXxNY`.
impl ParseGlobal for [u32; 2] {
    fn parse_global(text: &str, _: &str) -> Result<Self, String> {
        globals::parse_dims(text)
    }
}

/// `pallets`: a count, or off.
impl ParseGlobal for Option<[u32; 2]> {
    fn parse_global(text: &str, _: &str) -> Result<Self, String> {
        parse_pallets(text)
    }
}

impl ParseGlobal for bool {
    fn parse_global(text: &str, _: &str) -> Result<Self, String> {
        parse_bool(text)
    }
}

impl ParseGlobal for u32 {
    fn parse_global(text: &str, expects: &str) -> Result<Self, String> {
        parse_number(text, expects)
    }
}

impl ParseGlobal for u64 {
    fn parse_global(text: &str, expects: &str) -> Result<Self, String> {
        parse_number(text, expects)
    }
}

impl ParseGlobal for f64 {
    fn parse_global(text: &str, expects: &str) -> Result<Self, String> {
        parse_number(text, expects)
    }
}

/// `PXxPY`, or `off`/`none`/`false`/`no` for no pallets: the `pallets`
/// value of a scheme file, the editor and `--pallets` alike.
pub fn parse_pallets(value: &str) -> Result<Option<[u32; 2]>, String> {
    match value.trim().to_ascii_lowercase().as_str() {
        "off" | "none" | "false" | "no" => Ok(None),
        _ => match globals::parse_dims(value)? {
            dims if dims.contains(&0) => Err("needs at least one pallet each way".to_owned()),
            dims => Ok(Some(dims)),
        },
    }
}

/// `true`/`false`, `yes`/`no`, `on`/`off`, `1`/`0` (case-insensitive).
fn parse_bool(value: &str) -> Result<bool, String> {
    match value.trim().to_ascii_lowercase().as_str() {
        "true" | "yes" | "on" | "1" => Ok(true),
        "false" | "no" | "off" | "0" => Ok(false),
        _ => Err("expected true or false".to_owned()),
    }
}

fn parse_number<T: std::str::FromStr + IsFinite>(value: &str, what: &str) -> Result<T, String> {
    value
        .trim()
        .parse::<T>()
        .ok()
        .filter(IsFinite::is_finite_number)
        .ok_or_else(|| format!("expected {what}"))
}

/// Lets one parser refuse `inf` and `NaN`, which `f64::from_str` accepts.
trait IsFinite {
    fn is_finite_number(&self) -> bool;
}

impl IsFinite for f64 {
    fn is_finite_number(&self) -> bool {
        self.is_finite()
    }
}

impl IsFinite for u32 {
    fn is_finite_number(&self) -> bool {
        true
    }
}

impl IsFinite for u64 {
    fn is_finite_number(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn patch(pairs: &[(&str, &str)]) -> GlobalsPatch {
        let mut p = GlobalsPatch::default();
        for (k, v) in pairs {
            p.set(k, v).unwrap();
        }
        p
    }

    #[test]
    fn pallets_turned_on_get_the_default_size_and_a_frame() {
        let g = patch(&[("pallets", "2x3")])
            .apply(&Globals::default())
            .unwrap();
        assert_eq!(
            g.pallets,
            Some(Pallets {
                size: DEFAULT_PALLET_SIZE,
                count: [2, 3],
                boundary: true
            })
        );
    }

    #[test]
    fn pallets_recounted_keep_their_size_and_frame() {
        let onto = patch(&[
            ("pallets", "1x1"),
            ("pallet_size", "8"),
            ("pallet_boundary", "no"),
        ])
        .apply(&Globals::default())
        .unwrap();
        let g = patch(&[("pallets", "3x3")]).apply(&onto).unwrap();
        assert_eq!(
            g.pallets,
            Some(Pallets {
                size: 8,
                count: [3, 3],
                boundary: false
            })
        );
        assert_eq!(
            patch(&[("pallets", "off")]).apply(&onto).unwrap().pallets,
            None
        );
    }

    #[test]
    fn a_pallet_setting_without_pallets_is_refused_unless_it_changes_nothing() {
        let e = patch(&[("pallet_size", "5")])
            .apply(&Globals::default())
            .unwrap_err();
        assert_eq!(
            (e.kind, e.field.as_deref()),
            (SchemeErrorKind::PalletsOff, Some("pallet_size"))
        );
        let e = patch(&[("pallet_boundary", "true")])
            .apply(&Globals::default())
            .unwrap_err();
        assert_eq!(e.field.as_deref(), Some("pallet_boundary"));
        // No pallets, no frame: saying so is not a mistake.
        let g = patch(&[("pallet_boundary", "false")])
            .apply(&Globals::default())
            .unwrap();
        assert_eq!(g, Globals::default());
    }

    #[test]
    fn set_names_the_key_of_a_bad_value_and_refuses_unknown_keys() {
        let e = GlobalsPatch::default()
            .set("Block_Size", "inf")
            .unwrap_err();
        assert_eq!(e.field.as_deref(), Some("block_size"));
        let e = GlobalsPatch::default().set("colour", "red").unwrap_err();
        assert!(matches!(e.kind, SchemeErrorKind::UnknownGlobal(_)));
    }

    #[test]
    fn cells_read_back_to_the_same_globals() {
        let g = Globals {
            size: [7, 9],
            pallets: Some(Pallets {
                size: 4,
                count: [2, 1],
                boundary: false,
            }),
            block_size: 0.05,
            step_height: 0.025,
            base: 0.3,
            amount: 12,
            seed: u64::MAX,
        };
        let mut p = GlobalsPatch::default();
        for (key, text) in g.cells() {
            p.set_key(key, &text).unwrap();
        }
        assert_eq!(p.apply(&Globals::default()).unwrap(), g);
    }
}
