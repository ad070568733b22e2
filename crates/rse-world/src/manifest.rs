//! `rse.json`: what a world is (generator, parameters, seed pair, drawn
//! obstacles) and the SHA-256 of every other file in its folder.

use std::collections::BTreeMap;

use rse_core::{Difficulty, DrawnObstacle, Globals, Grid, Terrain};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::atlas::AtlasRecord;
use crate::target::{MeshMode, MujocoCollider, Targets};
use crate::templates::Templates;
use crate::world::{WorldFiles, WorldOptions};

/// The manifest's file name in a world folder.
pub const MANIFEST: &str = "rse.json";

/// The contents of `rse.json`.
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
    /// The difficulty the heights were scaled to; absent at 1, so worlds
    /// of full difficulty keep the bytes they had before difficulties.
    #[serde(default, skip_serializing_if = "is_full")]
    pub difficulty: Difficulty,
    /// The targets written.
    pub targets: Targets,
    /// The terrain model of the simulator files.
    pub mesh: MeshMode,
    /// What the `MuJoCo` world collides with; absent for boxes, so worlds
    /// made before height fields keep their bytes.
    #[serde(default, skip_serializing_if = "MujocoCollider::is_boxes")]
    pub mujoco_collider: MujocoCollider,
    /// `"builtin"` or `"custom"`.
    pub templates: String,
    /// SHA-256 of the template files used.
    pub templates_sha256: String,
    /// The grid.
    pub grid: Grid,
    /// The resolved global parameters (command-line overrides applied).
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

impl Manifest {
    /// The manifest of `world` (its files as they are, `rse.json` not
    /// among them), with no scheme, seed pair or drawn obstacles: the
    /// caller fills those in.
    pub(crate) fn of(
        world: &WorldFiles,
        terrain: &Terrain,
        globals: &Globals,
        options: &WorldOptions,
        templates: &Templates,
    ) -> Manifest {
        Manifest {
            generator: "rse".to_owned(),
            version: rse_core::VERSION.to_owned(),
            world: world.name.clone(),
            seed: 0,
            index: 0,
            difficulty: Difficulty::FULL,
            targets: options.targets.clone(),
            mesh: options.mesh,
            mujoco_collider: options.mujoco_collider,
            templates: if templates.is_custom() {
                "custom"
            } else {
                "builtin"
            }
            .to_owned(),
            templates_sha256: templates.digest().to_owned(),
            grid: terrain.grid(),
            globals: *globals,
            scheme: String::new(),
            drawn: Vec::new(),
            atlas: None,
            files: world
                .files
                .iter()
                .map(|(path, bytes)| (path.clone(), sha256_hex(bytes)))
                .collect(),
        }
    }

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
        m.targets
            .iter()
            .map(crate::target::Target::name)
            .collect::<Vec<_>>()
            .join(",")
    };
    let templates = |m: &Manifest| format!("{} ({:.12}…)", m.templates, m.templates_sha256);
    let settings: [(&str, Show); 8] = [
        ("seed", |m| m.seed.to_string()),
        ("index", |m| m.index.to_string()),
        ("difficulty", |m| m.difficulty.to_string()),
        ("targets", targets),
        ("mesh", |m| m.mesh.name().to_owned()),
        ("mujoco collider", |m| m.mujoco_collider.name().to_owned()),
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

/// For serde: whether a manifest's difficulty is left out.
#[allow(clippy::trivially_copy_pass_by_ref)] // serde passes a reference
fn is_full(d: &Difficulty) -> bool {
    d.is_full()
}

/// The SHA-256 of `bytes` as lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .fold(String::with_capacity(64), |mut s, b| {
            use std::fmt::Write as _;
            write!(s, "{b:02x}").expect("writing to a String cannot fail");
            s
        })
}
