#!/usr/bin/env bash
# The RL framework adapters (rse.mjlab, rse.isaaclab) run inside the real
# frameworks' terrain generators.
# mjlab pins MuJoCo 3.11 and pulls torch (several GB), so it gets its own
# venv, .venv-frameworks, apart from make test's .venv. See docs/frameworks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
say() { printf '\n== %s\n' "$*"; }

if [ ! -x .venv-frameworks/bin/python ]; then
    python3 -m venv .venv-frameworks
fi
say "mjlab, pytest and Isaac Lab's terrain generator's imports (tests/frameworks/requirements.txt)"
.venv-frameworks/bin/python -m pip install --quiet --disable-pip-version-check -r tests/frameworks/requirements.txt
say "Isaac Lab, without its dependencies (they pull Isaac Sim; the terrain generator needs none of it)"
.venv-frameworks/bin/python -m pip install --quiet --disable-pip-version-check --no-deps isaaclab==2.3.2.post1
say "the rse package"
.venv-frameworks/bin/python -m pip install --quiet --disable-pip-version-check ./crates/rse-py
say "tests/frameworks"
.venv-frameworks/bin/python -m pytest -p no:cacheprovider -c /dev/null -ra tests/frameworks
