//! `rse.json`, as data: what a world is (generator, options, seed pair,
//! drawn obstacles or an atlas recipe) and the SHA-256 of every other file
//! in its folder. Built by `world` (and `atlas`), read back by `rebuild`.

use std::collections::BTreeMap;

use rse_core::{DrawnObstacle, Globals, Grid};
use serde::{Deserialize, Serialize};

use crate::record::atlas_record::AtlasRecord;
use crate::record::options::{Target, WorldOptions};

/// The manifest's file name in a world folder.
pub const MANIFEST: &str = "rse.json";

/// `rse.json` larger than this is refused before it is read, bytes. A
/// manifest holds the scheme, the drawn obstacles and one hash per file:
/// kilobytes for any real scheme.
pub const MAX_MANIFEST_BYTES: u64 = 16 << 20;

/// The contents of `rse.json`.
///
/// Keys are written in field order; `options` is flattened into the
/// object, so a world option added to [`WorldOptions`] is recorded, compared
/// by `check` and rebuilt with no edit here.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Always `"rse"`.
    pub generator: String,
    /// The generator version that wrote the world.
    pub version: String,
    /// The world folder's name.
    pub world: String,
    /// Base seed of the batch.
    pub seed: u64,
    /// Index of the world in the batch.
    pub index: u64,
    /// What was written: difficulty, targets, terrain model, `MuJoCo`
    /// collider.
    #[serde(flatten)]
    pub options: WorldOptions,
    /// Which template set rendered the simulator files.
    pub templates: TemplateSet,
    /// SHA-256 of the template files used.
    pub templates_sha256: String,
    /// The grid the scheme gave, in cells.
    pub grid: Grid,
    /// The resolved global parameters (command-line overrides applied);
    /// a key added since worlds were first written is left out at its
    /// default, so their records keep their bytes.
    #[serde(serialize_with = "Globals::serialize_record")]
    pub globals: Globals,
    /// The obstacle table: the whole resolved scheme as canonical CSV,
    /// enough to regenerate the heightmap with `seed` and `index`. Absent
    /// for an atlas, whose schemes are in `atlas`.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub scheme: String,
    /// Every obstacle as drawn for this world (none for an atlas: its
    /// tiles are worlds of their own, named in `atlas.json`).
    pub drawn: Vec<DrawnObstacle>,
    /// For an atlas: everything it was built from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub atlas: Option<AtlasRecord>,
    /// SHA-256 (hex) of every other file of the folder, by `/`-separated
    /// relative path.
    pub files: BTreeMap<String, String>,
}

/// The template set a world's simulator files were rendered from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TemplateSet {
    /// Ours, built into the generator: `check` rebuilds every file.
    Builtin,
    /// Ours overlaid by a user's folder: `check` compares the rendered
    /// files with their recorded hashes only.
    Custom,
}

impl TemplateSet {
    /// `builtin` or `custom`, as `rse.json` writes it.
    pub fn name(self) -> &'static str {
        match self {
            TemplateSet::Builtin => "builtin",
            TemplateSet::Custom => "custom",
        }
    }
}

impl Manifest {
    /// The JSON text of the manifest: pretty, keys in a fixed order, a final
    /// newline.
    ///
    /// # Panics
    /// Never: every field serialises.
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).expect("a manifest serialises");
        text.push('\n');
        text
    }

    /// Parses `rse.json` text.
    pub fn from_json(text: &str) -> Result<Self, serde_json::Error> {
        serde_json::from_str(text)
    }
}

/// Why the world of manifest `now` is not the one of manifest `there`, in
/// a user's terms (`targets gazebo there, gazebo,mujoco now`): the first
/// setting that differs, or `None` when they were made alike (then their
/// files differ: edited by hand, or a different generator build).
pub fn what_differs(there: &Manifest, now: &Manifest) -> Option<String> {
    if there.scheme != now.scheme || there.globals != now.globals {
        return Some("it was made from another scheme or other global settings".to_owned());
    }
    let targets = |m: &Manifest| {
        m.options
            .targets
            .iter()
            .map(Target::name)
            .collect::<Vec<_>>()
            .join(",")
    };
    let templates = |m: &Manifest| format!("{} ({:.12}…)", m.templates.name(), m.templates_sha256);
    let settings: [(&str, Show); 8] = [
        ("seed", |m| m.seed.to_string()),
        ("index", |m| m.index.to_string()),
        ("difficulty", |m| m.options.difficulty.to_string()),
        ("targets", targets),
        ("mesh", |m| m.options.mesh.name().to_owned()),
        ("mujoco collider", |m| {
            m.options.mujoco_collider.name().to_owned()
        }),
        ("rse version", |m| m.version.clone()),
        ("templates", templates),
    ];
    if let Some((what, show)) = settings.iter().find(|(_, show)| show(there) != show(now)) {
        return Some(format!("{what} {} there, {} now", show(there), show(now)));
    }
    (there.templates_sha256 != now.templates_sha256)
        .then(|| "it was made with other templates".to_owned())
}

/// How [`what_differs`] shows one setting of a manifest.
type Show = fn(&Manifest) -> String;
