#!/usr/bin/env bash
# Batch throughput: 1000 worlds of the 50x50 six-obstacle sample, target
# gazebo, 2 jobs, beside `cp -r` of the very same tree (the aim: under 2x
# the copy time).
#
# Usage: bench/batch.sh [AMOUNT] [JOBS]   (run by `make bench`)
set -euo pipefail
cd "$(dirname "$0")/.."
amount=${1:-1000}
jobs=${2:-2}

cargo build --release --locked --quiet -p rse-cli
work=$(mktemp -d "${TMPDIR:-/tmp}/rse-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }

# Each timing starts with no dirty pages left by the step before it, so
# that neither pays for the other's writeback.
sync
start=$(now)
target/release/rse-gen batch schemes/six_obstacles.csv -o "$work/worlds" \
    --amount "$amount" --target gazebo --jobs "$jobs" 2>/dev/null
generate=$(echo "$(now) - $start" | bc -l)

sync
start=$(now)
cp -r "$work/worlds" "$work/copy"
copy=$(echo "$(now) - $start" | bc -l)

bytes=$(du -sb "$work/worlds" | cut -f1)
files=$(find "$work/worlds" -type f | wc -l)
awk -v n="$amount" -v j="$jobs" -v g="$generate" -v c="$copy" -v b="$bytes" -v f="$files" 'BEGIN {
    printf "rse-gen batch: %d worlds (%d files, %.1f MB), target gazebo, %d jobs\n", n, f, b / 1e6, j
    printf "  generate: %7.3f s  %8.1f worlds/s  %7.1f MB/s\n", g, n / g, b / 1e6 / g
    printf "  cp -r:    %7.3f s  %8.1f worlds/s  %7.1f MB/s\n", c, n / c, b / 1e6 / c
    printf "  ratio generate / copy: %.2f (aim: under 2)\n", g / c
}'
