//! One world folder checked: the world is rebuilt in memory from its
//! `rse.json` and every file compared byte for byte (the strongest check,
//! and cheap next to writing the world); files from templates `check`
//! does not have are hashed; then the meshes, heightmap and world files are
//! checked on their own, and with `physics` the terrain is dropped on.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::sync::Arc;

use rse_core::Terrain;
#[cfg(feature = "physics")]
use rse_physics::PhysicsReport;
use rse_world::{
    Generated, MANIFEST, Manifest, RebuildCost, RebuildError, Rebuilt, Recipe, Templates,
};
use serde::Serialize;

use crate::budget::Budget;
use crate::fault::{Fault, FaultKind, excerpt, line_of};
use crate::folder::{Folder, inside};
use crate::limits::{
    MAX_FAULTS, MAX_MANIFEST_BYTES, MAX_MANIFEST_FILES, REBUILD_VISITS, file_cap, rebuild_bytes,
};
use crate::{references, terrain};

/// What to check beyond the static checks, and with what.
#[derive(Debug, Clone)]
pub struct CheckOptions {
    /// Run the rapier physics smoke test on the terrain. A build without
    /// the `physics` feature ([`PHYSICS`](crate::PHYSICS) is `false`)
    /// reports a fault instead.
    pub physics: bool,
    /// Fail a world any of whose files could be compared only with its
    /// hash in `rse.json` (rendered from templates this check does not
    /// have): what such a world proves is only that its files are the ones
    /// it lists.
    pub strict: bool,
    /// The templates to rebuild worlds with: ours (`None`), or ours
    /// overlaid by a user's folder (`check --template DIR`), so that worlds
    /// made with that folder are compared byte for byte too.
    pub templates: Option<Arc<Templates>>,
    /// The rebuild budget, as a multiple of the default
    /// ([`REBUILD_VISITS`](crate::limits::REBUILD_VISITS) cell visits and
    /// the memory available): a world whose recipe costs more is a fault,
    /// not rebuilt.
    pub budget: Budget,
}

impl Default for CheckOptions {
    fn default() -> Self {
        CheckOptions {
            physics: false,
            strict: false,
            templates: None,
            budget: Budget::DEFAULT,
        }
    }
}

/// What was found in one world.
#[derive(Debug, Clone, Serialize)]
pub struct WorldReport {
    /// The world folder, as given or found.
    pub world: String,
    /// `true` when no fault was found.
    pub ok: bool,
    /// Every fault, in a stable order.
    pub faults: Vec<Fault>,
    /// Files that could only be compared with their hash in `rse.json`
    /// (rendered from templates this `check` does not have), sorted.
    pub hashed_only: Vec<String>,
    /// The seed pair from `rse.json`, when it could be read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// What the rebuild was estimated to cost before it was done (held to
    /// the budget), when it was estimated in full.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimate: Option<Estimate>,
    /// Why the physics smoke test asked for cannot judge this world (its
    /// blocks are too small): nothing of it was checked, and
    /// [`check_paths`](crate::check_paths) refuses the command naming it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub physics_refused: Option<String>,
    /// The world's index in its batch, when `rse.json` could be read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub index: Option<u64>,
    /// The manifest, when it could be read: the batch compares its worlds'
    /// recipes with it.
    #[serde(skip)]
    pub manifest: Option<Box<Manifest>>,
    /// The physics smoke test of each exact collider the world's simulators
    /// load, when asked for and the terrain could be rebuilt.
    #[cfg(feature = "physics")]
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub physics: Vec<PhysicsReport>,
}

/// A rebuild's estimated cost, as the JSON report gives it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Estimate {
    /// Memory at the peak, bytes.
    pub bytes: u64,
    /// Work, cell visits.
    pub visits: u64,
    /// The work as seconds on one core of the development machine.
    pub seconds: f64,
}

/// Checks the world folder `path`. Never panics on what is in the folder,
/// reads nothing outside it, and reads no file larger than a cap
/// (`limits`).
pub fn check_world(path: &Path, options: &CheckOptions) -> WorldReport {
    let (folder, mut faults) = Folder::list(path);
    let mut report = WorldReport {
        world: path.display().to_string(),
        ok: false,
        faults: Vec::new(),
        hashed_only: Vec::new(),
        seed: None,
        estimate: None,
        physics_refused: None,
        index: None,
        manifest: None,
        #[cfg(feature = "physics")]
        physics: Vec::new(),
    };
    if faults
        .iter()
        .any(|f| matches!(f.kind, FaultKind::TooManyFiles { .. }))
    {
        report.faults = faults;
        return report;
    }
    match read_manifest(&folder) {
        Err(kind) => {
            faults.push(Fault::of(MANIFEST, kind));
            // Without a manifest there is no world to compare with: look
            // into what can be checked alone.
            for path in folder.paths().filter(|p| references::names_files(p)) {
                match folder.read(path, file_cap(0)) {
                    Ok(bytes) => faults.extend(references::check(path, &bytes, &folder)),
                    Err(kind) => faults.push(Fault::of(path, kind)),
                }
            }
        }
        Ok(manifest) => {
            report.seed = Some(manifest.seed);
            report.index = Some(manifest.index);
            if let Some(folder) = folder_name(path)
                && folder != manifest.world
            {
                faults.push(Fault::new(
                    None,
                    FaultKind::Renamed {
                        folder,
                        index: manifest.index,
                    },
                ));
            }
            check_against_manifest(&folder, &manifest, options, &mut report, &mut faults);
            if options.strict && !report.hashed_only.is_empty() {
                faults.push(Fault::new(
                    None,
                    FaultKind::HashOnly {
                        files: report.hashed_only.len(),
                    },
                ));
            }
            report.manifest = Some(Box::new(manifest));
        }
    }
    // One fault per file and kind: a mesh named twice is missing once.
    let mut seen = BTreeSet::new();
    faults.retain(|f| seen.insert((f.file.clone(), f.message.clone())));
    // The first faults, then how many more: the report stays small,
    // however many files a hostile folder holds.
    if faults.len() > MAX_FAULTS {
        let more = faults.len() - MAX_FAULTS;
        faults.truncate(MAX_FAULTS);
        faults.push(Fault::new(None, FaultKind::MoreFaults { more }));
    }
    report.ok = faults.is_empty();
    report.faults = faults;
    report
}

/// The name of the folder `path` itself, however it was named on the
/// command line (`out/world_0003/.`, a link to it): links and `.`
/// resolved, so the verdict is the same.
fn folder_name(path: &Path) -> Option<String> {
    let real = std::fs::canonicalize(path).ok()?;
    Some(real.file_name()?.to_string_lossy().into_owned())
}

/// `rse.json`, read within its cap and parsed.
fn read_manifest(folder: &Folder) -> Result<Manifest, FaultKind> {
    let bytes = folder.read(MANIFEST, MAX_MANIFEST_BYTES)?;
    let text = std::str::from_utf8(&bytes).map_err(|_| FaultKind::NotText)?;
    Manifest::from_json(text).map_err(|e| FaultKind::BadManifest {
        reason: json_reason(&e),
    })
}

/// What is wrong with `rse.json`, in serde's words less the text it
/// quotes from the file (the variant of "unknown variant …", the string
/// of "invalid type: string …"): that text may be anyone's. A missing
/// field is ours to name.
fn json_reason(e: &serde_json::Error) -> String {
    let words = e.to_string();
    let words = words
        .rsplit_once(" at line ")
        .map_or(words.as_str(), |(words, _)| words);
    let quoted = words.find(['`', '"']);
    let said = match quoted {
        Some(at) if !words.starts_with("missing field") => {
            let close = words[at + 1..]
                .find(&words[at..=at])
                .map_or(words.len(), |end| at + 1 + end + 1);
            format!("{}…{}", &words[..at], &words[close..])
        }
        _ => words.to_owned(),
    };
    format!("{said} at line {}, column {}", e.line(), e.column())
}

/// The checks of a manifest before its recipe is read: the paths it
/// names, the world's name. `false`: do not rebuild.
fn fit_to_rebuild(manifest: &Manifest, faults: &mut Vec<Fault>) -> bool {
    // Each file listed is read or hashed: no more than a world can hold.
    if manifest.files.len() > MAX_MANIFEST_FILES {
        faults.push(Fault::of(
            MANIFEST,
            FaultKind::TooManyFiles {
                cap: MAX_MANIFEST_FILES,
            },
        ));
        return false;
    }
    // Paths the manifest names are checked as names before anything is read.
    let outside: Vec<&String> = manifest.files.keys().filter(|p| !inside(p)).collect();
    for path in &outside {
        faults.push(Fault::of(
            MANIFEST,
            FaultKind::OutsideWorld {
                path: excerpt(path),
            },
        ));
    }
    // A name that could not be written into a world's files: never
    // rendered, and not quoted (the manifest may be anyone's).
    if rse_world::world_name_problem(&manifest.world).is_some() {
        faults.push(Fault::of(
            MANIFEST,
            FaultKind::BadManifest {
                reason: "its world name is not a world name rse writes (letters, digits, '_', \
                         '-' and '.', at most 128)"
                    .to_owned(),
            },
        ));
        return false;
    }
    true
}

/// A manifest's recipe, parsed once, priced from itself and then, with the
/// terrain that price allowed generating, from the files its mesh and boxes
/// make: `rse.json` is input, and what it asks to rebuild is held to a
/// budget before anything is built. `None`: do not rebuild (the fault is
/// pushed).
fn generate_within_budget<'m>(
    manifest: &'m Manifest,
    options: &CheckOptions,
    report: &mut WorldReport,
    faults: &mut Vec<Fault>,
) -> Option<Generated<'m>> {
    let recipe = match Recipe::of(manifest) {
        Ok(recipe) => recipe,
        Err(e) => {
            faults.push(Fault::of(MANIFEST, rebuild_fault(e)));
            return None;
        }
    };
    let block_size = recipe.block_size();
    if options.physics
        && let Some(reason) = crate::physics::physics_refusal(block_size)
    {
        // Refused before anything is built: the command refuses the check.
        report.physics_refused = Some(reason);
        return None;
    }
    let mut within = |cost: RebuildCost, report: &mut WorldReport| {
        let cost = with_physics(cost, manifest, options, block_size);
        if let Some(kind) = over_budget(cost, options.budget) {
            faults.push(Fault::of(MANIFEST, kind));
            return false;
        }
        report.estimate = Some(Estimate {
            bytes: cost.bytes,
            visits: cost.visits,
            seconds: cost.seconds(),
        });
        true
    };
    let templates = templates_of(options);
    if !within(recipe.cost(templates), report) {
        return None;
    }
    match recipe.generate() {
        Ok(generated) => within(generated.cost(templates), report).then_some(generated),
        Err(e) => {
            faults.push(Fault::of(MANIFEST, rebuild_fault(e)));
            None
        }
    }
}

/// `cost` and, under `--physics`, the smoke test's.
fn with_physics(
    mut cost: RebuildCost,
    manifest: &Manifest,
    options: &CheckOptions,
    block_size: f64,
) -> RebuildCost {
    if options.physics {
        let (visits, bytes) = crate::physics::cost(manifest, &cost, block_size);
        cost.visits = cost.visits.saturating_add(visits);
        cost.bytes = cost.bytes.saturating_add(bytes);
    }
    cost
}

/// The memory the world at `path` is priced to take from its recipe alone
/// (before anything is generated; 0 where it has no recipe to price):
/// what [`check_paths`](crate::check_paths) counts to know how many
/// worlds fit in memory at once.
pub(crate) fn recipe_bytes(path: &Path, options: &CheckOptions) -> u64 {
    let (folder, _) = Folder::list(path);
    let Ok(manifest) = read_manifest(&folder) else {
        return 0;
    };
    let Ok(recipe) = Recipe::of(&manifest) else {
        return 0;
    };
    let cost = recipe.cost(templates_of(options));
    with_physics(cost, &manifest, options, recipe.block_size()).bytes
}

/// The templates worlds are rebuilt with: the user's, or ours.
fn templates_of(options: &CheckOptions) -> &Templates {
    options
        .templates
        .as_deref()
        .unwrap_or_else(|| Templates::builtin_shared())
}

/// Every check that needs the manifest.
fn check_against_manifest(
    folder: &Folder,
    manifest: &Manifest,
    options: &CheckOptions,
    report: &mut WorldReport,
    faults: &mut Vec<Fault>,
) {
    if !fit_to_rebuild(manifest, faults) {
        return;
    }
    let Some(generated) = generate_within_budget(manifest, options, report, faults) else {
        return;
    };
    let templates = templates_of(options);
    let Rebuilt {
        terrain,
        files: expected,
        hashed_only,
    } = match generated.rebuild(templates) {
        Ok(rebuilt) => rebuilt,
        Err(e) => {
            faults.push(Fault::of(MANIFEST, rebuild_fault(e)));
            return;
        }
    };
    let cells = u64::from(terrain.grid().nx) * u64::from(terrain.grid().ny);
    let mut contents: BTreeMap<&str, Vec<u8>> = BTreeMap::new();
    for (path, want) in &expected {
        // No more is read than the rebuilt file holds: a longer file is a
        // fault as it stands, and whatever parses it below (a mesh) parses
        // at most that much.
        // A file found to differ is a fault and nothing more: it is not
        // parsed, mesh-checked or dropped bodies on (a same-size hostile
        // OBJ once cost 15–36 s of CPU, and its physics ran away).
        match folder.read(path, want.len() as u64) {
            Ok(bytes) => match difference(path, &bytes, want, &terrain) {
                Some(kind) => faults.push(Fault::of(path, kind)),
                None => {
                    contents.insert(path, bytes);
                }
            },
            Err(kind) => faults.push(Fault::of(path, kind)),
        }
    }
    // Files check can only hash are hashed as they stream, never held: the
    // manifest can claim any number of them, each up to the rendered-file
    // cap. One that names other files is then read for its references, one
    // at a time and no larger than the memory budget.
    let text_cap = file_cap(cells).min(options.budget.scale(rebuild_bytes()));
    // A user's files that name others are read for their references too:
    // priced now they are rendered, by their size (a copied MJCF of 65,000
    // long paths took 3 s priced at nothing).
    let users_outputs = templates.user_outputs(&manifest.options.targets);
    let users_naming = users_outputs
        .iter()
        .filter(|path| references::names_files(path))
        .filter_map(|path| expected.get(path))
        .map(|bytes| bytes.len() as u64);
    let hashed =
        HashedCost::of(&hashed_only, folder, file_cap(cells), text_cap).and_read(users_naming);
    if !hashed.within_budget(cells, options, report, faults) {
        return;
    }
    let mut referenced = Vec::new();
    for path in &hashed_only {
        let Some(digest) = manifest.files.get(path) else {
            continue;
        };
        match folder.digest(path, file_cap(cells)) {
            Ok((found, _)) if found != *digest => {
                faults.push(Fault::of(path, FaultKind::HashMismatch));
            }
            Ok(_) if references::names_files(path) => referenced.push(path),
            Ok(_) => {}
            Err(kind) => faults.push(Fault::of(path, kind)),
        }
    }
    for path in folder.paths() {
        if !expected.contains_key(path) && !hashed_only.contains(path) {
            faults.push(Fault::of(path, FaultKind::Unexpected));
        }
    }
    // The files checked on their own: world files' references, meshes.
    for (path, bytes) in &contents {
        faults.extend(references::check(path, bytes, folder));
    }
    for path in referenced {
        match folder.read(path, text_cap) {
            Ok(bytes) => faults.extend(references::check(path, &bytes, folder)),
            Err(kind) => faults.push(Fault::of(path, kind)),
        }
    }
    let mut meshes: Vec<(&str, terrain::ObjMesh)> = Vec::new();
    let is_obj = |p: &str| {
        std::path::Path::new(p)
            .extension()
            .is_some_and(|e| e == "obj")
    };
    // Copies of one mesh (meshes/ and the Gazebo model's) are read and
    // checked once; each copy gets the faults found.
    let mut checked: Vec<(&[u8], Vec<FaultKind>)> = Vec::new();
    // Only the meshes rebuilt here: a terrain mesh is never rendered from a
    // template, and each is read no longer than ours.
    let rebuilt_obj = |p: &str| is_obj(p) && expected.contains_key(p);
    for (path, bytes) in contents.iter().filter(|(p, _)| rebuilt_obj(p)) {
        let bytes = bytes.as_slice();
        if let Some((_, found)) = checked.iter().find(|(b, _)| *b == bytes) {
            faults.extend(found.iter().map(|kind| Fault::of(path, kind.clone())));
            continue;
        }
        let found = match terrain::read_obj(bytes) {
            Ok(mesh) => {
                let found = terrain::mesh_faults_against(&mesh, &terrain);
                meshes.push((path, mesh));
                found
            }
            Err(kind) => vec![kind],
        };
        faults.extend(found.iter().map(|kind| Fault::of(path, kind.clone())));
        checked.push((bytes, found));
    }
    report.hashed_only = hashed_only.iter().cloned().collect();
    if options.physics {
        run_physics(manifest, meshes, &terrain, report, faults);
    }
}

/// The physics smoke test, its reports kept on `report` (a build without
/// physics has none: its `run` only adds the fault that says so).
fn run_physics(
    manifest: &Manifest,
    meshes: Vec<(&str, terrain::ObjMesh)>,
    terrain: &Terrain,
    report: &mut WorldReport,
    faults: &mut Vec<Fault>,
) {
    #[cfg(feature = "physics")]
    {
        report.physics = crate::physics::run(manifest, meshes, terrain, faults);
    }
    #[cfg(not(feature = "physics"))]
    {
        let _ = report;
        crate::physics::run(manifest, meshes, terrain, faults);
    }
}

/// How the file at `path` (its `bytes`) differs from the regenerated
/// `want`; `None` if it does not.
fn difference(path: &str, bytes: &[u8], want: &[u8], terrain: &Terrain) -> Option<FaultKind> {
    if bytes == want {
        return None;
    }
    if path == "heightmap.csv" {
        // Name the cell, not just the line, where that is the difference.
        if let Some(kind) = terrain::heightmap_fault(bytes, terrain) {
            return Some(kind);
        }
    }
    let byte = bytes
        .iter()
        .zip(want)
        .position(|(a, b)| a != b)
        .unwrap_or(bytes.len().min(want.len()));
    let text = std::str::from_utf8(want).is_ok();
    Some(FaultKind::Differs {
        line: text.then(|| line_of(want, byte)),
        byte,
    })
}

/// What `check` pays for the files it can only hash: reading and hashing
/// every byte, and parsing those that name other files for their
/// references; and for a user's files it rebuilt, their references.
struct HashedCost {
    visits: u64,
    bytes: u64,
}

/// Bytes hashed a visit (SHA-256 as it streams: bench/budget.py measured
/// 1.6 GB of sparse files hashed in ~1.3 s here, ~0.8 ns a byte).
const HASHED_BYTES_PER_VISIT: u64 = 4;
/// Parsing a byte of a world file for its references (XML as a stream,
/// the references checked): measured by bench/budget.py.
const REFERENCE_VISITS_PER_BYTE: u64 = 4;
/// Memory per byte of a file read for its references: the text, and the
/// references held while they are checked.
const REFERENCE_BYTES_PER_BYTE: u64 = 3;

impl HashedCost {
    /// Adds this to the world's estimate and holds the whole to the budget
    /// before a byte is hashed (8 sparse files of 4 GB once hashed for
    /// 175 s against an estimate of half a second); `false`, with the
    /// fault pushed, when it is over.
    fn within_budget(
        &self,
        cells: u64,
        options: &CheckOptions,
        report: &mut WorldReport,
        faults: &mut Vec<Fault>,
    ) -> bool {
        let Some(estimate) = &mut report.estimate else {
            return true;
        };
        let cost = RebuildCost {
            cells,
            bytes: estimate.bytes.max(self.bytes),
            visits: estimate.visits.saturating_add(self.visits),
            models: None,
        };
        (estimate.bytes, estimate.visits, estimate.seconds) =
            (cost.bytes, cost.visits, cost.seconds());
        match over_budget(cost, options.budget) {
            Some(kind) => {
                faults.push(Fault::of(MANIFEST, kind));
                false
            }
            None => true,
        }
    }

    /// The cost of the files `hashed` of `folder`, each hashed up to
    /// `cap` bytes and, if it names files, read up to `text_cap`.
    fn of(hashed: &BTreeSet<String>, folder: &Folder, cap: u64, text_cap: u64) -> Self {
        let (mut visits, mut bytes) = (0u64, 0u64);
        for path in hashed {
            let size = folder.size(path).unwrap_or(0);
            visits = visits.saturating_add(size.min(cap) / HASHED_BYTES_PER_VISIT);
            if references::names_files(path) {
                let read = size.min(text_cap);
                visits = visits.saturating_add(read.saturating_mul(REFERENCE_VISITS_PER_BYTE));
                // One file at a time: the largest is the peak.
                bytes = bytes.max(read.saturating_mul(REFERENCE_BYTES_PER_BYTE));
            }
        }
        HashedCost { visits, bytes }
    }

    /// This, and files of these `sizes`, already in memory, read for their
    /// references.
    fn and_read(mut self, sizes: impl Iterator<Item = u64>) -> Self {
        for size in sizes {
            self.visits = self
                .visits
                .saturating_add(size.saturating_mul(REFERENCE_VISITS_PER_BYTE));
            self.bytes = self
                .bytes
                .max(size.saturating_mul(REFERENCE_BYTES_PER_BYTE));
        }
        self
    }
}

/// The fault of a world whose rebuild would cost more than `scale` times
/// the default budget, or `None` when it is within it.
fn over_budget(cost: RebuildCost, budget: Budget) -> Option<FaultKind> {
    let bytes_budget = budget.scale(rebuild_bytes());
    let visits_budget = budget.scale(REBUILD_VISITS);
    (cost.bytes > bytes_budget || cost.visits > visits_budget).then_some(FaultKind::OverBudget {
        cells: cost.cells,
        bytes: cost.bytes,
        bytes_budget,
        visits: cost.visits,
        visits_budget,
    })
}

/// The fault of a manifest whose world cannot be rebuilt.
fn rebuild_fault(e: RebuildError) -> FaultKind {
    match e {
        RebuildError::Scheme(e) => FaultKind::BadScheme {
            reason: e.to_string(),
        },
        other => FaultKind::BadManifest {
            reason: other.to_string(),
        },
    }
}
