#!/usr/bin/env bash
# Batch throughput beside `cp -r` of the very same tree, in the same run:
# 300 worlds of schemes/nist_hill.csv, every target, 2 jobs, in alternating
# rounds (this 2-core machine's single timings vary by a third: 15 rounds
# by default), medians printed. The aim: the batch under 2x the copy.
#
# Usage: bench/batch.sh [AMOUNT] [JOBS] [ROUNDS] [SCHEME]   (run by `make bench`)
#        RSE_GEN=/path/to/an/older/rse-gen bench/batch.sh    (to compare builds)
set -euo pipefail
cd "$(dirname "$0")/.."
amount=${1:-300}
jobs=${2:-2}
rounds=${3:-15}
scheme=${4:-schemes/nist_hill.csv}
targets=obj,gazebo,webots,mujoco,urdf,usd

rse_gen=${RSE_GEN:-target/release/rse-gen}
[ -n "${RSE_GEN:-}" ] || cargo build --release --locked --quiet -p rse-cli
work=$(mktemp -d "${TMPDIR:-/tmp}/rse-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }

: >"$work/times"
for round in $(seq "$rounds"); do
    rm -rf "$work/worlds" "$work/copy"
    # Each timing starts with no dirty pages left by the step before it, so
    # that neither pays for the other's writeback.
    sync
    start=$(now)
    "$rse_gen" batch "$scheme" -o "$work/worlds" \
        --amount "$amount" --target "$targets" --jobs "$jobs" 2>/dev/null
    generate=$(echo "$(now) - $start" | bc -l)
    sync
    start=$(now)
    cp -r "$work/worlds" "$work/copy"
    copy=$(echo "$(now) - $start" | bc -l)
    echo "$generate $copy" >>"$work/times"
done

bytes=$(du -sb "$work/worlds" | cut -f1)
files=$(find "$work/worlds" -type f | wc -l)
median() { sort -n | awk '{ v[NR] = $1 } END { printf "%.3f", v[int((NR + 1) / 2)] }'; }
generate=$(cut -d' ' -f1 "$work/times" | median)
ratios=$(awk '{ printf "%.3f\n", $1 / $2 }' "$work/times" | sort -n)
ratio=$(echo "$ratios" | median)
awk -v n="$amount" -v j="$jobs" -v b="$bytes" -v f="$files" -v s="$scheme" -v t="$targets" -v k="$rounds" \
    -v g="$generate" -v r="$ratio" -v lo="$(echo "$ratios" | head -1)" -v hi="$(echo "$ratios" | tail -1)" 'BEGIN {
    printf "rse-gen batch: %d worlds of %s (%d files, %.1f MB), targets %s, %d jobs, %d rounds\n", n, s, f, b / 1e6, t, j, k
    printf "  generate, median: %7.3f s  %8.1f worlds/s  %7.1f MB/s\n", g, n / g, b / 1e6 / g
    printf "  generate / cp -r of the same tree, per round: median %.2f (min %.2f, max %.2f; aim: under 2)\n", r, lo, hi
}'
