//! The static part of each target's world (paper §3.5): files copied into
//! every world as they are, and `.j2` files rendered with minijinja (the
//! suffix dropped) with the world's values.

use std::collections::BTreeMap;
use std::path::Path;

use minijinja::{AutoEscape, Environment, UndefinedBehavior};

use crate::context::WorldContext;
use crate::digest::sha256_hex;
use crate::error::Error;
use crate::manifest::TemplateSet;
use crate::options::Target;
use crate::tree::list_files;

/// Suffix of the files that are rendered rather than copied.
const TEMPLATE_SUFFIX: &str = ".j2";

/// Our templates, built into the binary so that an installed `rse-gen`
/// needs no data files. `builtin_templates_match_the_folder` keeps this list
/// equal to `templates/`.
const BUILTIN: &[(Target, &str, &str)] = &[
    (
        Target::Gazebo,
        "rse.world.j2",
        include_str!("../../../templates/gazebo/rse.world.j2"),
    ),
    (
        Target::Gazebo,
        "rse_terrain/model.config.j2",
        include_str!("../../../templates/gazebo/rse_terrain/model.config.j2"),
    ),
    (
        Target::Gazebo,
        "rse_terrain/model.sdf.j2",
        include_str!("../../../templates/gazebo/rse_terrain/model.sdf.j2"),
    ),
    (
        Target::Webots,
        "rse.wbt.j2",
        include_str!("../../../templates/webots/rse.wbt.j2"),
    ),
    (
        Target::Mujoco,
        "rse.xml.j2",
        include_str!("../../../templates/mujoco/rse.xml.j2"),
    ),
    (
        Target::Urdf,
        "rse.urdf.j2",
        include_str!("../../../templates/urdf/rse.urdf.j2"),
    ),
    (
        Target::Usd,
        "rse.usda.j2",
        include_str!("../../../templates/usd/rse.usda.j2"),
    ),
];

/// One file of a target's template folder.
#[derive(Debug, Clone)]
struct TemplateFile {
    /// Path inside the target's folder, `/`-separated.
    path: String,
    /// Contents, for a file that is copied.
    bytes: Vec<u8>,
    /// The name errors give: where the file came from.
    origin: String,
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
        if !dir.is_dir() {
            return Err(Error::BadTemplateFolder {
                path: dir.to_owned(),
                reason: if dir.exists() {
                    "it is not a folder".to_owned()
                } else {
                    "it does not exist".to_owned()
                },
            });
        }
        let mut files = Self::builtin().files;
        let mut any = false;
        for target in Target::ALL {
            let folder = dir.join(target.name());
            if !folder.is_dir() {
                continue;
            }
            any = true;
            let theirs = read_tree(&folder)?;
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
    /// (`rse-gen templates export`); refuses to overwrite a file.
    ///
    /// # Panics
    /// Never: every path it writes is `dir/<target>/<file>`, with a parent.
    pub fn export_builtin(dir: &Path) -> Result<Vec<std::path::PathBuf>, Error> {
        let paths: Vec<_> = BUILTIN
            .iter()
            .map(|&(target, path, _)| dir.join(target.name()).join(path))
            .collect();
        if let Some(existing) = paths.iter().find(|p| p.exists()) {
            return Err(Error::BadTemplateFolder {
                path: dir.to_owned(),
                reason: format!(
                    "{} exists already: export into an empty folder",
                    existing.display()
                ),
            });
        }
        for (path, &(_, _, source)) in paths.iter().zip(BUILTIN) {
            let parent = path.parent().expect("a target folder");
            std::fs::create_dir_all(parent).map_err(Error::io("create", parent))?;
            std::fs::write(path, source).map_err(Error::io("write", path))?;
        }
        Ok(paths)
    }

    fn new(files: BTreeMap<Target, Vec<TemplateFile>>, custom: bool) -> Result<Self, Error> {
        let mut env = Environment::new();
        env.set_undefined_behavior(UndefinedBehavior::Strict);
        // World files are XML, VRML and USD with values we compute: numbers
        // and plain names. Nothing needs escaping, and HTML escaping would
        // be wrong in the non-XML ones.
        env.set_auto_escape_callback(|_| AutoEscape::None);
        env.set_syntax(
            minijinja::syntax::SyntaxConfig::builder()
                .trim_blocks(true)
                .lstrip_blocks(true)
                .keep_trailing_newline(true)
                .build()
                .expect("default delimiters"),
        );
        let mut all = Vec::new();
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
        let Some(list) = self.files.get(&target) else {
            return Ok(Vec::new());
        };
        let value = minijinja::Value::from(minijinja::value::Serde(context));
        list.iter()
            .map(|file| {
                let Some(path) = file.path.strip_suffix(TEMPLATE_SUFFIX) else {
                    return Ok((file.path.clone(), file.bytes.clone()));
                };
                let template = self
                    .env
                    .get_template(&file.origin)
                    .map_err(|e| template_error(&file.origin, &file.bytes, &e))?;
                let text = template
                    .render(&value)
                    .map_err(|e| template_error(&file.origin, &file.bytes, &e))?;
                Ok((path.to_owned(), text.into_bytes()))
            })
            .collect()
    }
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

/// Every file under `dir`, with paths relative to the target folder.
fn read_tree(dir: &Path) -> Result<Vec<TemplateFile>, Error> {
    list_files(dir)
        .map_err(Error::io("read", dir))?
        .into_iter()
        .map(|relative| {
            let path = dir.join(&relative);
            Ok(TemplateFile {
                bytes: std::fs::read(&path).map_err(Error::io("read", &path))?,
                origin: path.display().to_string(),
                path: relative,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let mut on_disk = Vec::new();
        for target in Target::ALL {
            let folder = root.join(target.name());
            if folder.is_dir() {
                let found = read_tree(&folder).unwrap();
                on_disk.extend(found.into_iter().map(|f| (target, f.path, f.bytes)));
            }
        }
        let built_in: Vec<_> = BUILTIN
            .iter()
            .map(|&(t, p, s)| (t, p.to_owned(), s.as_bytes().to_vec()))
            .collect();
        assert_eq!(
            on_disk, built_in,
            "list every file of templates/ in BUILTIN"
        );
    }
}
