//! A world again from its `rse.json`: the terrain and every file the
//! manifest says the folder holds, as `check` compares them. The one place
//! a manifest is read back into a world: its recipe (a scheme at a seed
//! pair, or an atlas) is parsed once ([`Recipe::of`]), priced, generated
//! once ([`Recipe::generate`]), priced again with the terrain, and rebuilt
//! ([`Generated::rebuild`]); a world option added to `WorldOptions` is
//! rebuilt with no edit here.

use std::collections::{BTreeMap, BTreeSet};

use rse_core::{Atlas, AtlasOptions, Scheme, SchemeError, Terrain, generate_by};

use crate::atlas::{atlas_of, atlas_world};
use crate::error::Error;
use crate::files::tree::inside;
use crate::record::atlas_record::NamedScheme;
use crate::record::cost::{RebuildCost, RecipeSize, after_generating, before_generating};
use crate::record::manifest::{MANIFEST, Manifest, TemplateSet};
use crate::render::templates::Templates;
use crate::render::world::build_world_of;

/// A manifest's recipe, its scheme (or an atlas's schemes) parsed once.
#[derive(Debug)]
pub struct Recipe<'m> {
    manifest: &'m Manifest,
    source: Source,
    size: RecipeSize,
}

/// What the world is made from.
#[derive(Debug)]
enum Source {
    /// A scheme, generated at the manifest's seed pair and difficulty.
    World(Scheme),
    /// An atlas of these schemes and options.
    Atlas {
        schemes: Vec<NamedScheme>,
        options: AtlasOptions,
    },
}

/// A recipe and the terrain it gives, generated once.
#[derive(Debug)]
pub struct Generated<'m> {
    manifest: &'m Manifest,
    size: RecipeSize,
    made: Made,
}

/// What the world is made from, and what it gave: the world's terrain, or
/// the whole atlas (its flat patches and tiles are written into the
/// folder too).
#[derive(Debug)]
enum Made {
    World {
        scheme: Scheme,
        terrain: Terrain,
    },
    Atlas {
        schemes: Vec<NamedScheme>,
        options: AtlasOptions,
        atlas: Atlas,
    },
}

/// A world rebuilt from its manifest.
#[derive(Debug, Clone)]
pub struct Rebuilt {
    /// Its terrain (an atlas's whole map).
    pub terrain: Terrain,
    /// Every file the folder must hold with the bytes it must have,
    /// `rse.json` included; the files in `hashed_only` are not among them.
    pub files: BTreeMap<String, Vec<u8>>,
    /// Files rendered from templates the rebuild did not have (a custom
    /// set, or another version's): their recorded SHA-256 is all there is
    /// to compare with. Sorted.
    pub hashed_only: BTreeSet<String>,
}

/// Why a manifest names no world that can be rebuilt.
#[derive(Debug, thiserror::Error)]
pub enum RebuildError {
    /// The recorded scheme (or an atlas's) does not parse.
    #[error(transparent)]
    Scheme(#[from] SchemeError),
    /// The world cannot be built with the recorded options.
    #[error("the world cannot be rebuilt from it: {0}")]
    World(#[from] Error),
    /// The manifest claims templates it cannot have been made with.
    #[error("the world cannot be rebuilt from it: {0}")]
    Templates(String),
}

impl<'m> Recipe<'m> {
    /// The recipe `manifest` records: its scheme or atlas parsed, nothing
    /// generated.
    pub fn of(manifest: &'m Manifest) -> Result<Self, RebuildError> {
        let (source, size) = if let Some(record) = &manifest.atlas {
            let schemes = record.schemes()?;
            let options = record.options(manifest.seed);
            let plain: Vec<Scheme> = schemes.iter().map(|s| s.scheme.clone()).collect();
            let size = RecipeSize::of_atlas(&plain, &options);
            (Source::Atlas { schemes, options }, size)
        } else {
            let scheme = Scheme::from_csv(&manifest.scheme, Some("rse.json scheme"))?;
            let size = RecipeSize::of_scheme(&scheme);
            (Source::World(scheme), size)
        };
        Ok(Recipe {
            manifest,
            source,
            size,
        })
    }

    /// The side of the world's cells, metres (an atlas's first scheme's:
    /// its tiles share one block size).
    pub fn block_size(&self) -> f64 {
        match &self.source {
            Source::World(scheme) => scheme.globals().block_size,
            Source::Atlas { schemes, .. } => schemes
                .first()
                .map_or(rse_core::Globals::default().block_size, |s| {
                    s.scheme.globals().block_size
                }),
        }
    }

    /// What rebuilding this world with `templates` would cost, from the
    /// recipe alone: to be held to a budget before [`Self::generate`].
    pub fn cost(&self, templates: &Templates) -> RebuildCost {
        before_generating(&self.size, &self.manifest.options, templates)
    }

    /// The terrain (an atlas's whole map, with its flat patches), the work
    /// [`Self::cost`] priced.
    pub fn generate(self) -> Result<Generated<'m>, RebuildError> {
        let manifest = self.manifest;
        let made = match self.source {
            Source::World(scheme) => {
                let terrain = generate_by(
                    &scheme,
                    manifest.seed,
                    manifest.index,
                    manifest.options.difficulty,
                    manifest.options.rule(),
                );
                Made::World { scheme, terrain }
            }
            Source::Atlas { schemes, options } => {
                let atlas = atlas_of(&schemes, &options)?;
                Made::Atlas {
                    schemes,
                    options,
                    atlas,
                }
            }
        };
        Ok(Generated {
            manifest,
            size: self.size,
            made,
        })
    }
}

impl Generated<'_> {
    /// The world's terrain (an atlas's whole map).
    pub fn terrain(&self) -> &Terrain {
        match &self.made {
            Made::World { terrain, .. } => terrain,
            Made::Atlas { atlas, .. } => atlas.terrain(),
        }
    }

    /// [`Recipe::cost`] and the files, which follow the terrain's mesh and
    /// boxes: to be held to a budget before [`Self::rebuild`].
    pub fn cost(&self, templates: &Templates) -> RebuildCost {
        after_generating(
            &self.size,
            &self.manifest.options,
            self.terrain(),
            templates,
        )
    }

    /// The world this manifest describes, built with `templates` (ours, in
    /// `check`) from the terrain generated already. With the templates it
    /// records (same set, same digest, this version of rse) that is every
    /// file, `rse.json` included; otherwise the files rendered from
    /// templates are left to their recorded hashes, and `rse.json` is
    /// rebuilt with those hashes and the recorded template set, digest and
    /// version, so every other byte of it is still checked.
    ///
    /// # Panics
    /// Never: the `rse.json` it reads back is one it has just written.
    pub fn rebuild(self, templates: &Templates) -> Result<Rebuilt, RebuildError> {
        let manifest = self.manifest;
        let same_version = manifest.version == rse_core::VERSION;
        // Another version's built-in templates are not this build's to
        // render: its files cannot be rebuilt, and taking their hashes
        // alone would let a world that claims a version pass with any
        // edit (a forged "0.1.1" with its collision boxes removed did).
        if manifest.templates == TemplateSet::Builtin && !same_version {
            return Err(RebuildError::Templates(format!(
                "made by rse {} with its built-in templates, which rse {} cannot rebuild: check it with rse {}",
                manifest.version,
                rse_core::VERSION,
                manifest.version
            )));
        }
        // This version's own templates have one digest: any other is a
        // forged claim, not a world to check by hashes alone.
        if manifest.templates == TemplateSet::Builtin
            && same_version
            && templates.set() == TemplateSet::Builtin
            && manifest.templates_sha256 != templates.digest()
        {
            return Err(RebuildError::Templates(format!(
                "templates_sha256 is {}, but rse {} has built-in templates {}",
                manifest.templates_sha256,
                rse_core::VERSION,
                templates.digest()
            )));
        }
        let name = manifest.world.clone();
        let (terrain, world) = match self.made {
            Made::World { scheme, terrain } => {
                let world = build_world_of(&terrain, &scheme, name, &manifest.options, templates)?;
                (terrain, world)
            }
            Made::Atlas {
                schemes,
                options,
                atlas,
            } => {
                let world = atlas_world(
                    &atlas,
                    &schemes,
                    &options,
                    name,
                    &manifest.options,
                    templates,
                )?;
                (atlas.terrain().clone(), world)
            }
        };
        let made_alike = same_version
            && manifest.templates == templates.set()
            && manifest.templates_sha256 == templates.digest();
        if made_alike {
            return Ok(Rebuilt {
                terrain,
                files: world.files,
                hashed_only: BTreeSet::new(),
            });
        }
        let mut files = world.files;
        for path in &world.from_templates {
            files.remove(path);
        }
        let rebuilt = files
            .remove(MANIFEST)
            .expect("a built world holds rse.json");
        let mut rebuilt = Manifest::from_json(
            std::str::from_utf8(&rebuilt).expect("rse.json is written as UTF-8"),
        )
        .expect("a manifest just written parses");
        let hashed_only: BTreeSet<String> = manifest
            .files
            .keys()
            .filter(|p| !files.contains_key(*p) && inside(p))
            .cloned()
            .collect();
        rebuilt.templates = manifest.templates;
        rebuilt
            .templates_sha256
            .clone_from(&manifest.templates_sha256);
        rebuilt.version.clone_from(&manifest.version);
        rebuilt.files.retain(|p, _| files.contains_key(p));
        for path in &hashed_only {
            rebuilt
                .files
                .insert(path.clone(), manifest.files[path].clone());
        }
        files.insert(MANIFEST.to_owned(), rebuilt.to_json().into_bytes());
        Ok(Rebuilt {
            terrain,
            files,
            hashed_only,
        })
    }
}
