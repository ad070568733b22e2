//! `rse-gen batch`: many worlds from one scheme, with a progress bar on a
//! terminal and a one-line summary.

use std::time::{Duration, Instant};

use anyhow::Context as _;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use rse_world::{BatchOptions, Templates, WorldOptions, write_batch};

use crate::ExitStatus;
use crate::args::{BatchArgs, SchemeOverrides};

pub fn run(args: &BatchArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let scheme = super::load_scheme(&args.scheme, overrides)?;
    let templates = match &args.template {
        Some(dir) => Templates::with_overrides(dir)?,
        None => Templates::builtin(),
    };
    let options = BatchOptions {
        out: args.output.clone(),
        amount: args.amount.unwrap_or(scheme.globals().amount),
        seed: args.seed.unwrap_or(scheme.globals().seed),
        world: WorldOptions {
            targets: args.target.clone(),
            mesh: args.mesh,
        },
        jobs: args.jobs.map(usize::from),
        shard: args.shard.unwrap_or_default(),
        force: args.force,
    };
    let shard = options.shard;
    let worlds = options.amount.saturating_sub(shard.k).div_ceil(shard.n);
    // Drawn only on a terminal: indicatif hides it on a pipe or file.
    let bar = ProgressBar::with_draw_target(Some(worlds), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template(
            "{elapsed_precise} [{wide_bar}] {pos}/{len} worlds, {rate}, ETA {eta}",
        )
        .expect("a valid template")
        .with_key(
            "rate",
            |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{:.0}/s", state.per_sec());
            },
        )
        .progress_chars("=> "),
    );
    bar.enable_steady_tick(Duration::from_millis(200));
    let start = Instant::now();
    let result = write_batch(&scheme, &templates, &options, &|_| bar.inc(1));
    bar.finish_and_clear();
    let summary =
        result.with_context(|| format!("batch into {} stopped", options.out.display()))?;
    let seconds = start.elapsed().as_secs_f64();
    let done = summary.written + summary.replaced;
    eprintln!(
        "rse-gen: {} worlds in {}: {} written, {} already there, {} replaced; {:.2} s, {:.1} worlds/s, {:.1} MB/s",
        summary.written + summary.skipped + summary.replaced,
        options.out.display(),
        summary.written,
        summary.skipped,
        summary.replaced,
        seconds,
        done as f64 / seconds.max(1e-9),
        summary.bytes as f64 / 1e6 / seconds.max(1e-9),
    );
    Ok(ExitStatus::Success)
}
