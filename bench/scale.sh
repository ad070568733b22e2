#!/usr/bin/env bash
# Scale, measured: batches of 10^3, 10^4 and 10^5 worlds of a small scheme
# (schemes/random.csv, 20x20) for one target set, then `rse-gen check` of
# each: time, bytes, files and folders (inodes). docs/scale.md extrapolates
# from these figures; per-world bytes and files for each target set come
# from a batch of 100.
#
# Usage: bench/scale.sh [MAX_AMOUNT] [TARGETS] [SCHEME] [JOBS]
set -euo pipefail
cd "$(dirname "$0")/.."
max=${1:-100000}
targets=${2:-mujoco}
scheme=${3:-schemes/random.csv}
jobs=${4:-2}

cargo build --release --locked --quiet -p rse-cli
work=$(mktemp -d "${TMPDIR:-/tmp}/rse-scale.XXXXXX")
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }
since() { echo "$(now) - $1" | bc -l; }

echo "per world, by target set (100 worlds of $scheme):"
for set in mujoco urdf gazebo webots usd obj obj,gazebo,webots,mujoco,urdf,usd; do
    target/release/rse-gen batch "$scheme" -o "$work/set" --amount 100 --target "$set" --jobs "$jobs" 2>/dev/null
    bytes=$(du -sb "$work/set" | cut -f1)
    files=$(find "$work/set" -type f | wc -l)
    folders=$(find "$work/set" -mindepth 1 -type d | wc -l)
    awk -v s="$set" -v b="$bytes" -v f="$files" -v d="$folders" \
        'BEGIN { printf "  %-34s %9.1f KB  %5.1f files  %5.1f folders\n", s, b / 1e3 / 100, f / 100, d / 100 }'
    rm -rf "$work/set"
done

echo "batches of $scheme, target $targets, $jobs jobs:"
for amount in 1000 10000 100000; do
    [ "$amount" -le "$max" ] || break
    sync
    start=$(now)
    target/release/rse-gen batch "$scheme" -o "$work/w$amount" --amount "$amount" --target "$targets" --jobs "$jobs" 2>/dev/null
    generate=$(since "$start")
    sync
    start=$(now)
    target/release/rse-gen check "$work/w$amount" 2>/dev/null >/dev/null
    check=$(since "$start")
    bytes=$(du -sb "$work/w$amount" | cut -f1)
    inodes=$(find "$work/w$amount" | wc -l)
    awk -v n="$amount" -v g="$generate" -v c="$check" -v b="$bytes" -v i="$inodes" 'BEGIN {
        printf "  %7d worlds: generate %8.1f s (%6.0f worlds/s), check %8.1f s (%6.0f worlds/s), %8.1f MB, %8d inodes\n",
            n, g, n / g, c, n / c, b / 1e6, i
    }'
    rm -rf "$work/w$amount"
done
