//! `rse-gen batch`: many worlds from one scheme, with a progress bar on a
//! terminal and a one-line summary.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::Context as _;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use rse_world::{BatchConfig, write_batch_until};

use crate::ExitStatus;
use crate::args::{BatchArgs, SchemeOverrides, in_flags};

pub fn run(args: &BatchArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let scheme = super::load_scheme(&args.scheme, overrides)?;
    let templates = args.files.templates()?;
    let options = BatchConfig {
        amount: args.amount,
        seed: args.seed,
        world: args.files.config(args.difficulty.value),
        jobs: args.jobs.map(usize::from),
        shard: args.shard,
        force: Some(args.force),
    }
    .resolve(&scheme, &args.output)
    .map_err(in_flags)?;
    let shard = options.shard;
    let worlds = shard.worlds(options.amount);
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
    let result = write_batch_until(
        &scheme,
        &templates,
        &options,
        &|_| bar.inc(1),
        stop_on_ctrl_c(),
    );
    bar.finish_and_clear();
    let summary =
        result.with_context(|| format!("batch into {} stopped", options.out.display()))?;
    if summary.not_started > 0 {
        eprintln!(
            "rse-gen: interrupted: {} worlds written whole, {} already there, {} not started; no world is half-written in {}. Rerun the same command to finish: it skips every world that is there.",
            summary.written + summary.replaced,
            summary.skipped,
            summary.not_started,
            options.out.display(),
        );
        return Ok(ExitStatus::Interrupted);
    }
    let seconds = start.elapsed().as_secs_f64();
    let done = summary.written + summary.replaced;
    let total = summary.written + summary.skipped + summary.replaced;
    eprintln!(
        "rse-gen: {total} {} in {}: {} written, {} already there, {} replaced; {:.2} s, {:.1} worlds/s, {:.1} MB/s",
        if total == 1 { "world" } else { "worlds" },
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

/// A flag set by the first Ctrl-C (SIGINT): the batch then finishes the
/// worlds it is writing and starts no other. A second Ctrl-C exits at once
/// (a world being written is left in its temporary folder, which the next
/// run removes).
fn stop_on_ctrl_c() -> &'static AtomicBool {
    static STOP: AtomicBool = AtomicBool::new(false);
    let handler = || {
        if STOP.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        eprintln!("\nrse-gen: stopping after the worlds being written (Ctrl-C again to quit now)");
    };
    // Fails only if a handler is already set: then that one stands.
    let _ = ctrlc::set_handler(handler);
    &STOP
}
