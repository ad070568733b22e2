//! What a world folder holds, as typed options with one set of defaults:
//! the simulator targets, the terrain model, the `MuJoCo` collider and the
//! difficulty. Every front end (clap, Python, the editor) parses these
//! types' `FromStr` and starts from their `Default`.

use std::fmt;
use std::str::FromStr;

use rse_core::{Difficulty, DifficultyRule};
use serde::{Deserialize, Serialize};

use crate::error::Error;

/// `WorldOptions` from the table of world options
/// ([`for_each_world_option`](crate::for_each_world_option)): the
/// difficulty's two fields by hand, then a field for each option whose
/// entry says `record: { field, … }`, in table order (the order `rse.json`
/// writes them in). Munches the table entry by entry.
macro_rules! declare_world_options {
    (@munch [$($fields:tt)*] [$($record:ident)*]) => {
        /// What to put in a world folder. Recorded in `rse.json` as it is
        /// (its fields flattened into the manifest, in this order), so an
        /// option added to the table is written, compared and rebuilt with
        /// no other edit.
        #[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
        pub struct WorldOptions {
            /// The difficulty the heights are scaled to; absent at 1, so
            /// worlds of full difficulty keep the bytes they had before
            /// difficulties.
            #[serde(default, skip_serializing_if = "is_full")]
            pub difficulty: Difficulty,
            /// How the scaled heights were rounded: written beside a
            /// difficulty below 1 ([`WorldConfig::resolve`](crate::WorldConfig::resolve)
            /// sets today's rule); absent in worlds written before the rule
            /// was recorded, which [`Self::rule`] reads as the rule they were
            /// written with.
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub difficulty_rule: Option<DifficultyRule>,
            $($fields)*
        }

        impl WorldOptions {
            /// Every recorded option by its name, at its default too (what
            /// the templates see as `options`: `rse.json` leaves an option
            /// at its default out, and a template need not know which).
            pub(crate) fn template_value(&self) -> minijinja::Value {
                let by_name: std::collections::BTreeMap<&str, minijinja::Value> = [
                    ("difficulty", minijinja::Value::from(minijinja::value::Serde(self.difficulty))),
                    $((stringify!($record), minijinja::Value::from(minijinja::value::Serde(&self.$record))),)*
                ]
                .into_iter()
                .collect();
                minijinja::Value::from(by_name)
            }
        }
    };
    (@munch [$($fields:tt)*] [$($names:ident)*]
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty {
            record: none,
            $($after:tt)*
        }
        $($rest:tt)*
    ) => {
        declare_world_options!(@munch [$($fields)*] [$($names)*] $($rest)*);
    };
    (@munch [$($fields:tt)*] [$($names:ident)*]
        $(#[doc = $what:literal])*
        $field:ident: $ty:ty {
            record: { field: $record:ident: $record_ty:ty, resolve: $resolve:ident, serde: ($($serde:tt)*) },
            $($after:tt)*
        }
        $($rest:tt)*
    ) => {
        declare_world_options!(@munch
            [$($fields)* $(#[doc = $what])* #[serde($($serde)*)] pub $record: $record_ty,]
            [$($names)* $record]
            $($rest)*);
    };
    ($($table:tt)*) => {
        declare_world_options!(@munch [] [] $($table)*);
    };
}

crate::for_each_world_option!(declare_world_options);

impl WorldOptions {
    /// The files of the single mesh a world of these options writes (for a
    /// terrain that is not empty): `meshes/terrain.obj` when `obj` is a
    /// target or Webots, `MuJoCo` or URDF use the mesh (`MuJoCo` draws it
    /// over its box set or height field), a copy in each Gazebo model that
    /// uses it (Gazebo classic draws it over its box set, always), and
    /// `usd/terrain.usda`. The one rule the writer and `check`'s cost model
    /// read.
    pub fn mesh_files(&self) -> MeshFiles {
        let targets = &self.targets;
        let meshed = |t: Target| targets.contains(t) && self.mesh.for_target(t) == MeshMode::Single;
        let shared = targets.contains(Target::Obj)
            || [Target::Webots, Target::Mujoco, Target::Urdf]
                .into_iter()
                .any(meshed);
        let gazebo = [Target::Gazebo, Target::GazeboClassic]
            .into_iter()
            .filter(|&t| meshed(t) || (t == Target::GazeboClassic && targets.contains(t)))
            .collect();
        MeshFiles {
            shared,
            gazebo,
            usd: meshed(Target::Usd),
        }
    }

    /// The rule the heights are rounded by: the recorded one, else
    /// [`DifficultyRule::Nearest`] (worlds from before the record, and
    /// options built without [`WorldConfig`](crate::WorldConfig)).
    pub fn rule(&self) -> DifficultyRule {
        self.difficulty_rule.unwrap_or(DifficultyRule::Nearest)
    }
}

/// For serde: whether a recorded option is at its type's default, and so
/// left out of `rse.json` (a world option added after worlds were written
/// says so in its table entry's `serde`, so theirs keep their bytes).
pub(crate) fn is_default<T: Default + PartialEq>(value: &T) -> bool {
    *value == T::default()
}

/// For serde: whether a manifest's difficulty is left out.
#[allow(clippy::trivially_copy_pass_by_ref)] // serde passes a reference
fn is_full(d: &Difficulty) -> bool {
    d.is_full()
}

/// A simulator (or file) a world is written for (docs/worlds.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Target {
    /// `meshes/terrain.obj` (+ `.mtl`) alone.
    Obj,
    /// A Gazebo (Sim) model folder and a `.world` including it, SDF 1.9.
    Gazebo,
    /// The same for Gazebo classic 11 (ROS 1): SDF 1.7, ODE's defaults.
    #[serde(rename = "gazebo-classic")]
    GazeboClassic,
    /// A Webots `.wbt` world.
    Webots,
    /// A `MuJoCo` MJCF file.
    Mujoco,
    /// A URDF robot description of the terrain (`PyBullet` and others).
    Urdf,
    /// A USD stage (Isaac Sim).
    Usd,
}

impl Target {
    /// Every target, in the order worlds list them.
    pub const ALL: [Target; 7] = [
        Target::Obj,
        Target::Gazebo,
        Target::GazeboClassic,
        Target::Webots,
        Target::Mujoco,
        Target::Urdf,
        Target::Usd,
    ];

    /// The name on the command line, and the world's folder for it.
    pub fn name(self) -> &'static str {
        match self {
            Target::Obj => "obj",
            Target::Gazebo => "gazebo",
            Target::GazeboClassic => "gazebo-classic",
            Target::Webots => "webots",
            Target::Mujoco => "mujoco",
            Target::Urdf => "urdf",
            Target::Usd => "usd",
        }
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Target {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self, Error> {
        Target::ALL
            .into_iter()
            .find(|t| t.name() == s)
            .ok_or_else(|| Error::BadOption {
                option: "target",
                message: format!("unknown target {s:?}: expected one of {}", names()),
            })
    }
}

fn names() -> String {
    Target::ALL.map(Target::name).join(", ")
}

/// A set of targets, without repeats, in [`Target::ALL`] order.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Targets(Vec<Target>);

impl Targets {
    /// Parses a comma-separated list such as `gazebo,mujoco`.
    pub fn parse(list: &str) -> Result<Self, Error> {
        let mut targets = list
            .split(',')
            .map(|s| s.trim().parse())
            .collect::<Result<Vec<Target>, _>>()?;
        targets.sort_unstable();
        targets.dedup();
        Ok(Targets(targets))
    }

    /// Every target ([`Target::ALL`]).
    pub fn all() -> Self {
        Targets(Target::ALL.to_vec())
    }

    /// The targets, in order.
    pub fn iter(&self) -> impl Iterator<Item = Target> + '_ {
        self.0.iter().copied()
    }

    /// Whether `target` is one of them.
    pub fn contains(&self, target: Target) -> bool {
        self.0.contains(&target)
    }
}

impl Default for Targets {
    /// Gazebo alone: every front end's default (`rse-gen batch` without
    /// `--target`, Python without `targets=`, the editor's first choice).
    fn default() -> Self {
        Targets(vec![Target::Gazebo])
    }
}

impl FromStr for Targets {
    type Err = Error;

    /// [`Targets::parse`].
    fn from_str(s: &str) -> Result<Self, Error> {
        Targets::parse(s)
    }
}

impl fmt::Display for Targets {
    /// The comma-separated list [`Targets::parse`] reads back.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, target) in self.iter().enumerate() {
            if i > 0 {
                f.write_str(",")?;
            }
            f.write_str(target.name())?;
        }
        Ok(())
    }
}

/// How the terrain is modelled in the simulator files (paper §3.1 "Mesh type").
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MeshMode {
    /// Each target's fastest exact collider that holds, as measured
    /// (docs/worlds.md, "Which collider each simulator gets"): the box set
    /// for URDF (`PyBullet` collides boxes faster than a concave mesh) and
    /// for Gazebo classic (ODE rolls bodies off the mesh's interior edges),
    /// the single mesh for every other target (`MuJoCo` collides boxes
    /// whatever the mode, and draws the mesh).
    #[default]
    Auto,
    /// The single closed mesh of docs/meshes.md, for every target.
    Single,
    /// The box set, for every target.
    Blocks,
}

impl MeshMode {
    /// Every mode, in the order help pages list them.
    pub const ALL: [MeshMode; 3] = [MeshMode::Auto, MeshMode::Single, MeshMode::Blocks];

    /// The name on the command line and in `rse.json`.
    pub fn name(self) -> &'static str {
        match self {
            MeshMode::Auto => "auto",
            MeshMode::Single => "single",
            MeshMode::Blocks => "blocks",
        }
    }

    /// What `target`'s files get: `Single` or `Blocks`, never `Auto` (the
    /// `mesh` value templates see).
    #[must_use]
    pub fn for_target(self, target: Target) -> MeshMode {
        match (self, target) {
            (MeshMode::Auto, Target::Urdf | Target::GazeboClassic) => MeshMode::Blocks,
            (MeshMode::Auto, _) => MeshMode::Single,
            (mode, _) => mode,
        }
    }
}

impl fmt::Display for MeshMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for MeshMode {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self, Error> {
        MeshMode::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| Error::BadOption {
                option: "mesh",
                message: format!("unknown mesh mode {s:?}: expected auto, single or blocks"),
            })
    }
}

/// The single mesh's files in a world ([`WorldOptions::mesh_files`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MeshFiles {
    /// `meshes/terrain.obj`.
    pub shared: bool,
    /// The Gazebo targets whose model folder holds a copy of the OBJ.
    pub gazebo: Vec<Target>,
    /// `usd/terrain.usda`.
    pub usd: bool,
}

impl MeshFiles {
    /// How many OBJ files (each a copy of one mesh).
    pub fn objs(&self) -> u64 {
        u64::from(self.shared) + self.gazebo.len() as u64
    }

    /// `true` when the world writes the mesh at all (it is built).
    pub fn any(&self) -> bool {
        self.objs() > 0 || self.usd
    }
}

/// What a target's simulator collides with in a world.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Collider {
    /// The single mesh (`obj` is the mesh itself).
    Mesh,
    /// The box set.
    Boxes,
    /// `MuJoCo`'s height field.
    Hfield,
}

impl Collider {
    /// What `target` collides with in a world of `mesh` mode and `mujoco`
    /// collider.
    pub fn of(target: Target, mesh: MeshMode, mujoco: MujocoCollider) -> Collider {
        match (target, mujoco, mesh.for_target(target)) {
            (Target::Obj, ..) => Collider::Mesh,
            (Target::Mujoco, MujocoCollider::Hfield { .. }, _) => Collider::Hfield,
            (Target::Mujoco, MujocoCollider::Boxes, _) | (_, _, MeshMode::Blocks) => {
                Collider::Boxes
            }
            _ => Collider::Mesh,
        }
    }
}

/// What `MuJoCo` worlds collide with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum MujocoCollider {
    /// The box set, one static box geom each (exact).
    #[default]
    Boxes,
    /// A height field of `oversample` samples per cell along each axis
    /// (`mujoco/terrain.bin`): exact but within half a sample of a step edge.
    Hfield {
        /// Samples per cell along each axis, 1 or more.
        oversample: u32,
    },
}

impl MujocoCollider {
    /// The default: boxes.
    pub fn is_boxes(&self) -> bool {
        *self == MujocoCollider::Boxes
    }

    /// The names [`MujocoCollider::parse`] takes, the default first.
    pub const NAMES: [&'static str; 2] = ["boxes", "hfield"];

    /// The collider named `boxes` or `hfield`, with `oversample` for a
    /// height field (`None`: [`rse_core::DEFAULT_OVERSAMPLE`]); an
    /// oversample with boxes is refused (its range, 1 or more, is the
    /// world option's: `WorldConfig::resolve` checks it first).
    pub fn parse(name: &str, oversample: Option<u32>) -> Result<Self, Error> {
        let bad = |message: String| Error::BadOption {
            option: "mujoco_collider",
            message,
        };
        match (name, oversample) {
            ("boxes", None) => Ok(MujocoCollider::Boxes),
            ("boxes", Some(_)) => Err(bad(
                "an oversample applies to the hfield collider only".to_owned()
            )),
            ("hfield", k) => Ok(MujocoCollider::Hfield {
                oversample: k.unwrap_or(rse_core::DEFAULT_OVERSAMPLE),
            }),
            _ => Err(bad(format!(
                "unknown MuJoCo collider {name:?}: expected boxes or hfield"
            ))),
        }
    }

    /// `boxes` or `hfield`, as templates see it.
    pub fn name(&self) -> &'static str {
        match self {
            MujocoCollider::Boxes => "boxes",
            MujocoCollider::Hfield { .. } => "hfield",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_target_collides_what_its_files_hold() {
        let of = |t, m| Collider::of(t, m, MujocoCollider::Boxes);
        let auto: Vec<Collider> = Target::ALL.iter().map(|&t| of(t, MeshMode::Auto)).collect();
        assert_eq!(
            auto,
            Target::ALL
                .iter()
                .map(|&t| match t {
                    Target::Urdf | Target::Mujoco | Target::GazeboClassic => Collider::Boxes,
                    _ => Collider::Mesh,
                })
                .collect::<Vec<_>>()
        );
        assert_eq!(of(Target::Gazebo, MeshMode::Blocks), Collider::Boxes);
        assert_eq!(of(Target::GazeboClassic, MeshMode::Single), Collider::Mesh);
        assert_eq!(of(Target::Urdf, MeshMode::Single), Collider::Mesh);
        assert_eq!(of(Target::Obj, MeshMode::Blocks), Collider::Mesh);
        let hfield = MujocoCollider::Hfield { oversample: 2 };
        assert_eq!(
            Collider::of(Target::Mujoco, MeshMode::Single, hfield),
            Collider::Hfield
        );
    }

    #[test]
    fn lists_parse_sorted_without_repeats() {
        let t = Targets::parse("usd, gazebo,usd,obj").unwrap();
        assert_eq!(
            t.iter().collect::<Vec<_>>(),
            [Target::Obj, Target::Gazebo, Target::Usd]
        );
    }

    #[test]
    fn unknown_targets_are_named() {
        let err = Targets::parse("gazebo,isaac").unwrap_err().to_string();
        assert!(err.contains("\"isaac\"") && err.contains("mujoco"), "{err}");
    }
}
