#!/usr/bin/env bash
# Runs every fuzz target (fuzz/, libFuzzer through libfuzzer-sys, built
# as cargo-fuzz builds them), FUZZ_JOBS targets at a time (default one per
# core), in one of two modes:
#   - random (`make fuzz`, the default): FUZZ_SECONDS each (default 12),
#     libFuzzer's own random seed, a corpus that grows across runs in
#     target/fuzz-corpus/ (not committed): new ground every time;
#   - seeded (FUZZ_MODE=seeded, what `make test` runs): a fixed number of
#     runs per target (the table below, ~6 s each here), -seed=FUZZ_SEED
#     (default 1), one rayon thread, from fuzz/seeds/<target>/ alone
#     (copied, so nothing grows between runs): the same start, the same
#     mutation stream and the same length every time, so CI explores the
#     neighbourhood of the seeds, not new ground that an unrelated change
#     would be blamed for. Not bit for bit: libFuzzer keeps an input for
#     the coverage it adds, and six of the seven targets' coverage varies
#     between runs of one input (measured: same seed, different corpora,
#     also without ASLR), so later mutations can differ. What makes a
#     failure reproducible is the input libFuzzer writes when it fails,
#     which the replay test runs deterministically.
# An input that fails is written to fuzz/regressions/<target>/, where the
# stable test crates/rse-fuzz/tests/replay.rs replays it for ever after:
# commit it with the fix. Exits 1 if any target found a failure.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-12}
mode=${FUZZ_MODE:-random}
seed=${FUZZ_SEED:-1}
# Runs per target in seeded mode: about 6 s of each on the 2-core machine
# (the targets' speeds differ by 500x: a rebuilt atlas or a resumed batch
# against a heightmap parse).
declare -A seeded_runs=(
    [atlas_record]=12000 [editor_api]=400000 [heightmap]=1500000 [manifest]=12000
    [obj]=80000 [resume]=3000 [scheme]=5000
)

# The build is cargo-fuzz's (`cargo fuzz build -O -s none`: libFuzzer's
# coverage passes, `--cfg fuzzing`) written out, so that neither cargo-fuzz
# nor the nightly toolchain is needed: every flag below is stable. No
# AddressSanitizer: rse forbids unsafe code, and what it would guard (out
# of bounds, use after free) is checked by Rust itself; a runaway
# allocation is still a finding (-rss_limit_mb). Nor cargo-fuzz's one
# codegen unit or opt-level 3 (fuzz/Cargo.toml): these runs last seconds,
# the build minutes. Overflow checks and debug assertions are on: a size
# that wraps is a finding.
# `cargo fuzz run <target>` works on the same layout for longer sessions.
triple=$(rustc -vV | awk '/^host:/ { print $2 }')
coverage="-Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4"
coverage="$coverage -Cllvm-args=-sanitizer-coverage-inline-8bit-counters"
coverage="$coverage -Cllvm-args=-sanitizer-coverage-pc-table"
coverage="$coverage -Cllvm-args=-sanitizer-coverage-trace-compares"
coverage="$coverage -Cllvm-args=-simplifycfg-branch-fold-threshold=0"
[[ "$triple" == *-linux-* ]] && coverage="$coverage -Cllvm-args=-sanitizer-coverage-stack-depth"
RUSTFLAGS="$coverage --cfg fuzzing" cargo build --manifest-path fuzz/Cargo.toml --locked \
    --release --target "$triple" --bins --quiet
# Where cargo put them: fuzz/target, or a shared CARGO_TARGET_DIR.
bin=${CARGO_TARGET_DIR:-fuzz/target}/$triple/release
# Targets run side by side, one per core (libFuzzer is single-threaded).
jobs=${FUZZ_JOBS:-$(nproc)}
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
run_one() {
    local target=$1 status=0
    local corpus=target/fuzz-corpus/$target regressions=fuzz/regressions/$target
    local budget=(-max_total_time="$seconds") threads=${RAYON_NUM_THREADS:-}
    if [ "$mode" = seeded ]; then
        [ -n "${seeded_runs[$target]:-}" ] || { echo "fuzz.sh: no seeded run count for $target" >&2; exit 2; }
        corpus=$logs/corpus-$target
        budget=(-seed="$seed" -runs="${seeded_runs[$target]}")
        threads=1
    fi
    mkdir -p "$corpus" "$regressions"
    # -timeout: one input taking longer is a hang; -rss_limit_mb: one
    # allocating more is a finding too.
    RAYON_NUM_THREADS=$threads "$bin/$target" "$corpus" "fuzz/seeds/$target" "${budget[@]}" \
        -timeout=10 -rss_limit_mb=4096 -max_len=65536 \
        -artifact_prefix="$regressions/" -print_final_stats=1 >"$logs/$target" 2>&1 || status=$?
    echo "$status" >"$logs/$target.status"
}
targets=$(basename -s .rs fuzz/fuzz_targets/*.rs)
running=0
for target in $targets; do
    run_one "$target" &
    running=$((running + 1))
    if [ "$running" -ge "$jobs" ]; then
        wait -n
        running=$((running - 1))
    fi
done
wait
findings=0
executions=0
for target in $targets; do
    log=$logs/$target
    status=$(cat "$log.status")
    runs=$(awk '/stat::number_of_executed_units/ { print $2 }' "$log" | tail -1)
    executions=$((executions + ${runs:-0}))
    if [ "$status" -ne 0 ]; then
        findings=$((findings + 1))
        echo "fuzz $target: FOUND a failure after ${runs:-?} runs (input kept in fuzz/regressions/$target/):" >&2
        # libFuzzer's words, or the end of the log when it has none (a
        # binary that did not start): never nothing.
        { grep -E "panicked|ERROR|SUMMARY|Test unit written" "$log" || tail -5 "$log"; } | head -20 >&2
    else
        echo "fuzz $target: ${runs:-0} runs, no failure" >&2
    fi
done
echo "fuzz ($mode): $executions runs over all targets, $findings targets with findings"
[ "$findings" -eq 0 ]
