//! Global parameters as a user gives them — a scheme file's `# key: value`
//! lines, command-line flags, Python keywords, the editor's fields — and the
//! one set of rules that turns them into [`Globals`] (the pallet rules live
//! here and nowhere else).

use crate::error::{SchemeError, SchemeErrorKind};
use crate::for_each_global_key;
use crate::global_key::GlobalKey;
use crate::global_range::GlobalRange;
use crate::global_value::{GlobalText as _, ParseGlobal, format_dims};
use crate::globals::{self, Globals, Pallets};
use crate::limits::DEFAULT_PALLET_SIZE;

/// [`GlobalsPatch`], its `set_key`, `combine` and `given`, from the table
/// of [`for_each_global_key`].
macro_rules! declare_globals_patch {
    ($(
        $(#[doc = $what:literal])*
        $variant:ident { $field:ident: $ty:ty, range: $range:expr, stored: $stored:tt, flag: $flag:tt }
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
            /// Sets `key` from its text as a scheme file writes it, in its
            /// range; the error's `field` names the key.
            pub fn set_key(&mut self, key: GlobalKey, text: &str) -> Result<(), SchemeError> {
                let expects = key.expects();
                let parsed = match key {
                    $(GlobalKey::$variant => {
                        <$ty as ParseGlobal>::parse_global(text, expects)
                            .and_then(|value| GlobalRange::check(&$range, &value).map(|()| value))
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

            /// `g` with the keys stored in a field of their own that this
            /// patch gives ([`apply`](GlobalsPatch::apply) writes out the
            /// grid's).
            fn apply_stored(&self, g: &mut Globals) {
                $(if_stored!($stored, if let Some(value) = self.$field {
                    g.$field = value;
                });)*
            }

            /// The keys stored in a field of their own, each given as `g`
            /// holds it.
            fn stored_of(g: &Globals) -> GlobalsPatch {
                let mut patch = GlobalsPatch::default();
                $(if_stored!($stored, patch.$field = Some(g.$field));)*
                patch
            }

            /// Each value given in its key's range (the table's `range`),
            /// the first outside it an error whose `field` names the key.
            /// What every skin's value passes through: the scheme file's
            /// text and the flags by [`set_key`](GlobalsPatch::set_key),
            /// the rest (Python, a record) by
            /// [`Globals::validate`](crate::Globals::validate).
            pub fn check_ranges(&self) -> Result<(), SchemeError> {
                $(if let Some(value) = &self.$field {
                    GlobalRange::check(&$range, value).map_err(|reason| {
                        SchemeError::new(SchemeErrorKind::BadGlobal {
                            value: value.global_text(),
                            reason,
                        })
                        .with_field(GlobalKey::$variant.name())
                    })?;
                })*
                Ok(())
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

/// `$code` for a key stored in a field of its own, nothing for the grid's
/// (`stored: by_hand`), whose fields `Globals` does not have.
macro_rules! if_stored {
    (by_hand, $($code:tt)*) => {};
    ({ $($stored:tt)* }, $($code:tt)*) => {
        $($code)*
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
        // The grid's keys, whose rules are these; the rest each replace
        // their field (`apply_stored`).
        let GlobalsPatch {
            size,
            pallets,
            pallet_size,
            pallet_boundary,
            ..
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
        self.apply_stored(&mut g);
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
            GlobalKey::Size => format_dims(defaults.size),
            GlobalKey::Pallets => "off".to_owned(),
            GlobalKey::PalletSize => turned_on().size.to_string(),
            GlobalKey::PalletBoundary => turned_on().boundary.to_string(),
            stored => Globals::stored_default_text(stored).unwrap_or_default(),
        }
    }

    /// Every key given, as these globals hold it: the pallet keys `None`
    /// with pallets off (`pallets` given as off). `apply` onto any globals
    /// gives these back.
    pub fn as_patch(&self) -> GlobalsPatch {
        GlobalsPatch {
            size: Some(self.size),
            pallets: Some(self.pallets.map(|p| p.count)),
            pallet_size: self.pallets.map(|p| p.size),
            pallet_boundary: self.pallets.map(|p| p.boundary),
            ..GlobalsPatch::stored_of(self)
        }
    }

    /// The `(key, text)` of each global a canonical scheme file writes, in
    /// [`GlobalKey::ALL`] order; [`GlobalsPatch::set`] reads each text back to
    /// the same value. Values equal to the defaults are left out where a
    /// reader would not miss them (`base`, `amount`, `seed`; `size` under
    /// pallets, which define the grid).
    pub fn cells(&self) -> Vec<(GlobalKey, String)> {
        GlobalKey::ALL
            .into_iter()
            .filter_map(|key| {
                let text = match key {
                    GlobalKey::Size => (self.pallets.is_none()
                        || self.size != Globals::default().size)
                        .then(|| format_dims(self.size)),
                    GlobalKey::Pallets => self.pallets.map(|p| format_dims(p.count)),
                    GlobalKey::PalletSize => self.pallets.map(|p| p.size.to_string()),
                    GlobalKey::PalletBoundary => self.pallets.map(|p| p.boundary.to_string()),
                    stored => self.stored_text(stored),
                };
                text.map(|text| (key, text))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The keys `stored: by_hand` are the four whose rules `apply`,
    /// `as_patch`, `cells` and `default_text` write out by name; another
    /// would be silently dropped by them.
    #[test]
    fn only_the_grids_keys_are_written_by_hand() {
        let by_hand: Vec<GlobalKey> = GlobalKey::ALL
            .into_iter()
            .filter(|key| !Globals::STORED.contains(key))
            .collect();
        assert_eq!(
            by_hand,
            [
                GlobalKey::Size,
                GlobalKey::Pallets,
                GlobalKey::PalletSize,
                GlobalKey::PalletBoundary
            ]
        );
    }

    /// Every key at its example.
    fn every_example() -> Globals {
        let mut patch = GlobalsPatch::default();
        for key in GlobalKey::ALL {
            patch.set_key(key, key.example()).unwrap();
        }
        patch.apply(&Globals::default()).unwrap()
    }

    /// Each key's example is read, and is not its default (with pallets
    /// on, for the pallet keys): a test that walks a key through a skin
    /// with it would otherwise prove nothing.
    #[test]
    fn every_example_is_a_value_other_than_the_default() {
        let pallets_on = GlobalsPatch {
            pallets: Some(Some([1, 1])),
            ..GlobalsPatch::default()
        }
        .apply(&Globals::default())
        .unwrap();
        for key in GlobalKey::ALL {
            let mut patch = GlobalsPatch::default();
            patch.set_key(key, key.example()).unwrap();
            assert_ne!(
                patch.apply(&pallets_on).unwrap(),
                pallets_on,
                "{}: its example is the default",
                key.name()
            );
        }
        let g = every_example();
        assert_eq!(
            g.cells().len(),
            GlobalKey::ALL.len(),
            "a key at its example is written"
        );
    }

    /// `as_patch` gives every key, and applied gives the globals back.
    #[test]
    fn a_globals_patch_gives_them_back() {
        let with_pallets = GlobalsPatch {
            pallets: Some(Some([2, 3])),
            pallet_size: Some(7),
            pallet_boundary: Some(false),
            block_size: Some(0.25),
            seed: Some(9),
            ..GlobalsPatch::default()
        }
        .apply(&Globals::default())
        .unwrap();
        for g in [Globals::default(), with_pallets] {
            let patch = g.as_patch();
            let pallet_keys = if g.pallets.is_some() { 0 } else { 2 };
            assert_eq!(patch.given().len(), GlobalKey::ALL.len() - pallet_keys);
            assert_eq!(patch.apply(&with_pallets).unwrap(), g);
        }
    }

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
        let e = GlobalsPatch::default().set("gravity", "9.8").unwrap_err();
        assert!(matches!(e.kind, SchemeErrorKind::UnknownGlobal(_)));
    }

    #[test]
    fn cells_read_back_to_the_same_globals() {
        let g = every_example();
        let mut p = GlobalsPatch::default();
        for (key, text) in g.cells() {
            p.set_key(key, &text).unwrap();
        }
        assert_eq!(p.apply(&Globals::default()).unwrap(), g);
    }
}
