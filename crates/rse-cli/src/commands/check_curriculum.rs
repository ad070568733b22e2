//! `rse-gen check-curriculum`: a scheme's per-level statistics as a table
//! (or JSON), exit 1 when a level is dead or no higher than the one below;
//! several schemes (a mix) each in turn, exit 1 when any fails.

use std::fmt::Write as _;
use std::io::Write as _;

use anyhow::Context as _;
use rse_core::{
    CurriculumOptions, CurriculumReport, check_curriculum_within, within_curriculum_budget,
};
use serde_json::json;

use crate::ExitStatus;
use crate::args::{CheckCurriculumArgs, SchemeOverrides};

pub fn run(args: &CheckCurriculumArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let schemes = super::load_schemes(&args.schemes, overrides)?;
    let budget = args.budget.unwrap_or_default().factor();
    let options_of = |scheme: &rse_core::Scheme| CurriculumOptions {
        levels: args.levels,
        draws: args.draws,
        seed: scheme.seed_or(args.seed),
    };
    // The budget holds the whole run, priced before a world is made: four
    // schemes at --budget 0.035 each ran within it and took 11 s.
    if let Some(first) = schemes.first() {
        let options = options_of(first).validate()?;
        let visits = schemes
            .iter()
            .fold(0u64, |sum, s| sum.saturating_add(options.visits(s)));
        within_curriculum_budget(visits, options, budget)
            .with_context(|| format!("check-curriculum: the {} schemes together", schemes.len()))?;
    }
    let mut tables = Vec::new();
    let mut reports = Vec::new();
    let mut ok = true;
    for (scheme, path) in schemes.iter().zip(&args.schemes) {
        let options = options_of(scheme);
        let name = path.display().to_string();
        // Ctrl-C ends the process as ever: nothing is written until the end.
        let report = check_curriculum_within(scheme, options, budget, &|| false)
            .with_context(|| format!("check-curriculum {name}"))?;
        ok &= report.problems.is_empty();
        if args.json {
            reports.push(report_json(&report, &name));
        } else {
            tables.push(table(&report, &name));
        }
    }
    // One scheme: its object, as before; several: a list of them.
    let text = match (args.json, &reports[..]) {
        (true, [one]) => format!("{one:#}\n"),
        (true, many) => format!("{:#}\n", serde_json::Value::Array(many.to_vec())),
        (false, _) => tables.join("\n"),
    };
    let mut stdout = std::io::stdout().lock();
    stdout.write_all(text.as_bytes())?;
    stdout.flush()?;
    Ok(if ok {
        ExitStatus::Success
    } else {
        ExitStatus::Failure
    })
}

/// The report as a table a person reads, problems last.
fn table(report: &CurriculumReport, scheme: &str) -> String {
    let o = report.options;
    let mut out = format!(
        "{scheme}: {} levels, {} worlds each (seed {})\n\
         level  difficulty  flat   mean height  mean step  max step  max slope  distinct\n",
        o.levels, o.draws, o.seed
    );
    for l in &report.levels {
        let _ = writeln!(
            out,
            "{:>5}  {:>10.3}  {:>4.0}%  {:>9.1} mm  {:>6.1} mm  {:>5.0} mm  {:>7.1}°  {:>8}",
            l.level,
            l.difficulty.get(),
            100.0 * l.flat_share,
            1000.0 * l.mean_height,
            1000.0 * l.mean_step,
            1000.0 * l.max_step,
            l.max_slope_deg,
            l.distinct,
        );
    }
    if report.problems.is_empty() {
        out += "ok: no dead level, the mean height rises at every level\n";
    }
    for problem in &report.problems {
        let _ = writeln!(out, "FAIL: {problem}");
    }
    out
}

/// The report as JSON: SI units, `ok` and the problems in words.
fn report_json(report: &CurriculumReport, scheme: &str) -> serde_json::Value {
    let o = report.options;
    json!({
        "scheme": scheme,
        "levels": o.levels,
        "draws": o.draws,
        "seed": o.seed,
        "ok": report.problems.is_empty(),
        "problems": report.problems.iter().map(ToString::to_string).collect::<Vec<_>>(),
        "per_level": report.levels.iter().map(|l| json!({
            "level": l.level,
            "difficulty": l.difficulty.get(),
            "flat_share": l.flat_share,
            "mean_height": l.mean_height,
            "mean_step": l.mean_step,
            "max_step": l.max_step,
            "max_slope_deg": l.max_slope_deg,
            "distinct": l.distinct,
        })).collect::<Vec<_>>(),
    })
}
