#!/usr/bin/env bash
# Install time and size of each framework venv the tests use (docs/frameworks.md
# quotes them): for each, a fresh venv in a scratch folder, `pip
# install -r` its requirements, then the seconds and `du -sh`. Heavy: about
# 15 minutes and 25 GB of scratch disk, removed as it goes.
# Run: bench/framework_installs.sh [scratch dir]
set -euo pipefail
cd "$(dirname "$0")/.."
scratch=${1:-$(mktemp -d)}
py312=$(command -v python3.12 || ls -d "$HOME"/.pyenv/versions/3.12*/bin/python 2>/dev/null | tail -1 || true)
for entry in "mjx python3 tests/mjx/requirements.txt" \
    "frameworks python3 tests/frameworks/requirements.txt" \
    "genesis python3 tests/genesis/requirements.txt" \
    "isaaclab3 ${py312:-missing} tests/isaaclab3/requirements.txt"; do
    read -r name python requirements <<<"$entry"
    if [ "$python" = missing ]; then
        echo "$name: needs Python 3.12 (pyenv install 3.12), skipped"
        continue
    fi
    venv=$scratch/venv-$name
    start=$(date +%s)
    "$python" -m venv "$venv"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
    end=$(date +%s)
    printf '%-10s %4d s  %s\n' "$name" "$((end - start))" "$(du -sh "$venv" | cut -f1)"
    rm -rf "$venv"
done
