#!/usr/bin/env bash
# `rse-gen check` of 1000 worlds of the 50x50 six-obstacle sample with every
# target (two OBJs each), no physics, 2 jobs: every world rebuilt in memory
# and compared byte for byte, meshes re-read. Beside it, the time to write
# the same batch, the baseline a check is "cheap next to" (the aim: under a
# minute; 11.9 s before full regeneration).
#
# Usage: bench/check.sh [AMOUNT]   (run by `make bench`)
set -euo pipefail
cd "$(dirname "$0")/.."
amount=${1:-1000}

cargo build --release --locked --quiet -p rse-cli
work=$(mktemp -d "${TMPDIR:-/tmp}/rse-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }

sync
start=$(now)
target/release/rse-gen batch schemes/six_obstacles.csv -o "$work/worlds" --amount "$amount" \
    --target obj,gazebo,webots,mujoco,urdf,usd 2>/dev/null
write=$(echo "$(now) - $start" | bc -l)

sync
start=$(now)
target/release/rse-gen check "$work/worlds" 2>/dev/null
check=$(echo "$(now) - $start" | bc -l)

awk -v n="$amount" -v w="$write" -v c="$check" 'BEGIN {
    printf "rse-gen check: %d worlds, every target, no physics, 2 cores\n", n
    printf "  write (batch): %7.2f s\n", w
    printf "  check:         %7.2f s  %7.1f worlds/s  (target: under 30 s)\n", c, n / c
    printf "  ratio check / write: %.2f\n", c / w
}'
