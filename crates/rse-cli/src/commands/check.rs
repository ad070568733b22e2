//! `rse-gen check`: prints what `rse_verify` finds in the worlds named —
//! one FAIL line per failed world (or a JSON report), a verdict on stderr.
//! Every check itself is in the library.

use std::io::Write as _;

use indicatif::{ProgressBar, ProgressDrawTarget};
#[cfg(feature = "physics")]
use rse_physics::{ColliderKind, PhysicsReport};
use rse_verify::{CheckConfig, CheckConfigError, CheckReport, check_paths};

use crate::ExitStatus;
use crate::args::CheckArgs;

pub fn run(args: &CheckArgs) -> anyhow::Result<ExitStatus> {
    let options = CheckConfig {
        physics: Some(args.physics),
        strict: Some(args.strict),
        template: args.template.clone(),
        budget: args.budget,
    }
    .resolve()
    .map_err(|e| match e {
        CheckConfigError::NoPhysics(why) => anyhow::anyhow!("--physics: {why}"),
        CheckConfigError::Template(e) => e.into(),
    })?;
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    let report = check_paths(&args.paths, &options, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let mut out = std::io::stdout().lock();
    if args.json {
        serde_json::to_writer_pretty(&mut out, &report)?;
        writeln!(out)?;
    } else {
        for fault in &report.batch_faults {
            writeln!(out, "FAIL {fault}")?;
        }
        for world in report.worlds.iter().filter(|r| !r.ok) {
            let faults: Vec<String> = world.faults.iter().map(ToString::to_string).collect();
            writeln!(
                out,
                "FAIL {}: {}",
                rse_verify::printable(&world.world),
                faults.join("; ")
            )?;
        }
    }
    out.flush()?;
    eprintln!("rse-gen: {}", report.verdict());
    let hashed: usize = report.worlds.iter().map(|w| w.hashed_only.len()).sum();
    if hashed > 0 {
        eprintln!(
            "rse-gen: {hashed} files from user templates could only be compared with their SHA-256 in rse.json"
        );
    }
    print_physics(&report);
    Ok(if report.ok() {
        ExitStatus::Success
    } else {
        ExitStatus::Failure
    })
}

/// The physics summary, one line per kind of collider tested (`mesh`,
/// `boxes`), when the smoke test ran.
#[cfg(feature = "physics")]
fn print_physics(report: &CheckReport) {
    let runs = || report.worlds.iter().flat_map(|r| &r.physics);
    let kinds: std::collections::BTreeSet<ColliderKind> = runs().map(|p| p.collider.kind).collect();
    // Mesh, then boxes (ColliderKind order), as before the kinds were typed.
    for &k in &kinds {
        let physics: Vec<&PhysicsReport> = runs().filter(|p| p.collider.kind == k).collect();
        let mean = |f: fn(&PhysicsReport) -> f64| {
            physics.iter().map(|p| f(p)).sum::<f64>() / physics.len() as f64
        };
        let errors: usize = physics.iter().map(|p| p.errors.len()).sum();
        eprintln!(
            "rse-gen: physics ({k}): {errors} errors; mean step {:.1} µs on the RSE, {:.1} µs on a plane (ratio {:.2})",
            mean(|p| p.rse_step_us),
            mean(|p| p.plane_step_us),
            mean(|p| p.ratio),
        );
    }
}

#[cfg(not(feature = "physics"))]
fn print_physics(_: &CheckReport) {}
