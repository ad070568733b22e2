//! One world folder, built in memory: heightmap, preview, meshes, each
//! target's files from its templates, and the manifest over them all.

use std::collections::{BTreeMap, BTreeSet};

use rse_core::export::{mtl, obj, usda};
use rse_core::{Globals, Scheme, Terrain, generate_by, preview};

use crate::error::Error;
use crate::files::digest::sha256_hex;
use crate::files::names::world_name_problem;
use crate::record::atlas_record::AtlasRecord;
use crate::record::manifest::{MANIFEST, Manifest};
use crate::record::options::{MeshMode, MujocoCollider, Target, WorldOptions};
use crate::render::context::{MODEL, WorldContext};
use crate::render::templates::Templates;

/// Where a world's `MuJoCo` height field file goes.
pub const HFIELD_FILE: &str = "mujoco/terrain.bin";

/// The files of one world folder, by `/`-separated relative path, with the
/// folder's name. Deterministic: the same inputs give the same bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct WorldFiles {
    /// The folder name, `world_0007`.
    pub name: String,
    /// Every file, `rse.json` included.
    pub files: BTreeMap<String, Vec<u8>>,
    /// The paths among `files` rendered from templates (the rest the
    /// generator writes itself): what `check` can only hash when a world was
    /// made with templates it does not have.
    pub from_templates: BTreeSet<String>,
}

impl WorldFiles {
    /// Total size of the files.
    pub fn bytes(&self) -> u64 {
        self.files.values().map(|b| b.len() as u64).sum()
    }
}

/// Builds world `index` of the batch with base seed `seed`, named `name`.
pub fn build_world(
    scheme: &Scheme,
    seed: u64,
    index: u64,
    name: String,
    options: &WorldOptions,
    templates: &Templates,
) -> Result<WorldFiles, Error> {
    SchemeCsv::new(scheme).build_world(seed, index, name, options, templates)
}

/// The world folder of `terrain`, generated from `scheme` at its seed pair
/// and `options.difficulty`: what [`build_world`] makes, for a caller that
/// has the terrain already (`check` compares with it too).
pub fn build_world_of(
    terrain: &Terrain,
    scheme: &Scheme,
    name: String,
    options: &WorldOptions,
    templates: &Templates,
) -> Result<WorldFiles, Error> {
    SchemeCsv::new(scheme).world_of(terrain, name, options, templates)
}

/// A scheme with the canonical CSV every world's `rse.json` records of it:
/// written once for a batch rather than once per world.
pub(crate) struct SchemeCsv<'a> {
    scheme: &'a Scheme,
    csv: String,
}

impl<'a> SchemeCsv<'a> {
    pub(crate) fn new(scheme: &'a Scheme) -> Self {
        SchemeCsv {
            scheme,
            csv: scheme.to_csv(),
        }
    }

    /// [`build_world`] of this scheme.
    pub(crate) fn build_world(
        &self,
        seed: u64,
        index: u64,
        name: String,
        options: &WorldOptions,
        templates: &Templates,
    ) -> Result<WorldFiles, Error> {
        let terrain = generate_by(self.scheme, seed, index, options.difficulty, options.rule());
        self.world_of(&terrain, name, options, templates)
    }

    /// [`build_world_of`] of this scheme.
    fn world_of(
        &self,
        terrain: &Terrain,
        name: String,
        options: &WorldOptions,
        templates: &Templates,
    ) -> Result<WorldFiles, Error> {
        debug_assert_eq!(
            terrain.difficulty(),
            options.difficulty,
            "the terrain's own"
        );
        let world = terrain_files(terrain, name, options, templates, BTreeMap::new())?;
        let recorded = Recorded::Scheme {
            csv: self.csv.clone(),
            seed: terrain.seed(),
            index: terrain.index(),
            terrain,
        };
        Ok(seal(
            world,
            recorded,
            self.scheme.globals(),
            options,
            templates,
        ))
    }
}

/// What a world is made from, as `rse.json` records it.
pub(crate) enum Recorded<'a> {
    /// A scheme (its canonical CSV) at a seed pair: `terrain` is the world
    /// it gives, whose drawn obstacles are recorded.
    Scheme {
        csv: String,
        seed: u64,
        index: u64,
        terrain: &'a Terrain,
    },
    /// An atlas of `seed`, and everything else it was built from.
    Atlas {
        seed: u64,
        record: AtlasRecord,
        terrain: &'a Terrain,
    },
}

/// `world` with its `rse.json`: the manifest of `recorded`, `globals` and
/// `options`, hashing every file `world` holds. The one place a manifest is
/// made.
pub(crate) fn seal(
    mut world: WorldFiles,
    recorded: Recorded,
    globals: &Globals,
    options: &WorldOptions,
    templates: &Templates,
) -> WorldFiles {
    let (seed, index, scheme, drawn, atlas, terrain) = match recorded {
        Recorded::Scheme {
            csv,
            seed,
            index,
            terrain,
        } => (seed, index, csv, terrain.drawn().to_vec(), None, terrain),
        Recorded::Atlas {
            seed,
            record,
            terrain,
        } => (seed, 0, String::new(), Vec::new(), Some(record), terrain),
    };
    let manifest = Manifest {
        generator: "rse".to_owned(),
        version: rse_core::VERSION.to_owned(),
        world: world.name.clone(),
        seed,
        index,
        options: options.clone(),
        templates: templates.set(),
        templates_sha256: templates.digest().to_owned(),
        grid: terrain.grid(),
        globals: *globals,
        scheme,
        drawn,
        atlas,
        files: digests(&world.files),
    };
    world
        .files
        .insert(MANIFEST.to_owned(), manifest.to_json().into_bytes());
    world
}

/// The SHA-256 of every file, by path. A file holding the same bytes as
/// one before it (the OBJ in `meshes/` and in Gazebo's model) takes that
/// one's digest: comparing is cheaper than hashing again. Looked up by
/// content in a hash map: a template folder of thousands of same-sized
/// files once compared each with every one before it.
fn digests(files: &BTreeMap<String, Vec<u8>>) -> BTreeMap<String, String> {
    let mut hashed: std::collections::HashMap<&[u8], String> = std::collections::HashMap::new();
    files
        .iter()
        .map(|(path, bytes)| {
            let digest = hashed
                .entry(bytes.as_slice())
                .or_insert_with(|| sha256_hex(bytes))
                .clone();
            (path.clone(), digest)
        })
        .collect()
}

/// Every file of a world folder of `terrain` but `rse.json`: `extra`
/// files, heightmap, preview, meshes and the targets' templates.
pub(crate) fn terrain_files(
    terrain: &Terrain,
    name: String,
    options: &WorldOptions,
    templates: &Templates,
    extra: BTreeMap<String, Vec<u8>>,
) -> Result<WorldFiles, Error> {
    if let Some(problem) = world_name_problem(&name) {
        return Err(Error::BadOption {
            option: "name",
            message: problem,
        });
    }
    let mut files = extra;
    files.insert(
        "heightmap.csv".to_owned(),
        terrain.heightmap().to_csv().into_bytes(),
    );
    files.insert("preview.png".to_owned(), preview::png(terrain, None)?);

    let boxes = terrain.boxes();
    // Each Gazebo's model folder holds its own mesh: the folder is what
    // the model path names, and a model reaches nothing outside it. Gazebo
    // classic draws the mesh over its box set too: a visual per box floods
    // gzserver's message queue (and gzclient's draw calls) on large fields.
    let targets = &options.targets;
    let written = options.mesh_files();
    let (shared_mesh, gazebo_meshes, usd_mesh) = if boxes.is_empty() {
        // An empty terrain: no mesh (the targets stand on the floor), but
        // the `obj` target's own (an empty OBJ).
        (targets.contains(Target::Obj), Vec::new(), false)
    } else {
        (written.shared, written.gazebo, written.usd)
    };
    if shared_mesh || !gazebo_meshes.is_empty() || usd_mesh {
        let mesh = terrain.mesh();
        let obj_bytes = obj(&mesh, Some("terrain.mtl")).into_bytes();
        let mtl_bytes = mtl(terrain.globals()).into_bytes();
        let mut mesh_folders = Vec::new();
        if shared_mesh {
            mesh_folders.push("meshes".to_owned());
        }
        for target in &gazebo_meshes {
            mesh_folders.push(format!("{target}/{MODEL}/meshes"));
        }
        // The last folder takes the OBJ's bytes themselves, the others a copy.
        if let Some((last, others)) = mesh_folders.split_last() {
            for folder in others {
                files.insert(format!("{folder}/terrain.obj"), obj_bytes.clone());
            }
            files.insert(format!("{last}/terrain.obj"), obj_bytes);
        }
        for folder in &mesh_folders {
            files.insert(format!("{folder}/terrain.mtl"), mtl_bytes.clone());
        }
        if usd_mesh {
            files.insert(
                "usd/terrain.usda".to_owned(),
                usda(&mesh, terrain.globals()).into_bytes(),
            );
        }
    }

    let mut context =
        WorldContext::new(name.clone(), terrain, options.mesh, &boxes).with_options(options);
    if let (MujocoCollider::Hfield { oversample }, true) =
        (options.mujoco_collider, targets.contains(Target::Mujoco))
    {
        let hfield = terrain.hfield(oversample)?;
        files.insert(HFIELD_FILE.to_owned(), hfield.to_mujoco_bin());
        context = context.with_hfield(&hfield);
    }
    let mut from_templates = BTreeSet::new();
    for target in targets.iter() {
        context.mesh = options.mesh.for_target(target).name();
        for (path, bytes) in templates.render(target, &context)? {
            let path = format!("{target}/{path}");
            if files.contains_key(&path) {
                return Err(Error::TemplateClash {
                    target: target.to_string(),
                    path,
                });
            }
            from_templates.insert(path.clone());
            files.insert(path, bytes);
        }
    }

    Ok(WorldFiles {
        name,
        files,
        from_templates,
    })
}

/// An MJCF model of `terrain` alone, for `mujoco.MjModel.from_xml_string`:
/// our `MuJoCo` template in block mode (floor, light, the box set as
/// static geoms), so it needs no mesh file.
///
/// # Panics
/// Never: our template writes `rse.xml`, as UTF-8 (tested).
pub fn mjcf(terrain: &Terrain) -> Result<String, Error> {
    let boxes = terrain.boxes();
    let name = format!("rse_{}_{}", terrain.seed(), terrain.index());
    let context = WorldContext::new(name, terrain, MeshMode::Blocks, &boxes);
    let files = Templates::builtin_shared().render(Target::Mujoco, &context)?;
    let (_, bytes) = files
        .into_iter()
        .find(|(path, _)| path == "rse.xml")
        .expect("our MuJoCo template writes rse.xml");
    Ok(String::from_utf8(bytes).expect("templates render UTF-8 text"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::options::Targets;
    use rse_core::{Difficulty, generate};

    /// Thousands of same-sized files that differ in their last byte (what a
    /// template folder can hold): each hashed once, copies sharing a
    /// digest, in one pass over the bytes (each file was compared with
    /// every one before it: 5000 of 4 KiB cost some 5·10¹⁰ byte compares).
    #[test]
    fn digests_look_copies_up_by_content() {
        let file = |i: u32| {
            let mut bytes = vec![b'x'; 4096];
            bytes[4092..].copy_from_slice(&i.to_le_bytes());
            bytes
        };
        let mut files: BTreeMap<String, Vec<u8>> = (0..5000)
            .map(|i| (format!("robot/part_{i:04}.stl"), file(i)))
            .collect();
        files.insert("zz/copy_of_7.stl".to_owned(), file(7));
        let found = digests(&files);
        assert_eq!(found.len(), 5001);
        for (path, bytes) in &files {
            assert_eq!(found[path], sha256_hex(bytes), "{path}");
        }
        assert_eq!(found["zz/copy_of_7.stl"], found["robot/part_0007.stl"]);
    }

    fn files(scheme: &str, mesh: MeshMode, targets: &str) -> Vec<String> {
        let scheme = Scheme::from_csv(scheme, None).unwrap();
        let options = WorldOptions {
            targets: Targets::parse(targets).unwrap(),
            mesh,
            ..WorldOptions::default()
        };
        let world = build_world(
            &scheme,
            0,
            3,
            "world_0003".into(),
            &options,
            &Templates::builtin(),
        )
        .unwrap();
        world.files.into_keys().collect()
    }

    const WALL: &str = "# size: 12x8\ntype,height,angle,x1,y1,x2,y2\nwall,3,45,2,2,9,5\n";

    #[test]
    fn a_single_mesh_world_has_the_layout_of_the_spec() {
        assert_eq!(
            files(WALL, MeshMode::Single, &Targets::all().to_string()),
            [
                "gazebo-classic/rse.world",
                "gazebo-classic/rse_terrain/meshes/terrain.mtl",
                "gazebo-classic/rse_terrain/meshes/terrain.obj",
                "gazebo-classic/rse_terrain/model.config",
                "gazebo-classic/rse_terrain/model.sdf",
                "gazebo/rse.world",
                "gazebo/rse_terrain/meshes/terrain.mtl",
                "gazebo/rse_terrain/meshes/terrain.obj",
                "gazebo/rse_terrain/model.config",
                "gazebo/rse_terrain/model.sdf",
                "heightmap.csv",
                "meshes/terrain.mtl",
                "meshes/terrain.obj",
                "mujoco/rse.xml",
                "preview.png",
                "rse.json",
                "urdf/rse.urdf",
                "usd/rse.usda",
                "usd/terrain.usda",
                "webots/rse.wbt",
            ]
        );
    }

    #[test]
    fn block_worlds_carry_no_mesh_but_the_obj_target() {
        let listed = files(WALL, MeshMode::Blocks, "gazebo,webots,mujoco,urdf,usd");
        assert!(
            !listed
                .iter()
                .any(|f| f.contains("terrain.obj") || f == "usd/terrain.usda"),
            "{listed:?}"
        );
        let with_obj = files(WALL, MeshMode::Blocks, "obj,mujoco");
        assert!(with_obj.contains(&"meshes/terrain.obj".to_owned()));
    }

    /// `auto`: URDF collides the box set (faster in `PyBullet`), Gazebo
    /// classic too (ODE rolls bodies off the mesh's interior edges) and draws
    /// the mesh, every other target keeps the mesh; a URDF-only world carries
    /// no mesh at all.
    #[test]
    fn auto_gives_urdf_and_gazebo_classic_boxes_and_the_others_the_mesh() {
        let text = |targets: &str, path: &str| {
            let options = WorldOptions {
                targets: Targets::parse(targets).unwrap(),
                ..WorldOptions::default()
            };
            let scheme = Scheme::from_csv(WALL, None).unwrap();
            let world =
                build_world(&scheme, 0, 3, "w".into(), &options, &Templates::builtin()).unwrap();
            world
                .files
                .get(path)
                .map(|b| String::from_utf8(b.clone()).unwrap())
        };
        let urdf = text(&Targets::all().to_string(), "urdf/rse.urdf").unwrap();
        assert!(
            urdf.contains("<box ") && !urdf.contains("terrain.obj"),
            "{urdf}"
        );
        let sdf = text(&Targets::all().to_string(), "gazebo/rse_terrain/model.sdf").unwrap();
        assert!(
            sdf.contains("terrain.obj") && !sdf.contains("<box>"),
            "{sdf}"
        );
        // Gazebo classic collides the box set and draws the mesh.
        let classic = text("gazebo-classic", "gazebo-classic/rse_terrain/model.sdf").unwrap();
        let (collisions, visual) = classic.split_once("<visual").unwrap();
        assert!(
            collisions.contains("<box>") && !collisions.contains("terrain.obj"),
            "{classic}"
        );
        assert!(
            visual.contains("terrain.obj") && !visual.contains("<box>"),
            "{classic}"
        );
        assert!(text("urdf", "meshes/terrain.obj").is_none());
        assert_eq!(
            files(WALL, MeshMode::Auto, &Targets::all().to_string()),
            files(WALL, MeshMode::Single, &Targets::all().to_string())
        );
    }

    #[test]
    fn an_empty_terrain_has_no_meshes_but_for_the_obj_target() {
        let empty = "# size: 4x4\ntype,height\n";
        let listed = files(empty, MeshMode::Single, &Targets::all().to_string());
        assert!(listed.contains(&"meshes/terrain.obj".to_owned()));
        assert!(
            !listed
                .iter()
                .any(|f| f.contains("rse_terrain/meshes") || f == "usd/terrain.usda")
        );
    }

    #[test]
    fn the_manifest_hashes_every_other_file() {
        let scheme = Scheme::from_csv(WALL, None).unwrap();
        let options = WorldOptions {
            targets: Targets::all(),
            mesh: MeshMode::Blocks,
            ..WorldOptions::default()
        };
        let world = build_world(
            &scheme,
            7,
            1,
            "world_0001".into(),
            &options,
            &Templates::builtin(),
        )
        .unwrap();
        let manifest =
            Manifest::from_json(std::str::from_utf8(&world.files[MANIFEST]).unwrap()).unwrap();
        assert_eq!((manifest.seed, manifest.index), (7, 1));
        assert_eq!(manifest.files.len(), world.files.len() - 1);
        for (path, digest) in &manifest.files {
            assert_eq!(*digest, sha256_hex(&world.files[path]), "{path}");
        }
        let again = Scheme::from_csv(&manifest.scheme, None).unwrap();
        assert_eq!(
            generate(&again, manifest.seed, manifest.index).heightmap(),
            generate(&scheme, 7, 1).heightmap()
        );
    }

    #[test]
    fn the_manifest_records_a_difficulty_below_one_only() {
        let scheme = Scheme::from_csv(WALL, None).unwrap();
        let manifest_of = |difficulty| {
            let options = WorldOptions {
                difficulty,
                ..WorldOptions::default()
            };
            let world =
                build_world(&scheme, 1, 2, "w".into(), &options, &Templates::builtin()).unwrap();
            String::from_utf8(world.files[MANIFEST].clone()).unwrap()
        };
        assert!(!manifest_of(Difficulty::FULL).contains("difficulty"));
        let half = manifest_of(Difficulty::new(0.5).unwrap());
        assert!(half.contains("\"difficulty\": 0.5,"), "{half}");
        assert_eq!(
            Manifest::from_json(&half).unwrap().options.difficulty,
            Difficulty::new(0.5).unwrap()
        );
    }

    #[test]
    fn mjcf_is_the_block_mode_mujoco_world() {
        let scheme = Scheme::from_csv(WALL, None).unwrap();
        let terrain = generate(&scheme, 2, 5);
        let xml = mjcf(&terrain).unwrap();
        assert!(xml.contains("<mujoco model=\"rse_2_5\">"));
        assert_eq!(xml.matches("type=\"box\"").count(), terrain.boxes().len());
        assert!(!xml.contains("<mesh"));
    }
}
