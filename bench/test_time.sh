#!/usr/bin/env bash
# Where `make test`'s time goes: clones HEAD into a scratch folder, runs
# `.ci/run` there as CI does (CI=true, no terminal), and prints the seconds
# each `== step` took and the total (docs/testing.md's table, "Where
# `make test`'s time goes"). Needs ../shared beside the clone as beside this checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
scratch=${1:-$(mktemp -d)}
rm -rf "$scratch/rse"
git clone -q . "$scratch/rse"
[ -e "$scratch/shared" ] || [ ! -d ../shared ] || ln -s "$(cd ../shared && pwd)" "$scratch/shared"
log=$scratch/test-time.log
start=$(date +%s)
status=0
(cd "$scratch/rse" && CI=true bash .ci/run </dev/null 2>&1) |
    while IFS= read -r line; do printf '%s %s\n' "$(date +%s)" "$line"; done >"$log" || status=$?
end=$(date +%s)
awk -v start="$start" -v end="$end" '
    / == / { if (name != "") printf "%6d s  %s\n", $1 - t, name; t = $1; sub(/^[0-9]+ == /, ""); name = $0; next }
    END { if (name != "") printf "%6d s  %s\n", end - t, name; printf "%6d s  total\n", end - start }
' "$log"
echo "log: $log"
exit "$status"
