#!/usr/bin/env bash
# The RL framework adapters (rse.mjlab) run inside the real framework.
# mjlab pins MuJoCo 3.11 and pulls torch (several GB), so it gets its own
# venv, .venv-frameworks, apart from make test's .venv. See docs/frameworks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
say() { printf '\n== %s\n' "$*"; }

if [ ! -x .venv-frameworks/bin/python ]; then
    python3 -m venv .venv-frameworks
fi
say "mjlab and pytest (tests/frameworks/requirements.txt)"
.venv-frameworks/bin/python -m pip install --quiet --disable-pip-version-check -r tests/frameworks/requirements.txt
say "the rse package"
.venv-frameworks/bin/python -m pip install --quiet --disable-pip-version-check ./crates/rse-py
say "tests/frameworks"
.venv-frameworks/bin/python -m pytest -p no:cacheprovider -c /dev/null -ra tests/frameworks
