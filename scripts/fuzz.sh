#!/usr/bin/env bash
# Runs every fuzz target (fuzz/, cargo-fuzz with libFuzzer on the nightly
# toolchain) for FUZZ_SECONDS each (default 12: about a minute in all).
# Seeds come from fuzz/seeds/<target>/; the growing corpus lives in
# target/fuzz-corpus/ (not committed). An input that fails is written to
# fuzz/regressions/<target>/, where the stable test
# crates/rse-fuzz/tests/replay.rs replays it for ever after: commit it with
# the fix. Exits 1 if any target found a failure.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-12}

if ! rustup run nightly rustc --version >/dev/null 2>&1; then
    echo "scripts/fuzz.sh: needs the nightly toolchain (rustup toolchain install nightly)" >&2
    exit 2
fi
if ! cargo +nightly fuzz --version >/dev/null 2>&1; then
    echo "== installing cargo-fuzz (crates.io)" >&2
    cargo install cargo-fuzz --locked --version 0.13.2
fi
cargo +nightly fuzz build -O
bin=fuzz/target/x86_64-unknown-linux-gnu/release
findings=0
executions=0
for target in $(cargo +nightly fuzz list); do
    corpus=target/fuzz-corpus/$target
    regressions=fuzz/regressions/$target
    mkdir -p "$corpus" "$regressions"
    log=$(mktemp)
    status=0
    # -timeout: one input taking longer is a hang; -rss_limit_mb: one
    # allocating more is a finding too.
    "$bin/$target" "$corpus" "fuzz/seeds/$target" -max_total_time="$seconds" \
        -timeout=10 -rss_limit_mb=4096 -max_len=65536 \
        -artifact_prefix="$regressions/" -print_final_stats=1 >"$log" 2>&1 || status=$?
    runs=$(awk '/stat::number_of_executed_units/ { print $2 }' "$log" | tail -1)
    executions=$((executions + ${runs:-0}))
    if [ "$status" -ne 0 ]; then
        findings=$((findings + 1))
        echo "fuzz $target: FOUND a failure after ${runs:-?} runs (input kept in $regressions/):" >&2
        grep -E "panicked|ERROR|SUMMARY|Test unit written" "$log" | head -20 >&2
    else
        echo "fuzz $target: ${runs:-0} runs, no failure" >&2
    fi
    rm -f "$log"
done
echo "fuzz: $executions runs over all targets, $findings targets with findings"
[ "$findings" -eq 0 ]
