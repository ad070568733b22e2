//! `rse-gen check`: are these worlds whole, reproducible and physically
//! sound? Static checks always; a rapier physics smoke test with `--physics`.

mod files;
mod terrain;

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use indicatif::{ProgressBar, ProgressDrawTarget};
use rayon::prelude::*;
use rse_core::Terrain;
use rse_physics::{PhysicsReport, SmokeTest, TerrainModel, smoke_test};
use rse_world::{MANIFEST, Manifest, MeshMode};
use serde::Serialize;

use crate::ExitStatus;
use crate::args::CheckArgs;

/// What was found in one world.
#[derive(Debug, Serialize)]
struct WorldReport {
    /// The world folder, as given or found.
    world: String,
    ok: bool,
    /// One line per fault: `file: what is wrong`.
    faults: Vec<String>,
    /// The physics smoke test, with `--physics`.
    #[serde(skip_serializing_if = "Option::is_none")]
    physics: Option<PhysicsReport>,
}

/// The whole run, for `--json`.
#[derive(Debug, Serialize)]
struct Report<'a> {
    worlds: &'a [WorldReport],
    checked: usize,
    failed: usize,
}

pub fn run(args: &CheckArgs) -> anyhow::Result<ExitStatus> {
    let worlds = discover(&args.paths)?;
    let bar =
        ProgressBar::with_draw_target(Some(worlds.len() as u64), ProgressDrawTarget::stderr());
    let reports: Vec<WorldReport> = worlds
        .par_iter()
        .map(|world| {
            let report = check_world(world, args.physics);
            bar.inc(1);
            report
        })
        .collect();
    bar.finish_and_clear();
    let failed = reports.iter().filter(|r| !r.ok).count();
    let mut out = std::io::stdout().lock();
    if args.json {
        let report = Report {
            worlds: &reports,
            checked: reports.len(),
            failed,
        };
        serde_json::to_writer_pretty(&mut out, &report)?;
        writeln!(out)?;
    } else {
        for report in reports.iter().filter(|r| !r.ok) {
            writeln!(out, "FAIL {}: {}", report.world, report.faults.join("; "))?;
        }
    }
    out.flush()?;
    eprintln!("rse-gen: {}", verdict(&reports));
    let physics: Vec<&PhysicsReport> = reports.iter().filter_map(|r| r.physics.as_ref()).collect();
    if !physics.is_empty() {
        let mean = |f: fn(&PhysicsReport) -> f64| {
            physics.iter().map(|p| f(p)).sum::<f64>() / physics.len() as f64
        };
        let errors: usize = physics.iter().map(|p| p.errors.len()).sum();
        eprintln!(
            "rse-gen: physics: {errors} errors; mean step {:.1} µs on the RSE, {:.1} µs on a plane (ratio {:.2})",
            mean(|p| p.rse_step_us),
            mean(|p| p.plane_step_us),
            mean(|p| p.ratio),
        );
    }
    Ok(if failed == 0 {
        ExitStatus::Success
    } else {
        ExitStatus::Failure
    })
}

/// The one-line `check` verdict on the worlds in `folder` (no physics), as
/// the editor shows it after a Generate.
pub fn summary(folder: &Path) -> String {
    let worlds = match discover(&[folder.to_path_buf()]) {
        Ok(worlds) => worlds,
        Err(e) => return format!("check: {e:#}"),
    };
    let reports: Vec<WorldReport> = worlds.par_iter().map(|w| check_world(w, false)).collect();
    let mut line = verdict(&reports);
    if let Some(first) = reports.iter().find(|r| !r.ok) {
        let _ = write!(
            line,
            " (first: {}: {})",
            first.world,
            first.faults.join("; ")
        );
    }
    line
}

/// `checked N worlds: G good, F failed`.
fn verdict(reports: &[WorldReport]) -> String {
    let failed = reports.iter().filter(|r| !r.ok).count();
    format!(
        "checked {} worlds: {} good, {failed} failed",
        reports.len(),
        reports.len() - failed
    )
}

/// The OBJ files among a world's files.
fn objs(present: &[String]) -> impl Iterator<Item = &String> {
    present
        .iter()
        .filter(|p| Path::new(p).extension().is_some_and(|e| e == "obj"))
}

/// The world folders named: a folder holding `rse.json` is a world; any
/// other folder is a batch, and its sub-folders holding one are its worlds.
fn discover(paths: &[PathBuf]) -> anyhow::Result<Vec<PathBuf>> {
    let mut worlds = Vec::new();
    for path in paths {
        if !path.is_dir() {
            bail!("{} is not a folder", path.display());
        }
        if path.join(MANIFEST).exists() {
            worlds.push(path.clone());
            continue;
        }
        let mut found: Vec<PathBuf> = std::fs::read_dir(path)
            .with_context(|| format!("cannot read {}", path.display()))?
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.join(MANIFEST).exists())
            .collect();
        if found.is_empty() {
            bail!(
                "{} holds no world (no rse.json in it or in its sub-folders)",
                path.display()
            );
        }
        found.sort();
        worlds.extend(found);
    }
    Ok(worlds)
}

/// Every fault of one world; with `physics`, the smoke test too.
fn check_world(world: &Path, physics: bool) -> WorldReport {
    let mut faults = Vec::new();
    let mut physics_report = None;
    let present = match rse_world::list_files(world) {
        Ok(present) => present,
        Err(e) => {
            faults.push(format!("cannot be read: {e}"));
            Vec::new()
        }
    };
    let manifest = std::fs::read_to_string(world.join(MANIFEST))
        .map_err(|e| e.to_string())
        .and_then(|text| Manifest::from_json(&text).map_err(|e| e.to_string()));
    match manifest {
        Err(e) => faults.push(format!("{MANIFEST}: {e}")),
        Ok(manifest) => {
            files::check_hashes(world, &manifest, &present, &mut faults);
            if let Some(terrain) = terrain::regenerate(world, &manifest, &mut faults) {
                // Each OBJ is read once, for the static checks and physics.
                let meshes: Vec<_> = objs(&present)
                    .map(|obj| (obj, terrain::read_obj(&world.join(obj))))
                    .collect();
                if physics {
                    let first = meshes.first().and_then(|(_, mesh)| mesh.as_ref().ok());
                    let report = physics_of(&manifest, first, &terrain);
                    faults.extend(report.errors.iter().map(|e| format!("physics: {e}")));
                    physics_report = Some(report);
                }
                for (obj, mesh) in &meshes {
                    terrain::check_obj(obj, mesh, &terrain, &mut faults);
                }
            }
        }
    }
    files::check_files(world, &present, &mut faults);
    // A file named twice (a mesh as collision and visual) is one fault.
    let mut seen = std::collections::HashSet::new();
    faults.retain(|f| seen.insert(f.clone()));
    WorldReport {
        world: world.display().to_string(),
        ok: faults.is_empty(),
        faults,
        physics: physics_report,
    }
}

/// The smoke test of a world's terrain as its simulators load it: the mesh
/// read back from its (first) OBJ in single-mesh worlds, the box set
/// otherwise — or when the OBJ could not be read, already a fault of the
/// static checks: boxes keep the test going.
fn physics_of(
    manifest: &Manifest,
    obj: Option<&terrain::ObjMesh>,
    terrain: &Terrain,
) -> PhysicsReport {
    let model = match (manifest.mesh, obj) {
        (MeshMode::Single, Some(mesh)) => TerrainModel::Mesh {
            vertices: mesh.vertices.clone(),
            triangles: mesh.triangles.clone(),
        },
        _ => TerrainModel::boxes_of(terrain),
    };
    smoke_test(&model, terrain, SmokeTest::default())
}
