#!/usr/bin/env bash
# `scripts/count_tests.sh LOG...`: one closing line for a whole run, over
# cargo's test binaries ("test result: ok. N passed; N failed; N ignored")
# and pytest's summaries ("N passed, N skipped in Ts") in the logs.
set -euo pipefail
awk '
    /^test result:/ { p += $4; f += $6; s += $8; next }
    / in [0-9.]+s/ && /passed|failed/ {
        for (i = 1; i < NF; i++) {
            if ($(i + 1) ~ /^passed/) p += $i
            if ($(i + 1) ~ /^failed/) f += $i
            if ($(i + 1) ~ /^skipped/) s += $i
        }
    }
    END { printf "all tests: %d passed, %d failed, %d skipped\n", p, f, s }
' "$@"
