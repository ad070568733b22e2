//! A world again from its `rse.json`: the terrain and every file the
//! manifest says the folder holds, as `check` compares them. The one place
//! a manifest is read back into a world (its recipe: a scheme at a seed
//! pair, or an atlas), so a world option added to `WorldOptions` is
//! rebuilt with no edit here.

use std::collections::{BTreeMap, BTreeSet};

use rse_core::{Scheme, SchemeError, Terrain, generate_at};

use crate::atlas::build_atlas_world;
use crate::error::Error;
use crate::manifest::{MANIFEST, Manifest, TemplateSet};
use crate::templates::Templates;
use crate::tree::inside;
use crate::world::build_world_of;

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

impl Manifest {
    /// The world this manifest describes, built with `templates` (ours, in
    /// `check`). With the templates it records (same set, same digest, this
    /// version of rse) that is every file, `rse.json` included; otherwise
    /// the files rendered from templates are left to their recorded hashes,
    /// and `rse.json` is rebuilt with those hashes and the recorded template
    /// set, digest and version, so every other byte of it is still checked.
    /// The terrain is generated once.
    ///
    /// # Panics
    /// Never: the `rse.json` it reads back is one it has just written.
    pub fn rebuild(&self, templates: &Templates) -> Result<Rebuilt, RebuildError> {
        let same_version = self.version == rse_core::VERSION;
        // This version's own templates have one digest: any other is a
        // forged claim, not a world to check by hashes alone.
        if self.templates == TemplateSet::Builtin
            && same_version
            && templates.set() == TemplateSet::Builtin
            && self.templates_sha256 != templates.digest()
        {
            return Err(RebuildError::Templates(format!(
                "templates_sha256 is {}, but rse {} has built-in templates {}",
                self.templates_sha256,
                rse_core::VERSION,
                templates.digest()
            )));
        }
        let name = self.world.clone();
        let (terrain, world) = if let Some(record) = &self.atlas {
            let schemes = record.schemes()?;
            let (world, atlas) = build_atlas_world(
                &schemes,
                &record.options(self.seed),
                name,
                &self.options,
                templates,
            )?;
            (atlas.terrain().clone(), world)
        } else {
            let scheme = Scheme::from_csv(&self.scheme, Some("rse.json scheme"))?;
            let terrain = generate_at(&scheme, self.seed, self.index, self.options.difficulty);
            let world = build_world_of(&terrain, &scheme, name, &self.options, templates)?;
            (terrain, world)
        };
        let made_alike = same_version
            && self.templates == templates.set()
            && self.templates_sha256 == templates.digest();
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
        let hashed_only: BTreeSet<String> = self
            .files
            .keys()
            .filter(|p| !files.contains_key(*p) && inside(p))
            .cloned()
            .collect();
        rebuilt.templates = self.templates;
        rebuilt.templates_sha256.clone_from(&self.templates_sha256);
        rebuilt.version.clone_from(&self.version);
        rebuilt.files.retain(|p, _| files.contains_key(p));
        for path in &hashed_only {
            rebuilt.files.insert(path.clone(), self.files[path].clone());
        }
        files.insert(MANIFEST.to_owned(), rebuilt.to_json().into_bytes());
        Ok(Rebuilt {
            terrain,
            files,
            hashed_only,
        })
    }
}
