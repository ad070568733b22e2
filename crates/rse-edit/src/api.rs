//! The editor's JSON API, one function a route: request body in, JSON
//! answer out (no socket here: the command line serves these).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use base64::Engine as _;
use rse_core::{Field, GlobalKey, Globals, ObstacleKind, Usage, preview};
use rse_verify::{CheckOptions, check_paths};
use rse_world::{BatchConfig, MeshMode, Target, Targets, Templates, WorldConfig, write_batch};
use serde::Deserialize;
use serde_json::{Value, json};

use crate::drafts::{Drafts, Stored, unnamed_id};
use crate::model::{FieldError, PageScheme};
use crate::words;

/// The editor's state between requests.
#[derive(Default)]
pub struct Editor {
    /// The scheme file named on the command line, if any.
    pub path: Option<PathBuf>,
    /// The scheme it held when the editor started.
    pub initial: PageScheme,
    /// The file the page saved last and the scheme written there: what a
    /// reload starts from from then on (it started from `initial`, so the
    /// next Save wrote the old values back).
    pub saved: Mutex<Option<(PathBuf, PageScheme)>>,
    /// The batch being written (or last written).
    pub job: Arc<Job>,
    /// Where each file's draft and undo history are kept (None: nowhere,
    /// the page keeps them in the browser only).
    pub drafts: Option<Drafts>,
    /// Held while a draft is compared and written: two tabs' writes never
    /// interleave.
    pub drafts_written: Mutex<()>,
}

/// Progress of a Generate run.
#[derive(Default)]
pub struct Job {
    /// A batch is being written.
    pub running: Mutex<bool>,
    /// Worlds written so far.
    pub done: AtomicU64,
    /// Worlds to write.
    pub total: AtomicU64,
    /// The outcome line, or the error, once finished.
    pub result: Mutex<Option<Result<String, String>>>,
    /// The `check` summary of the written worlds.
    pub check: Mutex<Option<String>>,
    /// An output folder to offer when the one given holds other worlds.
    pub suggestion: Mutex<Option<String>>,
    /// Each written world's `check` (its name, whether it is good, its
    /// faults), at most [`WORLDS_LISTED`].
    pub worlds: Mutex<Vec<Value>>,
    /// The folder the last batch wrote into, whole (its worlds' previews
    /// are served from it, and Open folder opens it).
    pub folder: Mutex<Option<PathBuf>>,
}

/// The most worlds whose check results the page is sent one by one (the
/// summary line counts them all).
pub const WORLDS_LISTED: usize = 1000;

/// What a handler answers: `Ok` the result, `Err` a refusal for the page
/// (both are sent as JSON; the page reads `ok`).
pub type Answer = Result<Value, Value>;

fn error(e: &FieldError) -> Value {
    json!({ "ok": false, "error": e })
}

/// The request body as `T`, or the page's "bad request".
fn request<T: serde::de::DeserializeOwned>(body: &[u8]) -> Result<T, Value> {
    serde_json::from_slice(body).map_err(|e| bad(format!("bad request: {e}")))
}

fn bad(message: impl Into<String>) -> Value {
    json!({ "ok": false, "error": { "row": null, "field": null, "message": message.into() } })
}

/// `GET /api/state`: the scheme to start from: the one saved last, else
/// the file the editor started on.
///
/// # Panics
/// If the lock is poisoned (a panic while saving).
pub fn state(editor: &Editor) -> Value {
    let folder = std::env::current_dir()
        .map(|d| d.display().to_string())
        .unwrap_or_default();
    // The page was last on a scheme in no file yet (New, a sample, a file
    // from the browser's computer): that one, with its draft, whatever
    // reload, port or restart (once lost to the command line's file).
    let current = editor
        .drafts
        .as_ref()
        .and_then(|d| d.current(&start_document(editor)));
    if let Some(document) = current.filter(|d| unnamed_id(d).is_some()) {
        let (draft, revision) = draft_of(editor, &document);
        if let Some(scheme) = draft.get("scheme").filter(|s| s.is_object()) {
            return json!({
                "ok": true,
                "document": document,
                "scheme": scheme,
                "draft": draft,
                "revision": revision,
                "path": null,
                "folder": folder,
            });
        }
    }
    let saved = editor.saved.lock().unwrap();
    let (path, scheme) = match &*saved {
        Some((path, scheme)) => (Some(path), scheme),
        None => (editor.path.as_ref(), &editor.initial),
    };
    let shown = path.map(|p| p.display().to_string());
    let (draft, revision) = draft_of(editor, shown.as_deref().unwrap_or(""));
    json!({
        "ok": true,
        "document": shown.as_deref().unwrap_or(""),
        "scheme": scheme,
        "draft": draft,
        "revision": revision,
        "path": shown,
        // The command line's file is not there yet: Save writes it.
        "new_file": path.is_some_and(|p| !p.exists()),
        // Where relative paths (Open path, Save as, the output folder) start.
        "folder": folder,
    })
}

/// The document the editor started on: the command line's file ("": none).
fn start_document(editor: &Editor) -> String {
    editor
        .path
        .as_ref()
        .map_or_else(String::new, |p| p.display().to_string())
}

/// `document`'s draft as the server keeps it (null: none) and its
/// revision (0: none).
fn draft_of(editor: &Editor, document: &str) -> (Value, u64) {
    match &editor.drafts {
        Some(drafts) => {
            let (draft, revision) = drafts.load_revised(document);
            (draft.unwrap_or(Value::Null), revision)
        }
        None => (Value::Null, 0),
    }
}

#[derive(Deserialize)]
struct DraftRequest {
    /// The document the draft is of: a file as the server named it, or
    /// `unnamed:ID` for a scheme in no file yet.
    file: String,
    /// The page's draft (its scheme, the file's scheme it was made from,
    /// its undo history), kept as the page sent it; null forgets it.
    draft: Value,
    /// The tab writing it (a page load's own id).
    #[serde(default)]
    tab: String,
    /// The revision of this draft the tab read or wrote last (0: none).
    #[serde(default)]
    base: u64,
    /// Write over another tab's later draft (the user chose this one).
    #[serde(default)]
    force: bool,
    /// The page is on this document now: a reload starts from it.
    #[serde(default)]
    current: bool,
}

/// `POST /api/draft`: keeps (or with a null draft forgets) the page's
/// draft of a document, so a reload, another browser or the editor
/// restarted on another port finds it; never over another tab's draft
/// written since this tab read it (the answer is `conflict` with theirs).
///
/// # Panics
/// If the drafts' lock is poisoned (a panic while writing one).
pub fn draft(editor: &Editor, body: &[u8]) -> Answer {
    let request: DraftRequest = request(body)?;
    let Some(drafts) = &editor.drafts else {
        return Ok(json!({ "ok": true, "kept": false }));
    };
    if !request.file.is_empty()
        && request.file.starts_with("unnamed:")
        && unnamed_id(&request.file).is_none()
    {
        return Err(bad("bad request: not a document name"));
    }
    let failed = |e: rse_world::Error| {
        bad(format!(
            "the draft could not be kept: {}",
            words::world_failure(&e)
        ))
    };
    // One tab's read-compare-write at a time.
    let _one = editor.drafts_written.lock().expect("not poisoned");
    let mut answer = json!({ "ok": true, "kept": true });
    if request.draft.is_null() {
        drafts.forget(&request.file);
    } else if !request.draft.is_object() {
        return Err(bad("bad request: a draft is an object"));
    } else {
        let stored = drafts
            .store_revised(
                &request.file,
                &request.draft,
                &request.tab,
                request.base,
                request.force,
            )
            .map_err(failed)?;
        match stored {
            Stored::Kept { revision } => answer["revision"] = revision.into(),
            Stored::Conflict { theirs, revision } => {
                return Ok(json!({
                    "ok": false,
                    "conflict": true,
                    "theirs": theirs,
                    "revision": revision,
                }));
            }
        }
    }
    if request.current {
        drafts
            .set_current(&start_document(editor), &request.file)
            .map_err(failed)?;
    }
    Ok(answer)
}

/// `GET /api/schema`: what the page's fields and lists are made of — the
/// global keys with their defaults, the obstacle types with the columns
/// each needs or takes, the targets and those written by default — so the
/// script holds no copy of them.
///
pub fn schema() -> Value {
    let global = |key: GlobalKey| {
        json!({
            "key": key.name(),
            "default": Globals::default_text(key),
            "unit": key.unit(),
            "doc": key.described().replace('`', ""),
        })
    };
    let columns: Vec<Field> = Field::ALL
        .into_iter()
        .filter(|&f| f != Field::Type)
        .collect();
    let usage = |kind: ObstacleKind| {
        columns
            .iter()
            .map(|&f| {
                let usage = match kind.usage(f) {
                    Usage::Required => "required",
                    Usage::Optional => "optional",
                    Usage::Unused => "unused",
                };
                (f.name().to_owned(), Value::from(usage))
            })
            .collect::<serde_json::Map<_, _>>()
    };
    let column = |f: &Field| json!({ "name": f.name(), "unit": f.unit(), "doc": f.doc() });
    json!({
        "ok": true,
        "globals": GlobalKey::ALL.map(global),
        "columns": columns.iter().map(|f| f.name()).collect::<Vec<_>>(),
        "column_docs": Field::ALL.iter().map(column).collect::<Vec<_>>(),
        "mesh_modes": MeshMode::ALL.map(MeshMode::name),
        "default_mesh": MeshMode::default().name(),
        "types": ObstacleKind::ALL.map(|kind| json!({ "name": kind.name(), "columns": usage(kind) })),
        "targets": Target::ALL.map(|t| t.to_string()),
        "default_targets": Targets::default().iter().map(|t| t.to_string()).collect::<Vec<_>>(),
        "world_options": rse_world::WORLD_OPTIONS.iter().map(|o| json!({
            "name": o.name, "help": o.help, "default": o.default, "value_name": o.value_name,
        })).collect::<Vec<_>>(),
        "new_scheme": page_scheme_of(crate::NEW_SCHEME),
        "samples": crate::SAMPLES.map(|(name, csv)| {
            let scheme = page_scheme_of(csv);
            // The notes' first sentence, their lines joined.
            let notes = scheme.notes.split_whitespace().collect::<Vec<_>>().join(" ");
            let about = notes.find(". ").map_or(notes.as_str(), |end| &notes[..=end]).to_owned();
            json!({ "name": name, "about": about, "scheme": scheme })
        }),
    })
}

/// A built-in scheme's text as the page holds it (a test reads each).
fn page_scheme_of(csv: &str) -> PageScheme {
    PageScheme::from_scheme(
        &rse_core::Scheme::from_csv(csv, None).expect("a built-in scheme reads"),
    )
}

#[derive(Deserialize)]
struct PreviewRequest {
    scheme: PageScheme,
    /// The world's base seed as typed (a number or its text); absent, null
    /// or blank: the scheme's `# seed:`.
    #[serde(default)]
    seed: Value,
    /// The world's index as typed; absent, null or blank: 0.
    #[serde(default)]
    index: Value,
}

/// A refusal of one of the page's own controls (not a scheme field): the
/// page marks the control whose id is `control`.
fn control_error(control: &str, message: &str) -> Value {
    json!({ "ok": false, "error": { "row": null, "field": null, "control": control, "message": message } })
}

/// A whole number the page's control `control` (shown as `label`) holds, as
/// typed: `None` when blank, else a number `0..=u64::MAX` or a refusal in
/// the page's words (a parser's "expected u64", or the bound, tells a user
/// nothing).
fn whole_number(control: &str, label: &str, value: &Value) -> Result<Option<u64>, Value> {
    let text = match value {
        Value::Null => return Ok(None),
        Value::String(text) => text.trim().to_owned(),
        other => other.to_string(),
    };
    if text.is_empty() {
        return Ok(None);
    }
    text.parse::<u64>()
        .map(Some)
        .map_err(|_| control_error(control, &words::not_a_whole_number(label, &text)))
}

/// The largest grid the editor previews, in cells (500×500): its answer
/// carries every box of the world to draw, tens of megabytes beyond this
/// (a 5000×5000 grid gave 795 MB of JSON after 18 s).
pub const MAX_PREVIEW_CELLS: u64 = 250_000;

/// The most cell visits a preview's generation may cost
/// ([`Scheme::generation_visits`](rse_core::Scheme::generation_visits)):
/// well under a second. Many gentle peaks reaching a whole 500×500 grid
/// took 25 s.
pub const MAX_PREVIEW_VISITS: u64 = 50_000_000;

/// `POST /api/preview`: the world's heights, for the page to draw both its
/// views from (the top-down view with [`preview::palette`]'s colours, so it
/// matches `preview.png` pixel for pixel, and the 3D view on the same
/// scale): one byte a cell, two (little-endian) where a cell is above 255
/// steps, base64. A 200×200 world is 53 kB (its PNG and box list were
/// 858 kB).
pub fn preview(body: &[u8]) -> Answer {
    let start = Instant::now();
    let request: PreviewRequest = request(body)?;
    let seed = whole_number("seed", "world seed", &request.seed)?;
    let index = whole_number("index", "index", &request.index)?;
    let scheme = request.scheme.scheme().map_err(|e| error(&e))?;
    let grid = scheme.grid();
    let cells = u64::from(grid.nx) * u64::from(grid.ny);
    if cells > MAX_PREVIEW_CELLS {
        let field = if scheme.globals().pallets.is_some() {
            "pallets"
        } else {
            "size"
        };
        return Err(error(&FieldError {
            row: None,
            field: Some(field.to_owned()),
            message: format!(
                "a {}x{} grid ({cells} cells) is more than the editor draws ({MAX_PREVIEW_CELLS} cells, e.g. 500x500): make it smaller to see it here; Generate writes worlds of any size",
                grid.nx, grid.ny
            ),
        }));
    }
    let visits = scheme.generation_visits();
    if visits > MAX_PREVIEW_VISITS {
        return Err(error(&FieldError {
            row: None,
            field: None,
            message: format!(
                "its obstacles reach {visits} cells in all, more than the editor draws ({MAX_PREVIEW_VISITS}): fewer or steeper peaks and walls to see it here; Generate writes it as it is"
            ),
        }));
    }
    let terrain = rse_core::WorldRequest {
        seed,
        index,
        difficulty: None,
    }
    .generate(&scheme);
    let (lo, hi) = preview::height_span(&terrain);
    let map = terrain.heightmap();
    let wide = map.max() > u16::from(u8::MAX);
    let mut bytes = Vec::with_capacity(grid.cells() * if wide { 2 } else { 1 });
    for y in 0..grid.ny {
        for &h in map.row(y) {
            // Not wide: every height is at most 255, its low byte.
            let le = h.to_le_bytes();
            bytes.extend_from_slice(if wide { &le } else { &le[..1] });
        }
    }
    let mut response = json!({
        "ok": true,
        "nx": grid.nx,
        "ny": grid.ny,
        "heights": base64::engine::general_purpose::STANDARD.encode(bytes),
        "bytes_per_height": if wide { 2 } else { 1 },
        // The colour scale: the lowest and highest cell that is not frame.
        "lo": lo,
        "hi": hi,
        "frame_period": grid.frame_period,
        // Each ramp's cells, climb and rise, for the 3D view's wedges.
        "ramps": terrain.ramps(),
        "cell_pixels": preview::auto_cell_pixels(grid.nx, grid.ny),
        "server_ms": start.elapsed().as_secs_f64() * 1e3,
    });
    // The lengths the 3D view scales by, under their keys' names.
    let globals = json!(scheme.globals());
    for key in [GlobalKey::BlockSize, GlobalKey::StepHeight, GlobalKey::Base] {
        response[key.name()] = globals[key.name()].clone();
    }
    Ok(response)
}

#[derive(Deserialize)]
struct ParseRequest {
    csv: String,
}

/// `POST /api/parse`: a scheme file's text as the page's fields.
pub fn parse(body: &[u8]) -> Answer {
    let request: ParseRequest = request(body)?;
    let scheme =
        rse_core::Scheme::from_csv(&request.csv, None).map_err(|e| bad(words::file_fault(&e)))?;
    Ok(json!({ "ok": true, "scheme": PageScheme::from_scheme(&scheme) }))
}

#[derive(Deserialize)]
struct OpenRequest {
    path: PathBuf,
}

/// `POST /api/open`: reads the scheme file at `path` (a `.csv`), and makes
/// it the file Save writes and a reload starts from.
///
/// # Panics
/// If the lock is poisoned (a panic while saving).
pub fn open(editor: &Editor, body: &[u8]) -> Answer {
    let request: OpenRequest = request(body)?;
    let path = request.path;
    let shown = path.display();
    if path.extension().is_none_or(|e| e != "csv") {
        return Err(control_error(
            "path",
            &format!("{shown}: a scheme file ends in .csv"),
        ));
    }
    // A regular file only, its size counted as it is read: a FIFO held a
    // worker thread for good, a link to /dev/zero (size 0) ran the memory out.
    let bytes = rse_core::read_scheme_file(&path)
        .map_err(|e| control_error("path", &words::io_failure("open", &path, &e)))?;
    let scheme = rse_core::Scheme::from_csv_bytes(&bytes, Some(&shown.to_string()))
        .map_err(|e| control_error("path", &format!("{shown}, {}", words::file_fault(&e))))?;
    Ok(remember(editor, path, &scheme))
}

/// Makes `path`, holding `scheme`, the file a reload starts from (after an
/// open or a save), and the page's answer naming both.
///
/// # Panics
/// If the lock is poisoned (a panic while saving).
fn remember(editor: &Editor, path: PathBuf, scheme: &rse_core::Scheme) -> Value {
    let page = PageScheme::from_scheme(scheme);
    let shown = path.display().to_string();
    let (draft, revision) = draft_of(editor, &shown);
    let answer = json!({
        "ok": true,
        "draft": draft,
        "revision": revision,
        "path": shown,
        "scheme": page,
    });
    *editor.saved.lock().unwrap() = Some((path, page));
    answer
}

#[derive(Deserialize)]
struct CsvRequest {
    scheme: PageScheme,
}

/// `POST /api/csv`: the page's scheme as the canonical CSV Save writes, for
/// the page to offer as a download (nothing is written here).
pub fn csv(body: &[u8]) -> Answer {
    let request: CsvRequest = request(body)?;
    let scheme = request.scheme.scheme().map_err(|e| error(&e))?;
    Ok(json!({ "ok": true, "csv": scheme.to_csv() }))
}

#[derive(Deserialize)]
struct SaveRequest {
    scheme: PageScheme,
    path: PathBuf,
    /// Make the file's folder when it does not exist (the page asked the
    /// user first).
    #[serde(default)]
    make_folder: bool,
}

/// `POST /api/save`: writes the scheme as canonical CSV to the file the
/// user named (the only file the editor writes besides the batch), and
/// remembers it as what a reload starts from. A folder that does not exist
/// is made when asked (`make_folder`), else the refusal names it
/// (`missing_folder`) for the page to ask.
///
/// # Panics
/// If the lock is poisoned (a panic while saving).
pub fn save(editor: &Editor, body: &[u8]) -> Answer {
    let request: SaveRequest = request(body)?;
    let scheme = request.scheme.scheme().map_err(|e| error(&e))?;
    if request.path.extension().is_none_or(|e| e != "csv") {
        return Err(control_error("path", "a scheme file's name ends in .csv"));
    }
    if let Some(folder) = request.path.parent().filter(|f| !f.as_os_str().is_empty())
        && !folder.exists()
    {
        if !request.make_folder {
            let mut refusal = control_error(
                "path",
                &format!("the folder {} does not exist", folder.display()),
            );
            refusal["missing_folder"] = json!(folder.display().to_string());
            return Err(refusal);
        }
        std::fs::create_dir_all(folder)
            .map_err(|e| control_error("path", &words::io_failure("create", folder, &e)))?;
    }
    rse_world::write_atomically(&request.path, scheme.to_csv().as_bytes())
        .map_err(|e| control_error("path", &words::world_failure(&e)))?;
    Ok(remember(editor, request.path, &scheme))
}

#[derive(Deserialize)]
struct GenerateRequest {
    scheme: PageScheme,
    out: PathBuf,
    /// As typed; absent, null or blank: the scheme's `# amount:` and
    /// `# seed:`, as `rse-gen batch` takes them.
    #[serde(default)]
    amount: Value,
    #[serde(default)]
    seed: Value,
    /// `auto`, `single` or `blocks` (absent: auto).
    #[serde(default)]
    mesh: Option<String>,
    /// Target names; none given: the default targets.
    #[serde(default)]
    targets: Vec<String>,
    /// A folder of the user's own templates over the built-in ones (the
    /// paper's "custom base files"); absent or blank: the built-in ones.
    #[serde(default)]
    templates: Option<String>,
    /// The other world options (rse-world's table, `/api/schema`'s
    /// `world_options`) by name, as typed; blank: the default.
    #[serde(default)]
    options: BTreeMap<String, String>,
}

/// The control of world option `name` on the page: its own for targets
/// and mesh, else the field the page makes for it from the schema.
fn world_option_control(name: &str) -> String {
    match name {
        "targets" => "gen-targets".to_owned(),
        "mesh" => "mesh".to_owned(),
        other => format!("gen-opt-{other}"),
    }
}

/// The world options a generate request gives, each read by rse-world's
/// table (`WorldConfig::set`), a refusal at that option's control.
fn world_config(request: &GenerateRequest) -> Result<WorldConfig, Value> {
    let targets = (!request.targets.is_empty()).then(|| request.targets.join(","));
    let given = [
        ("targets", targets.as_deref()),
        ("mesh", request.mesh.as_deref()),
    ]
    .into_iter()
    .filter_map(|(name, text)| text.map(|text| (name, text)))
    .chain(
        request
            .options
            .iter()
            .map(|(name, text)| (name.as_str(), text.as_str())),
    );
    let mut world = WorldConfig::default();
    for (name, text) in given {
        if text.trim().is_empty() {
            continue;
        }
        world
            .set(name, text)
            .map_err(|e| control_error(&world_option_control(name), &e.to_string()))?;
    }
    Ok(world)
}

/// `POST /api/generate`: starts writing a batch in the background.
///
/// # Panics
/// If the job's lock is poisoned (a panic in the batch thread).
pub fn generate(editor: &Editor, body: &[u8]) -> Answer {
    let request: GenerateRequest = request(body)?;
    let amount = whole_number("gen-amount", "number of worlds", &request.amount)?;
    let seed = whole_number("seed", "world seed", &request.seed)?;
    let world = world_config(&request)?;
    if request.out.as_os_str().is_empty() {
        return Err(control_error(
            "gen-out",
            "name the folder the worlds go into",
        ));
    }
    let scheme = request.scheme.scheme().map_err(|e| error(&e))?;
    let templates = match request.templates.as_deref().map(str::trim) {
        None | Some("") => Templates::builtin(),
        Some(folder) => Templates::with_overrides(Path::new(folder))
            .map_err(|e| control_error("gen-templates", &words::world_failure(&e)))?,
    };
    let job = Arc::clone(&editor.job);
    {
        let mut running = job.running.lock().expect("not poisoned");
        if *running {
            return Err(bad("a batch is already being written"));
        }
        *running = true;
    }
    let options = BatchConfig {
        amount,
        seed,
        world,
        ..BatchConfig::default()
    }
    .resolve(&scheme, request.out);
    let options = match options {
        Ok(options) => options,
        Err(e) => {
            *job.running.lock().expect("not poisoned") = false;
            return Err(match &e {
                rse_world::Error::BadOption { option, .. }
                    if rse_world::WORLD_OPTIONS.iter().any(|o| o.name == *option) =>
                {
                    control_error(&world_option_control(option), &words::world_failure(&e))
                }
                _ => bad(words::world_failure(&e)),
            });
        }
    };
    if let Err(refusal) = fits_on_disk(&scheme, &templates, &options) {
        *job.running.lock().expect("not poisoned") = false;
        return Err(refusal);
    }
    job.done.store(0, Ordering::SeqCst);
    job.total.store(options.amount, Ordering::SeqCst);
    *job.result.lock().expect("not poisoned") = None;
    *job.check.lock().expect("not poisoned") = None;
    *job.suggestion.lock().expect("not poisoned") = None;
    job.worlds.lock().expect("not poisoned").clear();
    let total = options.amount;
    // Said and served whole: a relative path means little on the page.
    let whole = std::path::absolute(&options.out).unwrap_or_else(|_| options.out.clone());
    *job.folder.lock().expect("not poisoned") = Some(whole.clone());
    std::thread::spawn(move || {
        let templates = Arc::new(templates);
        let outcome = write_batch(&scheme, &templates, &options, &|_| {
            job.done.fetch_add(1, Ordering::SeqCst);
        });
        if let Err(rse_world::Error::Conflict { .. }) = &outcome {
            *job.suggestion.lock().expect("not poisoned") =
                words::free_folder_beside(&options.out).map(|p| p.display().to_string());
        }
        let result = outcome.map_err(|e| words::world_failure(&e)).map(|s| {
            format!(
                "{} worlds written, {} already there, into {}",
                s.written,
                s.skipped,
                whole.display()
            )
        });
        if result.is_ok() {
            let (check, worlds) = check_summary(&options.out, templates);
            *job.check.lock().expect("not poisoned") = Some(check);
            *job.worlds.lock().expect("not poisoned") = worlds;
        }
        *job.result.lock().expect("not poisoned") = Some(result);
        *job.running.lock().expect("not poisoned") = false;
    });
    Ok(json!({ "ok": true, "total": total }))
}

/// Refuses a batch that could not fit on the disk it goes to, priced from
/// its first worlds built in memory (2⁶⁴ − 1 worlds asked from the page
/// once wrote until the disk was full). Worlds already there are counted
/// too: a batch resumed on a full disk is refused a little early.
fn fits_on_disk(
    scheme: &rse_core::Scheme,
    templates: &Templates,
    options: &rse_world::BatchOptions,
) -> Result<(), Value> {
    let need = rse_world::batch_disk_bytes(scheme, templates, options)
        .map_err(|e| bad(words::world_failure(&e)))?;
    let Some(free) = rse_world::free_disk_bytes(&options.out) else {
        return Ok(());
    };
    if need <= free {
        return Ok(());
    }
    let worlds = options.shard.worlds(options.amount).max(1);
    let each = need / worlds;
    let mib = |bytes: u64| (bytes >> 20).max(1);
    Err(control_error(
        "gen-amount",
        &format!(
            "{worlds} worlds of some {} MiB each need some {} MiB, but {} MiB are free where \
             they go: ask for at most {} worlds, or free some space",
            mib(each),
            mib(need),
            free >> 20,
            free / each.max(1)
        ),
    ))
}

/// `GET /api/job`: the batch's progress and, once done, its summaries.
///
/// # Panics
/// If the job's lock is poisoned (a panic in the batch thread).
pub fn job(editor: &Editor) -> Value {
    let job = &editor.job;
    let result = job.result.lock().expect("not poisoned").clone();
    json!({
        "ok": true,
        "running": *job.running.lock().expect("not poisoned"),
        "done": job.done.load(Ordering::SeqCst),
        "total": job.total.load(Ordering::SeqCst),
        "summary": result.as_ref().and_then(|r| r.as_ref().ok()),
        "error": result.as_ref().and_then(|r| r.as_ref().err()),
        "check": *job.check.lock().expect("not poisoned"),
        "suggestion": *job.suggestion.lock().expect("not poisoned"),
        "worlds": *job.worlds.lock().expect("not poisoned"),
        "folder": job.folder.lock().expect("not poisoned").as_ref().map(|f| f.display().to_string()),
    })
}

/// The most worlds whose previews the page shows after a Generate.
pub const PREVIEWS_SHOWN: usize = 24;

/// `GET /api/world-preview/NAME`: `preview.png` of the world `NAME` of the
/// last batch (one the page lists), read from its folder as `check` reads
/// a world (no link followed); None when there is none.
///
/// # Panics
/// If the job's lock is poisoned (a panic in the batch thread).
pub fn world_preview(editor: &Editor, name: &str) -> Option<Vec<u8>> {
    let listed = editor
        .job
        .worlds
        .lock()
        .expect("not poisoned")
        .iter()
        .take(PREVIEWS_SHOWN)
        .any(|w| w["world"] == name);
    if !listed || rse_world::world_name_problem(name).is_some() {
        return None;
    }
    let folder = editor.job.folder.lock().expect("not poisoned").clone()?;
    let opened = rse_world::OpenFolder::open(&folder, true).ok()?;
    // A preview is a few MB at most (`rse-gen preview` caps its pixels).
    let file = opened
        .read(&format!("{name}/preview.png"), 256 << 20)
        .ok()?;
    Some(file.bytes)
}

/// `POST /api/open-folder`: opens the last batch's folder in the desktop's
/// file manager (`xdg-open`, `open` on macOS), or says why not and where
/// the worlds are.
///
/// # Panics
/// If the job's lock is poisoned (a panic in the batch thread).
pub fn open_folder(editor: &Editor) -> Answer {
    let Some(folder) = editor.job.folder.lock().expect("not poisoned").clone() else {
        return Err(bad("no worlds written yet: Generate first"));
    };
    match crate::desktop::open(folder.as_os_str()) {
        Ok(()) => Ok(json!({ "ok": true, "folder": folder })),
        Err(why) => Err(bad(format!(
            "this machine has no file manager to open it with ({why}): the worlds are in {}",
            folder.display()
        ))),
    }
}

/// The `check` of the worlds in `folder` (no physics; with the templates
/// they were written with, so custom files are compared byte for byte) as
/// the page shows it after a Generate: the verdict and the first fault,
/// and each world's name, verdict and faults.
fn check_summary(folder: &Path, templates: Arc<Templates>) -> (String, Vec<Value>) {
    let options = CheckOptions {
        templates: Some(templates),
        ..CheckOptions::default()
    };
    let report = match check_paths(&[folder.to_path_buf()], &options, &|| {}) {
        Ok(report) => report,
        Err(e) => return (format!("check: {e}"), Vec::new()),
    };
    let worlds = report
        .worlds
        .iter()
        .take(WORLDS_LISTED)
        .enumerate()
        .map(|(i, w)| {
            let name = Path::new(&w.world)
                .file_name()
                .map_or_else(|| w.world.clone(), |n| n.to_string_lossy().into_owned());
            let faults: Vec<String> = w.faults.iter().map(ToString::to_string).collect();
            // Its height range and step: the preview's colours run over
            // them, the page draws the legend beside it.
            let step = w.manifest.as_ref().map(|m| m.globals.step_height);
            let range = w
                .manifest
                .as_ref()
                .filter(|_| i < PREVIEWS_SHOWN)
                .and_then(|m| heights_of(&Path::new(&w.world).join("heightmap.csv"), &m.grid));
            let path = std::path::absolute(&w.world).unwrap_or_else(|_| PathBuf::from(&w.world));
            json!({
                "world": name, "ok": w.ok, "faults": faults,
                "path": path, "heights": range, "step_height": step,
            })
        })
        .collect();
    let line = match report.first_fault() {
        Some(first) => format!("{} (first: {first})", report.verdict()),
        None => report.verdict(),
    };
    (line, worlds)
}

/// The lowest and highest cell of a world's `heightmap.csv` on `grid`, in
/// steps, as its preview's colours run (None: not read, or all frame).
fn heights_of(csv: &Path, grid: &rse_core::Grid) -> Option<[u16; 2]> {
    let text = std::fs::read_to_string(csv).ok()?;
    let map = rse_core::Heightmap::from_csv(&text).ok()?;
    let (lo, hi) = rse_core::preview::heights_span(&map, grid);
    (lo <= hi).then_some([lo, hi])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_schema_lists_what_core_and_world_accept() {
        let schema = schema();
        let names = |key: &str, field: Option<&str>| -> Vec<String> {
            schema[key]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| field.map_or(v, |f| &v[f]).as_str().unwrap().to_owned())
                .collect()
        };
        assert_eq!(names("globals", Some("key")), rse_core::GLOBAL_KEYS);
        for t in names("types", Some("name")) {
            assert!(t.parse::<ObstacleKind>().is_ok(), "{t}");
        }
        assert_eq!(names("types", Some("name")).len(), ObstacleKind::ALL.len());
        assert_eq!(
            Targets::parse(&names("default_targets", None).join(",")).unwrap(),
            Targets::default()
        );
        // Each default reads back through core's own parser.
        let mut patch = rse_core::GlobalsPatch::default();
        for g in schema["globals"].as_array().unwrap() {
            let key = g["key"].as_str().unwrap();
            if !key.starts_with("pallet_") {
                patch.set(key, g["default"].as_str().unwrap()).unwrap();
            }
        }
        assert_eq!(
            patch.apply(&Globals::default()).unwrap(),
            Globals::default()
        );
    }

    /// docs/schemes.md's table of global keys is written from rse-core's
    /// table (`RSE_UPDATE_DOCS=1` rewrites it; the editor's tooltips are
    /// the same words), and each column's tooltip is its table row's text
    /// there, backticks removed.
    #[test]
    fn the_tooltips_are_the_scheme_docs_text() {
        use std::fmt::Write as _;

        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/schemes.md");
        let mut docs = std::fs::read_to_string(path).unwrap();
        let header = "| key | value | default |\n|---|---|---|\n";
        let start = docs
            .find(header)
            .expect("docs/schemes.md has its table of keys")
            + header.len();
        let end = start + docs[start..].find("\n\n").unwrap() + 1;
        let mut rows = String::new();
        for key in GlobalKey::ALL {
            let (name, doc, default) = (key.name(), key.described(), Globals::default_text(key));
            writeln!(rows, "| `{name}` | {doc} | `{default}` |").unwrap();
        }
        if docs[start..end] != rows {
            if std::env::var_os("RSE_UPDATE_DOCS").is_some() {
                // Rewritten, and the rest of the test reads what it wrote
                // (it once failed its first run on the old text).
                docs = format!("{}{rows}{}", &docs[..start], &docs[end..]);
                std::fs::write(path, &docs).unwrap();
            } else {
                panic!(
                    "docs/schemes.md's table of global keys is not rse-core's: rerun with RSE_UPDATE_DOCS=1\n{rows}"
                );
            }
        }
        let row = |name: &str| -> Vec<String> {
            let start = format!("| `{name}` |");
            let line = docs
                .lines()
                .find(|l| l.starts_with(&start))
                .unwrap_or_else(|| panic!("docs/schemes.md has no table row for `{name}`"));
            line.trim_matches('|')
                .split(" | ")
                .map(|cell| cell.trim().replace('`', ""))
                .collect()
        };
        let schema = schema();
        for g in schema["globals"].as_array().unwrap() {
            let cells = row(g["key"].as_str().unwrap());
            assert_eq!(cells[1], g["doc"].as_str().unwrap(), "{}", g["key"]);
        }
        for c in schema["column_docs"].as_array().unwrap() {
            let cells = row(c["name"].as_str().unwrap());
            assert_eq!(cells[2], c["doc"].as_str().unwrap(), "{}", c["name"]);
            assert_eq!(cells[1], c["unit"].as_str().unwrap_or("–"), "{}", c["name"]);
        }
    }

    #[test]
    fn a_page_control_typed_wrong_is_refused_in_words_on_that_control() {
        let scheme = seeded_page_scheme();
        for (seed, index, control, words) in [
            (
                json!("abc"),
                json!(0),
                "seed",
                "the world seed must be a whole number of 0 or more",
            ),
            (
                json!(null),
                json!(-1),
                "index",
                "the index must be a whole number of 0 or more",
            ),
            (json!(""), json!("1.5"), "index", "not `1.5`"),
        ] {
            let body = json!({ "scheme": scheme, "seed": seed, "index": index });
            let refusal = preview(body.to_string().as_bytes()).unwrap_err();
            assert_eq!(refusal["error"]["control"], control, "{refusal}");
            let message = refusal["error"]["message"].as_str().unwrap();
            assert!(message.contains(words), "{message}");
            assert!(!message.contains("expected u64"), "{message}");
        }
        let body = json!({ "scheme": scheme, "seed": " 9 ", "index": "" });
        assert!(
            preview(body.to_string().as_bytes()).is_ok(),
            "blank and spaced numbers are fine"
        );

        let editor = Editor::default();
        let body = json!({ "scheme": scheme, "out": "w", "amount": "abc" });
        let refusal = generate(&editor, body.to_string().as_bytes()).unwrap_err();
        assert_eq!(refusal["error"]["control"], "gen-amount", "{refusal}");
        assert!(!*editor.job.running.lock().unwrap(), "nothing started");
    }

    #[test]
    fn open_reads_a_scheme_and_makes_it_the_file_a_reload_starts_from() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("other.csv");
        std::fs::write(&path, "# size: 7x6\ntype,height\nrandom,2\n").unwrap();
        let editor = Editor::default();
        let answer = open(&editor, json!({ "path": path }).to_string().as_bytes()).unwrap();
        assert_eq!(answer["scheme"]["globals"]["size"], "7x6");
        let now = state(&editor);
        assert_eq!(now["path"], path.display().to_string());
        assert_eq!(now["scheme"], answer["scheme"]);

        let missing = dir.path().join("missing.csv");
        let refusal = open(&editor, json!({ "path": missing }).to_string().as_bytes()).unwrap_err();
        assert!(
            refusal["error"]["message"]
                .as_str()
                .unwrap()
                .starts_with("cannot open "),
            "{refusal}"
        );
        std::fs::write(dir.path().join("bad.csv"), "type,height\nrandom,x\n").unwrap();
        let bad = dir.path().join("bad.csv");
        let refusal = open(&editor, json!({ "path": bad }).to_string().as_bytes()).unwrap_err();
        let message = refusal["error"]["message"].as_str().unwrap();
        assert!(message.contains("bad.csv, line 2: height"), "{message}");
        let refusal = open(
            &editor,
            json!({ "path": "/etc/passwd" }).to_string().as_bytes(),
        )
        .unwrap_err();
        assert!(
            refusal["error"]["message"]
                .as_str()
                .unwrap()
                .contains(".csv"),
            "{refusal}"
        );
        assert_eq!(
            state(&editor)["path"],
            path.display().to_string(),
            "a refusal changes nothing"
        );
    }

    /// Fifth hardening round: a FIFO named `x.csv` blocked a worker thread
    /// for good (four opens and the page stopped answering), and a link to
    /// `/dev/zero` (size 0) passed the size cap and was read until memory
    /// ran out. Open reads regular files only, its cap counted as it reads.
    #[cfg(target_os = "linux")]
    #[test]
    fn open_refuses_a_fifo_and_a_device_at_once() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo.csv");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.unwrap().success(), "mkfifo");
        let zero = dir.path().join("zero.csv");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        let big = dir.path().join("big.csv");
        std::fs::write(&big, vec![b'#'; (rse_core::MAX_SCHEME_BYTES + 1) as usize]).unwrap();
        let editor = Editor::default();
        for (path, said) in [
            (&fifo, "not a regular file"),
            (&zero, "not a regular file"),
            (&big, "larger than any scheme"),
        ] {
            let refusal =
                open(&editor, json!({ "path": path }).to_string().as_bytes()).unwrap_err();
            let message = refusal["error"]["message"].as_str().unwrap();
            assert!(message.contains(said), "{}: {message}", path.display());
        }
        assert_eq!(state(&editor)["path"], Value::Null, "nothing opened");
    }

    /// The preview's cap prices what generation builds: 17,000 gaussian rows
    /// (1 MB of request) each built a table of 65,535 erfcs and ran for
    /// minutes. Rows alike now share one table (previewed at once); rows
    /// each of its own height are priced each, and refused unbuilt.
    #[test]
    fn gaussian_tables_count_against_the_preview_cap() {
        let row = |height: u32| json!({ "type": "gaussian", "height": [height.to_string(), ""], "sigma": ["10000", ""] });
        let scheme = |rows: Vec<Value>| {
            json!({
                "scheme": { "globals": { "size": "2x2", "step_height": "0.001" }, "obstacles": rows },
            })
        };
        let distinct = (0..17_000).map(|i| row(65_535 - i)).collect();
        let refused = preview(scheme(distinct).to_string().as_bytes()).unwrap_err();
        let message = refused["error"]["message"].as_str().unwrap();
        assert!(message.contains("more than the editor draws"), "{message}");
        let alike = vec![row(65_535); 17_000];
        assert!(preview(scheme(alike).to_string().as_bytes()).is_ok());
    }

    /// Hostile worlds VI: 2⁶⁴ − 1 worlds asked from the page wrote until
    /// the disk was full. A batch is priced from its first worlds and
    /// refused, at the amount's control, when it could not fit in the
    /// space free where it goes; nothing is written or left running.
    #[test]
    fn a_batch_larger_than_the_disk_is_refused_before_a_world_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("w");
        let editor = Editor::default();
        let body = json!({
            "scheme": seeded_page_scheme(),
            "out": out,
            "amount": u64::MAX.to_string(),
            "targets": ["obj"],
        });
        let refusal = generate(&editor, body.to_string().as_bytes()).unwrap_err();
        assert_eq!(refusal["error"]["control"], "gen-amount", "{refusal}");
        let message = refusal["error"]["message"].as_str().unwrap();
        assert!(
            message.contains("MiB are free") && message.contains("ask for at most"),
            "{message}"
        );
        assert!(!*editor.job.running.lock().unwrap(), "nothing started");
        assert!(!out.exists(), "nothing written");
    }

    /// A page scheme with `# seed: 9` and `# amount: 2` of `random,3`.
    fn seeded_page_scheme() -> Value {
        json!({
            "globals": { "size": "6x5", "seed": "9", "amount": "2" },
            "obstacles": [ { "type": "random", "height": ["3", ""] } ],
        })
    }

    #[test]
    fn the_scheme_seed_and_amount_rule_when_the_page_gives_none() {
        let preview_of = |seed: Value| {
            let body = json!({ "scheme": seeded_page_scheme(), "seed": seed, "index": null });
            let answer = preview(body.to_string().as_bytes()).unwrap();
            answer["heights"].clone()
        };
        assert_eq!(
            preview_of(Value::Null),
            preview_of(json!(9)),
            "null is the scheme's seed"
        );
        assert_ne!(preview_of(Value::Null), preview_of(json!(0)), "not seed 0");

        let dir = tempfile::tempdir().unwrap();
        let editor = Editor::default();
        let body = json!({ "scheme": seeded_page_scheme(), "out": dir.path().join("w"), "targets": ["obj"] });
        let started = generate(&editor, body.to_string().as_bytes()).unwrap();
        assert_eq!(started["total"], 2, "the scheme's amount");
        while *editor.job.running.lock().unwrap() {
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let manifest: Value = serde_json::from_slice(
            &std::fs::read(dir.path().join("w/world_0001/rse.json")).unwrap(),
        )
        .unwrap();
        assert_eq!(manifest["seed"], 9, "the scheme's seed");
        assert!(!dir.path().join("w/world_0002").exists());
    }

    /// A generate request with world option `name` given as `text`: the
    /// targets and mesh in their own controls, the rest by name.
    fn with_world_option(out: &Path, name: &str, text: &str) -> Value {
        let mut body = json!({ "scheme": seeded_page_scheme(), "out": out, "amount": "1", "targets": ["obj", "mujoco"] });
        match name {
            "targets" => body["targets"] = json!([text]),
            "mesh" => body["mesh"] = json!(text),
            other => body["options"] = json!({ other: text }),
        }
        body
    }

    /// Every world option of rse-world's table reaches the page's batch:
    /// its example is written into `rse.json`, and a value outside what it
    /// takes is refused at its control, naming it, before a world is
    /// written. (The collider's oversample needs the height field.)
    #[test]
    fn every_world_option_is_taken_from_the_page_and_checked() {
        for option in rse_world::WORLD_OPTIONS {
            let dir = tempfile::tempdir().unwrap();
            let out = dir.path().join("w");
            let editor = Editor::default();
            let body = with_world_option(&out, option.name, option.outside);
            let refusal = generate(&editor, body.to_string().as_bytes()).unwrap_err();
            assert_eq!(
                refusal["error"]["control"],
                world_option_control(option.name),
                "{refusal}"
            );
            let message = refusal["error"]["message"].as_str().unwrap();
            assert!(message.contains(option.name), "{message}");
            assert!(!out.exists(), "nothing written");

            let mut body = with_world_option(&out, option.name, option.example);
            if option.name == "oversample" {
                body["options"]["mujoco_collider"] = json!("hfield");
            }
            generate(&editor, body.to_string().as_bytes()).unwrap();
            while *editor.job.running.lock().unwrap() {
                std::thread::sleep(std::time::Duration::from_millis(20));
            }
            let manifest: Value =
                serde_json::from_slice(&std::fs::read(out.join("world_0000/rse.json")).unwrap())
                    .unwrap();
            // What rse-world's own config makes of the same options.
            let mut config = WorldConfig::default();
            config.set("targets", "obj,mujoco").unwrap();
            if option.name == "oversample" {
                config.set("mujoco_collider", "hfield").unwrap();
            }
            config.set(option.name, option.example).unwrap();
            let expected = serde_json::to_value(config.resolve().unwrap()).unwrap();
            for (key, value) in expected.as_object().unwrap() {
                assert_eq!(&manifest[key], value, "{}: {key}", option.name);
            }
        }
    }
}
