//! One world folder at a path the user names (an atlas, a terrain written
//! from Python), placed as a batch places its worlds: built in a hidden
//! folder beside it, renamed into place, never half-written.

use std::path::{Path, PathBuf};

use rse_core::Scheme;

use crate::error::Error;
use crate::files::names::world_name_problem;
use crate::files::place::{Outcome, lock_in, place_world, remove_leftovers};
use crate::files::write::Created;
use crate::memory::check_memory_for;
use crate::record::options::WorldOptions;
use crate::render::templates::Templates;
use crate::render::world::{WorldFiles, build_world};

/// Writes the world `build` makes (given the folder's name) at `out`: the
/// same world already there is left alone, a different one is replaced
/// only with `force`. Returns the outcome and what `build` returned beside
/// the files.
pub fn place_folder<T>(
    out: &Path,
    force: bool,
    build: impl FnOnce(String) -> Result<(WorldFiles, T), Error>,
) -> Result<(Outcome, T), Error> {
    let name = out
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| Error::BadOption {
            option: "out",
            message: format!("{}: a world folder needs a UTF-8 name", out.display()),
        })?
        .to_owned();
    if let Some(problem) = world_name_problem(&name) {
        return Err(Error::BadOption {
            option: "out",
            message: format!("{}: {problem}", out.display()),
        });
    }
    let (world, built) = build(name)?;
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
        _ => PathBuf::from("."),
    };
    // Folders made for it are removed again if it fails.
    let outcome = Created::undone_on_error(|made| {
        made.folder_chain(&parent, None)?;
        // Held until the folder is in place: a second run on the same
        // folder waits for nothing and cleans up nothing of ours.
        let _lock = lock_in(&parent, &format!("world {}", world.name), || {
            Error::BusyWorld {
                path: out.to_path_buf(),
            }
        })?;
        remove_leftovers(&parent, |leftover| leftover == world.name)?;
        place_world(&parent, &world, force)
    })?;
    Ok((outcome, built))
}

/// Writes world `index` of seed `seed` as the folder `out` (its name is
/// the world's), with `rse.json` as a batch writes it: `rse-gen check`
/// verifies it like any batch world.
pub fn write_world_at(
    scheme: &Scheme,
    seed: u64,
    index: u64,
    out: &Path,
    options: &WorldOptions,
    templates: &Templates,
    force: bool,
) -> Result<Outcome, Error> {
    let grid = scheme.grid();
    check_memory_for(grid.cells() as u64, options, 1)?;
    let (outcome, ()) = place_folder(out, force, |name| {
        Ok((
            build_world(scheme, seed, index, name, options, templates)?,
            (),
        ))
    })?;
    Ok(outcome)
}
