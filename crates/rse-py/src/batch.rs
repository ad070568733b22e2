//! Many terrains at once: `generate_batch` in parallel without the GIL, and
//! `write_worlds`, the Python face of `rse-gen batch`.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use rse_world::{BatchConfig, Outcome, Shard, Templates};

use crate::errors::world_error;
use crate::keywords::{self, KeywordGroup as _, keyword_group};
use crate::options::{WorldKeywords, world_keywords_text};
use crate::scheme::{PyDifficulty, Scheme};
use crate::terrain::Terrain;

/// A rayon pool of `jobs` threads (`None`: one per core).
pub fn pool(py: Python<'_>, jobs: Option<usize>) -> PyResult<rayon::ThreadPool> {
    rse_world::thread_pool(jobs).map_err(|e| world_error(py, &e))
}

/// Worlds `0..amount` of seed `seed` (default: the scheme's `# seed:`,
/// else 0, as on the command line), generated in parallel on `jobs`
/// threads with the GIL released; the same terrains whatever `jobs` is.
#[pyfunction]
#[pyo3(signature = (scheme, amount, seed=None, jobs=None, difficulty=None))]
pub fn generate_batch(
    py: Python<'_>,
    scheme: &Scheme,
    amount: u64,
    seed: Option<u64>,
    jobs: Option<usize>,
    difficulty: Option<PyDifficulty>,
) -> PyResult<Vec<Terrain>> {
    let pool = pool(py, jobs)?;
    let scheme = &scheme.inner;
    crate::memory::fits(
        "amount",
        amount.saturating_mul(crate::memory::terrain_bytes(scheme)),
        format_args!("{amount} terrains"),
    )?;
    let rse_core::WorldAt {
        seed, difficulty, ..
    } = rse_core::WorldRequest {
        seed,
        index: None,
        difficulty: difficulty.map(|d| d.0),
    }
    .resolve(scheme);
    Ok(py.detach(|| {
        pool.install(|| {
            (0..amount)
                .into_par_iter()
                .map(|index| Terrain::generate(scheme, seed, index, difficulty))
                .collect()
        })
    }))
}

keyword_group! {
    /// What `write_worlds` takes beyond the world options: the batch.
    pub struct BatchKeywords {
        /// `amount=`: worlds (default: the scheme's `# amount:`).
        amount: u64,
        /// `seed=`: the batch's seed (default: the scheme's `# seed:`).
        seed: u64,
        /// `jobs=`: worker threads (default: one a core).
        jobs: usize,
        /// `shard=`: `K/N`, this run's share of the batch.
        shard: String,
        /// `difficulty=`: 0 to 1 (default 1).
        difficulty: PyDifficulty,
    }
}

// The signature heads the docstring, as CPython's builtins write theirs
// (pyo3's `text_signature` takes a literal only): the world keywords are
// rse-world's table's.
#[doc = concat!(
    "write_worlds(scheme, out, *, amount=None, seed=None, jobs=None, shard=None, difficulty=None, ",
    rse_world::for_each_world_option!(world_keywords_text),
    ")\n--\n"
)]
/// Writes simulator worlds as `rse-gen batch` does (same folders, same
/// bytes); returns counts: `written`, `skipped`, `replaced`, `bytes`.
/// Keywords: the batch's (`amount`, `seed`, `jobs`, `shard`,
/// `difficulty`) and the world options every writer takes.
#[pyfunction]
#[pyo3(signature = (scheme, out, **options), text_signature = None)]
// The signature heading the docstring is Python's, not markdown.
#[allow(clippy::doc_markdown)]
pub fn write_worlds<'py>(
    py: Python<'py>,
    scheme: &Scheme,
    out: std::path::PathBuf,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let given = keywords::given(py, options)?;
    let batch = BatchKeywords::take(&given)?;
    let world = WorldKeywords::take(&given)?;
    keywords::none_left(
        "write_worlds",
        &given,
        &[BatchKeywords::NAMES, WorldKeywords::NAMES],
    )?;
    let options = BatchConfig {
        amount: batch.amount,
        seed: batch.seed,
        world: world.config(py, batch.difficulty.map(|d| d.0))?,
        jobs: batch.jobs,
        shard: batch
            .shard
            .as_deref()
            .map(str::parse::<Shard>)
            .transpose()
            .map_err(|e| world_error(py, &e))?,
        force: Some(world.force.unwrap_or(false)),
    }
    .resolve(&scheme.inner, out)
    .map_err(|e| world_error(py, &e))?;
    let templates = templates(py, world.template.as_deref())?;
    let scheme = &scheme.inner;
    let summary = py
        .detach(|| rse_world::write_batch(scheme, &templates, &options, &|_| {}))
        .map_err(|e| world_error(py, &e))?;
    let dict = PyDict::new(py);
    dict.set_item("written", summary.written)?;
    dict.set_item("skipped", summary.skipped)?;
    dict.set_item("replaced", summary.replaced)?;
    dict.set_item("bytes", summary.bytes)?;
    Ok(dict)
}

#[doc = concat!("write_world(terrain, out, *, ", rse_world::for_each_world_option!(world_keywords_text), ")\n--\n")]
/// Writes `terrain` as the world folder `out` (named after it), as
/// `rse-gen batch` writes each world: the same files, an `rse.json` that
/// `rse.check` and `rse-gen check` verify, whole or not at all. An identical
/// folder is left alone (`"skipped"`), a different one refused unless
/// `force=True`. Returns `"written"`, `"skipped"` or `"replaced"`.
/// Keywords: the world options every writer takes.
#[pyfunction]
#[pyo3(signature = (terrain, out, **options), text_signature = None)]
// The signature heading the docstring is Python's, not markdown.
#[allow(clippy::doc_markdown)]
pub fn write_world(
    py: Python<'_>,
    terrain: &Terrain,
    out: std::path::PathBuf,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<&'static str> {
    let world = keywords::read::<WorldKeywords>(py, "write_world", options)?;
    let Some(scheme) = &terrain.scheme else {
        return Err(PyValueError::new_err(
            "this terrain is an atlas's map: write it with Atlas.write",
        ));
    };
    let t = &terrain.inner;
    let options = world.options(py, t.difficulty())?;
    let templates = templates(py, world.template.as_deref())?;
    let force = world.force.unwrap_or(false);
    let outcome = py
        .detach(|| {
            rse_world::write_world_at(
                scheme,
                t.seed(),
                t.index(),
                &out,
                &options,
                &templates,
                force,
            )
        })
        .map_err(|e| world_error(py, &e))?;
    Ok(outcome_name(outcome))
}

/// Our templates, overlaid by the folder `template` when given.
pub fn templates(py: Python<'_>, template: Option<&std::path::Path>) -> PyResult<Templates> {
    match template {
        Some(dir) => Templates::with_overrides(dir).map_err(|e| world_error(py, &e)),
        None => Ok(Templates::builtin()),
    }
}

/// What a writer returns for one world folder.
pub fn outcome_name(outcome: Outcome) -> &'static str {
    match outcome {
        Outcome::Written(_) => "written",
        Outcome::Skipped => "skipped",
        Outcome::Replaced(_) => "replaced",
    }
}

/// Seconds `scheme.generate(seed, i)` takes for `i` in `0..count`, timed
/// inside Rust: the benchmark's yardstick for the cost of the Python call.
#[pyfunction]
#[pyo3(signature = (scheme, count, seed=0))]
pub fn _time_generate(py: Python<'_>, scheme: &Scheme, count: u64, seed: u64) -> f64 {
    let scheme = &scheme.inner;
    py.detach(|| {
        let start = std::time::Instant::now();
        for index in 0..count {
            std::hint::black_box(rse_core::generate(scheme, seed, index));
        }
        start.elapsed().as_secs_f64()
    })
}
