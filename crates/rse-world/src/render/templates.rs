//! The static part of each target's world (paper §3.5): files copied into
//! every world as they are, and `.j2` files rendered with minijinja (the
//! suffix dropped) with the world's values.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use minijinja::{AutoEscape, Environment, UndefinedBehavior};

use crate::error::Error;
use crate::files::digest::sha256_hex;
use crate::files::nofollow::{Listed, OpenFolder, ReadError, refused};
use crate::files::write::Created;
use crate::record::manifest::TemplateSet;
use crate::record::options::Target;
use crate::render::context::WorldContext;

/// Suffix of the files that are rendered rather than copied.
const TEMPLATE_SUFFIX: &str = ".j2";

/// Our templates, built into the binary so that an installed `rse-gen`
/// needs no data files. `builtin_templates_match_the_folder` keeps this list
/// equal to `templates/`.
const BUILTIN: &[(Target, &str, &str)] = &[
    (
        Target::Gazebo,
        "rse.world.j2",
        include_str!("../../../../templates/gazebo/rse.world.j2"),
    ),
    (
        Target::Gazebo,
        "rse_terrain/model.config.j2",
        include_str!("../../../../templates/gazebo/rse_terrain/model.config.j2"),
    ),
    (
        Target::Gazebo,
        "rse_terrain/model.sdf.j2",
        include_str!("../../../../templates/gazebo/rse_terrain/model.sdf.j2"),
    ),
    (
        Target::GazeboClassic,
        "rse.world.j2",
        include_str!("../../../../templates/gazebo-classic/rse.world.j2"),
    ),
    (
        Target::GazeboClassic,
        "rse_terrain/model.config.j2",
        include_str!("../../../../templates/gazebo-classic/rse_terrain/model.config.j2"),
    ),
    (
        Target::GazeboClassic,
        "rse_terrain/model.sdf.j2",
        include_str!("../../../../templates/gazebo-classic/rse_terrain/model.sdf.j2"),
    ),
    (
        Target::Webots,
        "rse.wbt.j2",
        include_str!("../../../../templates/webots/rse.wbt.j2"),
    ),
    (
        Target::Mujoco,
        "rse.xml.j2",
        include_str!("../../../../templates/mujoco/rse.xml.j2"),
    ),
    (
        Target::Urdf,
        "rse.urdf.j2",
        include_str!("../../../../templates/urdf/rse.urdf.j2"),
    ),
    (
        Target::Usd,
        "rse.usda.j2",
        include_str!("../../../../templates/usd/rse.usda.j2"),
    ),
];

/// Our files that every target's templates share, imported by name
/// (`{% import "look.j2" as look %}`: the terrain's and the ground's looks
/// in every target, so a look key of the scheme is written in one file).
/// Built in, for ours and a user's templates alike; never written into a
/// world, and not replaced by a `--template` folder (a user's template
/// that wants another look writes it itself).
const SHARED: &[(&str, &str)] = &[("look.j2", include_str!("../../../../templates/look.j2"))];

/// One file of a target's template folder.
#[derive(Debug, Clone)]
struct TemplateFile {
    /// Path inside the target's folder, `/`-separated.
    path: String,
    /// Contents, for a file that is copied.
    bytes: Vec<u8>,
    /// The name errors give: where the file came from.
    origin: String,
    /// One of our templates (`BUILTIN`), not a user's.
    ours: bool,
}

/// The template folders of every target, parsed once for a whole batch.
pub struct Templates {
    files: BTreeMap<Target, Vec<TemplateFile>>,
    env: Environment<'static>,
    custom: bool,
    digest: String,
}

impl std::fmt::Debug for Templates {
    /// The set and its digest: the parsed templates themselves say little.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Templates")
            .field("set", &self.set())
            .field("digest", &self.digest())
            .finish_non_exhaustive()
    }
}

impl Templates {
    /// Our own templates (`templates/` of the repository).
    ///
    /// # Panics
    /// Never: the tests render every built-in template.
    pub fn builtin() -> Self {
        let mut files: BTreeMap<Target, Vec<TemplateFile>> = BTreeMap::new();
        for &(target, path, source) in BUILTIN {
            files.entry(target).or_default().push(TemplateFile {
                path: path.to_owned(),
                bytes: source.as_bytes().to_vec(),
                origin: format!("templates/{target}/{path}"),
                ours: true,
            });
        }
        Self::new(files, false).expect("the built-in templates parse")
    }

    /// Ours, parsed once per process and shared: for callers that render
    /// with them again and again (`check` per world, `mjcf` per terrain).
    pub fn builtin_shared() -> &'static Templates {
        static BUILTIN: std::sync::OnceLock<Templates> = std::sync::OnceLock::new();
        BUILTIN.get_or_init(Templates::builtin)
    }

    /// Ours, overlaid file by file with the target folders present in
    /// `dir` (`dir/gazebo/`, …): a user's file replaces ours of the same
    /// output path (`rse.world` and `rse.world.j2` both replace our
    /// `rse.world.j2`), and their other files (a robot model, say) are
    /// added to every world; our files they do not name are kept. So a
    /// folder holding one edited template is a whole template set.
    pub fn with_overrides(dir: &Path) -> Result<Self, Error> {
        // Opened once, by descriptor (the folder named may be a link; nothing
        // below it is followed): every file is read as `check` reads a
        // world, so a link, FIFO or device in it is refused, not followed.
        let opened = OpenFolder::open(dir, true).map_err(|e| match e {
            ReadError::Missing => Error::BadTemplateFolder {
                path: dir.to_owned(),
                reason: "it does not exist".to_owned(),
            },
            ReadError::NotAFile => Error::BadTemplateFolder {
                path: dir.to_owned(),
                reason: "it is not a folder".to_owned(),
            },
            other => refused(dir, "", other),
        })?;
        let mut theirs = read_tree(&opened)?;
        let mut files = Self::builtin().files;
        let mut any = false;
        for target in Target::ALL {
            let Some(theirs) = theirs.remove(&target) else {
                continue;
            };
            any = true;
            let ours = files.entry(target).or_default();
            ours.retain(|file| {
                !theirs
                    .iter()
                    .any(|t| output_path(&t.path) == output_path(&file.path))
            });
            ours.extend(theirs);
            ours.sort_by(|a, b| a.path.cmp(&b.path));
        }
        if !any {
            return Err(Error::BadTemplateFolder {
                path: dir.to_owned(),
                reason: format!(
                    "it has no target folder (expected one of {})",
                    Target::ALL.map(Target::name).join(", ")
                ),
            });
        }
        Self::new(files, true)
    }

    /// Writes our templates into `dir/<target>/…`, to copy and edit
    /// (`rse-gen templates export`). `dir` may be a link to a folder;
    /// nothing below it is followed: a sub-folder that is a link or a file
    /// is refused, and every file is created new (`O_EXCL`), so an existing
    /// file or link is never written through. On any failure every file
    /// and folder it made is removed again.
    pub fn export_builtin(dir: &Path) -> Result<Vec<std::path::PathBuf>, Error> {
        Created::undone_on_error(|made| export_into(dir, made))
    }

    fn new(files: BTreeMap<Target, Vec<TemplateFile>>, custom: bool) -> Result<Self, Error> {
        let mut env = Environment::new();
        env.set_undefined_behavior(UndefinedBehavior::Strict);
        // World files are XML, VRML and USD with values we compute: numbers
        // and plain names. Nothing needs escaping, and HTML escaping would
        // be wrong in the non-XML ones.
        env.set_auto_escape_callback(|_| AutoEscape::None);
        env.add_filter("join", crate::render::join_filter::join);
        env.set_syntax(
            minijinja::syntax::SyntaxConfig::builder()
                .trim_blocks(true)
                .lstrip_blocks(true)
                .keep_trailing_newline(true)
                .build()
                .expect("default delimiters"),
        );
        let mut all = Vec::new();
        for &(name, source) in SHARED {
            all.extend(format!("{name}\0{}\0", source.len()).bytes());
            all.extend(source.as_bytes());
            env.add_template(name, source)
                .map_err(|e| template_error(&format!("templates/{name}"), source.as_bytes(), &e))?;
        }
        for (target, list) in &files {
            for file in list {
                all.extend(format!("{target}/{}\0{}\0", file.path, file.bytes.len()).bytes());
                all.extend(&file.bytes);
                if !file.path.ends_with(TEMPLATE_SUFFIX) {
                    continue;
                }
                let source =
                    String::from_utf8(file.bytes.clone()).map_err(|e| Error::Template {
                        file: file.origin.clone(),
                        line: file.bytes[..e.utf8_error().valid_up_to()]
                            .split(|&b| b == b'\n')
                            .count(),
                        message: "not UTF-8 text".to_owned(),
                    })?;
                env.add_template_owned(file.origin.clone(), source)
                    .map_err(|e| template_error(&file.origin, &file.bytes, &e))?;
            }
        }
        let digest = sha256_hex(&all);
        Ok(Templates {
            files,
            env,
            custom,
            digest,
        })
    }

    /// `true` when a user's folder replaced some of ours.
    pub fn is_custom(&self) -> bool {
        self.custom
    }

    /// The set `rse.json` records: built-in or custom.
    pub fn set(&self) -> TemplateSet {
        if self.custom {
            TemplateSet::Custom
        } else {
            TemplateSet::Builtin
        }
    }

    /// SHA-256 over every template file (paths and bytes): what the
    /// manifest records instead of a path.
    pub fn digest(&self) -> &str {
        &self.digest
    }

    /// The files of `target`'s folder for one world: `(path inside the
    /// target folder, bytes)`.
    pub(crate) fn render(
        &self,
        target: Target,
        context: &WorldContext,
    ) -> Result<Vec<(String, Vec<u8>)>, Error> {
        let boxes = context.boxes.len().unwrap_or_default();
        self.render_with_fuel(target, context, render_fuel(boxes as u64), Fueled::Users)
    }

    /// [`render`](Self::render) with `fuel` instructions per file of
    /// those `fueled` names.
    fn render_with_fuel(
        &self,
        target: Target,
        context: &WorldContext,
        fuel: u64,
        fueled: Fueled,
    ) -> Result<Vec<(String, Vec<u8>)>, Error> {
        let Some(list) = self.files.get(&target) else {
            return Ok(Vec::new());
        };
        let value = minijinja::Value::from(minijinja::value::Serde(context));
        // Fuel per file, for this world's box count: a user's template's
        // loops cannot run on without bound (three nested `range(100000)`).
        // Ours loop over the boxes only and need a fifth of it
        // (`our_templates_need_a_fifth_of_the_fuel`): they run without
        // the count, which cost a fifth of their time. Cloning an
        // environment shares its compiled templates.
        let counted = |file: &TemplateFile| fueled == Fueled::All || !file.ours;
        let fueled_env = list.iter().any(counted).then(|| {
            let mut env = self.env.clone();
            env.set_fuel(Some(fuel));
            env
        });
        list.iter()
            .map(|file| {
                let Some(path) = file.path.strip_suffix(TEMPLATE_SUFFIX) else {
                    return Ok((file.path.clone(), file.bytes.clone()));
                };
                let env = match &fueled_env {
                    Some(env) if counted(file) => env,
                    _ => &self.env,
                };
                let template = env
                    .get_template(&file.origin)
                    .map_err(|e| template_error(&file.origin, &file.bytes, &e))?;
                let mut out = CappedOutput::new(output_cap(context));
                template
                    .render_captured_to(&value, &mut out)
                    .map(drop)
                    .map_err(|e| {
                        if out.over {
                            Error::Template {
                                file: file.origin.clone(),
                                line: e.line().unwrap_or(1),
                                message: format!(
                                    "renders more than {} bytes for a world of this size",
                                    out.cap
                                ),
                            }
                        } else {
                            template_error(&file.origin, &file.bytes, &e)
                        }
                    })?;
                Ok((path.to_owned(), out.bytes))
            })
            .collect()
    }
}

/// Whose templates a render counts the instructions of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Fueled {
    /// A user's only: ours are known to end.
    Users,
    /// Ours too (the tests that measure what ours need).
    All,
}

/// The fuel one template may spend for a world of `boxes` boxes: our
/// templates spend 24–48 a box, bytes included (minijinja counts an
/// instruction as a fuel and a byte it creates as a 64th:
/// `our_templates_need_a_fifth_of_the_fuel`); a user's gets four times our
/// most, and a fixed part for loops and text of their own (some 70 ms of
/// loops, or 128 MB of text). `check --template` prices a user's template
/// at this bound, in time and in memory (it cannot know less before
/// rendering), so the bound is kept near what templates need: at 1000 a
/// box and 10⁷ fixed, a 1000×1000 field priced 29 GB a file.
pub const FUEL_PER_BOX: u64 = 200;
/// See [`FUEL_PER_BOX`].
pub const FIXED_FUEL: u64 = 2_000_000;

/// Bytes a template may create for one fuel: minijinja 3.1 charges one
/// 64th of a fuel for each byte of a string, list or output it makes.
pub const BYTES_PER_FUEL: u64 = 64;

/// One instruction of minijinja's, in cell visits ([`crate::VISIT_NANOS`]
/// each): a loop that spends a world's whole fuel took 2.0 s for 5.5·10⁷
/// instructions, ~36 ns each.
pub const VISITS_PER_FUEL: u64 = 7;

impl Templates {
    /// The user's files of `targets`' folders, with their targets.
    fn users_files<'a>(
        &'a self,
        targets: &'a crate::Targets,
    ) -> impl Iterator<Item = (Target, &'a TemplateFile)> + 'a {
        targets
            .iter()
            .filter_map(|target| Some((target, self.files.get(&target)?)))
            .flat_map(|(target, list)| list.iter().map(move |file| (target, file)))
            .filter(|(_, file)| !file.ours)
    }

    /// How many of the files `targets` render are a user's templates (run
    /// under fuel; ours are priced with the files they write).
    pub(crate) fn user_templates(&self, targets: &crate::Targets) -> u64 {
        self.users_files(targets)
            .filter(|(_, file)| file.path.ends_with(TEMPLATE_SUFFIX))
            .count() as u64
    }

    /// The bytes of the user's files `targets` copy as they are (not
    /// templates): each world holds them (a 240 MB one was priced at
    /// nothing).
    pub(crate) fn copied_bytes(&self, targets: &crate::Targets) -> u64 {
        self.users_files(targets)
            .filter(|(_, file)| !file.path.ends_with(TEMPLATE_SUFFIX))
            .map(|(_, file)| file.bytes.len() as u64)
            .fold(0, u64::saturating_add)
    }

    /// Where in a world of `targets` the user's files land (rendered or
    /// copied): `target/path`, as `rse.json` lists them.
    pub fn user_outputs(&self, targets: &crate::Targets) -> BTreeSet<String> {
        self.users_files(targets)
            .map(|(target, file)| format!("{target}/{}", output_path(&file.path)))
            .collect()
    }
}

/// The most work rendering `users` of a user's templates for a world of
/// `boxes` boxes may take, in cell visits: each at its fuel.
pub(crate) fn render_visits(users: u64, boxes: u64) -> u64 {
    users
        .saturating_mul(render_fuel(boxes))
        .saturating_mul(VISITS_PER_FUEL)
}

/// The most memory rendering `users` of a user's templates for a world of
/// `boxes` boxes may hold: each the bytes its fuel lets it create (its
/// strings and its output; nested `replace`s once built 117 MB priced at
/// nothing), and its output once more as `check` reads it back.
pub(crate) fn render_bytes(users: u64, boxes: u64) -> u64 {
    users
        .saturating_mul(render_fuel(boxes))
        .saturating_mul(BYTES_PER_FUEL)
        .saturating_mul(2)
}

fn render_fuel(boxes: u64) -> u64 {
    FIXED_FUEL.saturating_add(boxes.saturating_mul(FUEL_PER_BOX))
}

/// The most bytes one rendered file of a world may hold: what `check`
/// accepts of a file it cannot regenerate ([`rendered_file_cap`]).
fn output_cap(context: &WorldContext) -> u64 {
    rendered_file_cap(u64::from(context.cells[0]) * u64::from(context.cells[1]))
}

/// A file rendered from a template may hold at most this many bytes per
/// cell of the world's grid, plus [`FIXED_FILE_BYTES`]. Our largest per-cell
/// file, a block-mode world's box list, is well under 1 KiB per cell.
pub const FILE_BYTES_PER_CELL: u64 = 4096;

/// The fixed part of the per-file cap, bytes: room for a robot model or a
/// texture a user's template adds to every world.
pub const FIXED_FILE_BYTES: u64 = 64 << 20;

/// The byte cap of a rendered file (or one `check` cannot regenerate) in a
/// world of `cells` cells.
pub fn rendered_file_cap(cells: u64) -> u64 {
    FIXED_FILE_BYTES.saturating_add(cells.saturating_mul(FILE_BYTES_PER_CELL))
}

/// A rendered file's bytes, refused past a cap: a template that prints
/// without bound fails instead of filling memory.
struct CappedOutput {
    bytes: Vec<u8>,
    cap: u64,
    over: bool,
}

impl CappedOutput {
    fn new(cap: u64) -> Self {
        CappedOutput {
            bytes: Vec::new(),
            cap,
            over: false,
        }
    }
}

impl std::io::Write for CappedOutput {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if (self.bytes.len() + buf.len()) as u64 > self.cap {
            self.over = true;
            return Err(std::io::Error::other("over the cap"));
        }
        self.bytes.extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// [`Templates::export_builtin`]'s work, noting in `made` what it creates.
fn export_into(dir: &Path, made: &mut Created) -> Result<Vec<std::path::PathBuf>, Error> {
    let bad = |path: &Path, reason: String| Error::BadTemplateFolder {
        path: path.to_owned(),
        reason,
    };
    let paths: Vec<_> = BUILTIN
        .iter()
        .map(|&(target, path, _)| dir.join(target.name()).join(path))
        .collect();
    if let Some(existing) = paths.iter().find(|p| p.symlink_metadata().is_ok()) {
        return Err(bad(
            dir,
            format!(
                "{} exists already: export into an empty folder",
                existing.display()
            ),
        ));
    }
    made.folder_chain(dir, None)?;
    for (path, &(_, _, source)) in paths.iter().zip(BUILTIN) {
        let parent = path.parent().expect("a target folder");
        made.folder_chain(parent, Some(dir))?;
        made.new_file(path, source.as_bytes())?;
    }
    Ok(paths)
}

/// The path a template file gets in a world: `.j2` files lose the suffix.
fn output_path(path: &str) -> &str {
    path.strip_suffix(TEMPLATE_SUFFIX).unwrap_or(path)
}

/// Our error for a minijinja error in `file` (its text `source`), with its
/// line; an undefined value is named (`undefined value 'spawn_height'`),
/// which minijinja itself does not do.
fn template_error(file: &str, source: &[u8], e: &minijinja::Error) -> Error {
    let named = (e.kind() == minijinja::ErrorKind::UndefinedError)
        .then(|| e.range())
        .flatten()
        .and_then(|range| source.get(range))
        .and_then(|text| std::str::from_utf8(text).ok())
        .map(str::trim)
        .filter(|name| !name.is_empty());
    Error::Template {
        file: file.to_owned(),
        line: e.line().unwrap_or(1),
        message: match (named, e.detail()) {
            (Some(name), _) => format!("undefined value '{name}'"),
            (None, Some(detail)) => format!("{}: {detail}", e.kind()),
            (None, None) => e.kind().to_string(),
        },
    }
}

/// The most bytes of one file of a user's template folder (a robot's
/// meshes fit), and of all its files together: every world gets a copy, and
/// the set is held in memory for the whole batch.
pub const MAX_TEMPLATE_FILE_BYTES: u64 = 256 << 20;
/// See [`MAX_TEMPLATE_FILE_BYTES`].
pub const MAX_TEMPLATE_BYTES: u64 = 1 << 30;

/// The files of every target folder (`gazebo/`, …) of a user's template
/// folder, with paths relative to the target folder: listed and read
/// through the folder's one descriptor ([`OpenFolder`]: no link followed at
/// any level, no FIFO or device opened, every file read from the
/// descriptor that was checked, within a cap). A link or special file in a
/// target folder, or a target folder that is a link or a file, is an error
/// naming it: following one would copy whatever it points at (a secret,
/// `/dev/zero`) into every world. Entries outside the target folders are
/// not read.
fn read_tree(folder: &OpenFolder) -> Result<BTreeMap<Target, Vec<TemplateFile>>, Error> {
    let dir = folder.path();
    let mut files: BTreeMap<Target, Vec<TemplateFile>> = BTreeMap::new();
    let mut total = 0u64;
    for (relative, listed) in folder.list() {
        let (top, inner) = relative.split_once('/').unwrap_or((&relative, ""));
        let Ok(target) = top.parse::<Target>() else {
            continue;
        };
        let path = dir.join(&relative);
        let bad = |reason: &str| Error::BadTemplateFolder {
            path: path.clone(),
            reason: reason.to_owned(),
        };
        match listed {
            // Nothing to write: a world has no empty folders.
            Listed::EmptyFolder => {
                files.entry(target).or_default();
            }
            Listed::NotAFile if inner.is_empty() => {
                return Err(bad("a target folder must be a folder, not a link or file"));
            }
            Listed::File { .. } if inner.is_empty() => {
                return Err(bad("a target folder must be a folder, not a file"));
            }
            Listed::NotAFile => {
                return Err(bad(
                    "a link or special file: template files are read, never followed",
                ));
            }
            Listed::Unreadable(reason) => {
                return Err(Error::io("read", path)(std::io::Error::other(reason)));
            }
            Listed::File { .. } => {
                let cap = MAX_TEMPLATE_FILE_BYTES.min(MAX_TEMPLATE_BYTES.saturating_sub(total));
                let file = match folder.read(&relative, cap) {
                    // Another name for it may be outside the folder (a
                    // secret linked in would reach every world): `check`
                    // reads no world file with two names either. Judged
                    // on the file opened, not the listing.
                    Ok(file) if file.links > 1 => {
                        return Err(bad(&format!(
                            "it has {} hard links: another name for it may be outside the \
                             folder (template files are read from this folder alone: copy \
                             it in)",
                            file.links
                        )));
                    }
                    Ok(file) => file,
                    Err(ReadError::TooLarge { bytes, .. }) => {
                        return Err(bad(&format!(
                            "it holds {bytes} bytes: a template file may hold {} MiB, a \
                             template folder {} MiB in all",
                            MAX_TEMPLATE_FILE_BYTES >> 20,
                            MAX_TEMPLATE_BYTES >> 20
                        )));
                    }
                    Err(e) => return Err(refused(dir, &relative, e)),
                };
                total += file.bytes.len() as u64;
                files.entry(target).or_default().push(TemplateFile {
                    bytes: file.bytes,
                    origin: path.display().to_string(),
                    path: inner.to_owned(),
                    ours: false,
                });
            }
        }
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::options::MeshMode;

    /// Plants a hostile entry at a path.
    type Plant<'a> = &'a dyn Fn(&Path);

    /// A plain file replaces our `.j2` of the same output path; the rest of
    /// ours stays.
    #[test]
    fn a_users_file_replaces_ours_of_the_same_output_path() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("gazebo")).unwrap();
        std::fs::write(dir.path().join("gazebo/rse.world"), "plain\n").unwrap();
        let templates = Templates::with_overrides(dir.path()).unwrap();
        let paths: Vec<&str> = templates.files[&Target::Gazebo]
            .iter()
            .map(|f| f.path.as_str())
            .collect();
        assert_eq!(
            paths,
            [
                "rse.world",
                "rse_terrain/model.config.j2",
                "rse_terrain/model.sdf.j2"
            ]
        );
        assert!(templates.is_custom());
        let missing = Templates::with_overrides(&dir.path().join("nowhere"));
        assert!(
            matches!(&missing, Err(Error::BadTemplateFolder { reason, .. }) if reason == "it does not exist"),
            "{:?}",
            missing.err()
        );
    }

    #[test]
    fn builtin_templates_match_the_folder() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../templates");
        let folder = OpenFolder::open(&root, true).unwrap();
        let on_disk: Vec<_> = read_tree(&folder)
            .unwrap()
            .into_iter()
            .flat_map(|(target, files)| files.into_iter().map(move |f| (target, f.path, f.bytes)))
            .collect();
        let built_in: Vec<_> = BUILTIN
            .iter()
            .map(|&(t, p, s)| (t, p.to_owned(), s.as_bytes().to_vec()))
            .collect();
        assert_eq!(
            on_disk, built_in,
            "list every file of templates/ in BUILTIN"
        );
    }

    /// Our templates render a world of many boxes on a fifth of the fuel a
    /// user's template gets a box (they take 24–48): the per-box fuel is
    /// no tight fit.
    #[test]
    fn our_templates_need_a_fifth_of_the_fuel() {
        let scheme =
            rse_core::Scheme::from_csv("# size: 40x40\ntype,height\nrandom,4\n", None).unwrap();
        let terrain = rse_core::generate(&scheme, 1, 0);
        let boxes = terrain.boxes();
        assert!(boxes.len() > 500, "{}", boxes.len());
        let context = WorldContext::new("w".to_owned(), &terrain, MeshMode::Blocks, &boxes);
        let templates = Templates::builtin();
        let fuel = 1000 + boxes.len() as u64 * FUEL_PER_BOX / 4;
        for target in Target::ALL {
            templates
                .render_with_fuel(target, &context, fuel, Fueled::All)
                .unwrap_or_else(|e| panic!("{target}: {e}"));
        }
        // ... and fail when starved: the fuel is counted.
        let starved =
            templates.render_with_fuel(Target::Webots, &context, boxes.len() as u64, Fueled::All);
        assert!(starved.is_err());
    }

    /// Three nested `range(100000)` loops rendered forever; a template
    /// that prints without bound filled memory. Both now fail, naming the
    /// file.
    #[test]
    fn endless_loops_and_endless_output_fail() {
        let scheme =
            rse_core::Scheme::from_csv("# size: 3x3\ntype,height\nrandom,2\n", None).unwrap();
        let terrain = rse_core::generate(&scheme, 1, 0);
        let boxes = terrain.boxes();
        let context = WorldContext::new("w".to_owned(), &terrain, MeshMode::Blocks, &boxes);
        for (name, source, said) in [
            (
                "loops.txt.j2",
                "{% for a in range(100000) %}{% for b in range(100000) %}{% for c in range(100000) %}.{% endfor %}{% endfor %}{% endfor %}",
                "fuel",
            ),
            (
                "big.txt.j2",
                "{% set x = 'x' * 9900000 %}{% for a in range(100) %}{{ x }}{% endfor %}",
                "renders more than",
            ),
        ] {
            let dir = tempfile::tempdir().unwrap();
            std::fs::create_dir(dir.path().join("urdf")).unwrap();
            std::fs::write(dir.path().join("urdf").join(name), source).unwrap();
            let templates = Templates::with_overrides(dir.path()).unwrap();
            let started = std::time::Instant::now();
            let err = templates.render(Target::Urdf, &context).unwrap_err();
            let text = err.to_string();
            assert!(text.contains(name) && text.contains(said), "{text}");
            // Not a speed test: only "it ends" (the loops were 10^15 steps).
            assert!(started.elapsed().as_secs() < 120);
        }
    }

    /// A template folder is read by descriptor: a link in it (to a secret,
    /// to `/dev/zero`), a hard link, a FIFO, or a target folder that is a
    /// link, is refused naming it, never followed, read or waited on.
    #[cfg(unix)]
    #[test]
    fn links_and_special_files_in_a_template_folder_are_refused() {
        let secret = tempfile::NamedTempFile::new().unwrap();
        std::fs::write(secret.path(), "secret").unwrap();
        let cases: [(&str, Plant); 5] = [
            ("urdf/key.txt", &|at| {
                std::os::unix::fs::symlink(secret.path(), at).unwrap();
            }),
            // Hostile worlds VI: a hard link to a file outside was copied
            // into every world.
            ("urdf/linked.txt", &|at| {
                std::fs::hard_link(secret.path(), at).unwrap();
            }),
            ("urdf/zero.bin", &|at| {
                std::os::unix::fs::symlink("/dev/zero", at).unwrap();
            }),
            ("urdf/pipe", &|at| {
                rustix::fs::mkfifoat(rustix::fs::CWD, at, rustix::fs::Mode::from_raw_mode(0o600))
                    .unwrap();
            }),
            ("gazebo", &|at| {
                std::os::unix::fs::symlink(secret.path().parent().unwrap(), at).unwrap();
            }),
        ];
        for (name, plant) in cases {
            let dir = tempfile::tempdir().unwrap();
            std::fs::create_dir(dir.path().join("urdf")).unwrap();
            std::fs::write(dir.path().join("urdf/ok.txt"), "ok").unwrap();
            plant(&dir.path().join(name));
            let err = Templates::with_overrides(dir.path()).unwrap_err();
            let text = err.to_string();
            assert!(
                matches!(err, Error::BadTemplateFolder { .. }) && text.contains(name),
                "{name}: {text}"
            );
        }
        // The folder named may itself be a link (a user's choice).
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("real/urdf")).unwrap();
        std::fs::write(dir.path().join("real/urdf/ok.txt"), "ok").unwrap();
        std::os::unix::fs::symlink(dir.path().join("real"), dir.path().join("link")).unwrap();
        assert!(Templates::with_overrides(&dir.path().join("link")).is_ok());
    }

    /// Export never writes through a link planted in the folder, and a
    /// failed export leaves nothing it made.
    #[cfg(unix)]
    #[test]
    fn export_refuses_links_and_leaves_nothing_when_it_fails() {
        let dir = tempfile::tempdir().unwrap();
        let elsewhere = tempfile::tempdir().unwrap();
        let out = dir.path().join("new/templates");
        std::fs::create_dir_all(&out).unwrap();
        // A link where a target folder goes: refused, not written through.
        std::os::unix::fs::symlink(elsewhere.path(), out.join("webots")).unwrap();
        let err = Templates::export_builtin(&out).unwrap_err();
        assert!(err.to_string().contains("webots"), "{err}");
        assert_eq!(std::fs::read_dir(elsewhere.path()).unwrap().count(), 0);
        // Everything written before it was removed: only the link is left.
        let left: Vec<_> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(left, ["webots"]);
        // A file where the folder goes.
        let file = dir.path().join("file");
        std::fs::write(&file, "x").unwrap();
        let err = Templates::export_builtin(&file.join("t")).unwrap_err();
        assert!(matches!(err, Error::NotAFolder { .. }), "{err}");
        // Fresh: every file, all of which read back as a template set.
        std::fs::remove_file(out.join("webots")).unwrap();
        let written = Templates::export_builtin(&out).unwrap();
        assert_eq!(written.len(), BUILTIN.len());
        Templates::with_overrides(&out).unwrap();
    }
}
