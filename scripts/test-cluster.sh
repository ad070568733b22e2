#!/usr/bin/env bash
# Mass generation on clusters the tests start and stop themselves, on this
# machine only: Ray (a head and a worker node from Ray's cluster_utils).
# Its own venv, .venv-cluster (ray[default], 480 MB, 40 s). See docs/guide.md.
set -euo pipefail
cd "$(dirname "$0")/.."
say() { printf '\n== %s\n' "$*"; }

if [ ! -x .venv-cluster/bin/python ]; then
    python3 -m venv .venv-cluster
fi
say "Ray (tests/cluster/requirements.txt)"
.venv-cluster/bin/python -m pip install --quiet --disable-pip-version-check -r tests/cluster/requirements.txt
say "the rse package"
rm -rf target/py-wheel
.venv-cluster/bin/python -m pip wheel --quiet --disable-pip-version-check --no-deps -w target/py-wheel ./crates/rse-py
.venv-cluster/bin/python -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/py-wheel/rse_gen-*.whl
say "tests/cluster (a two-node Ray cluster on this machine)"
.venv-cluster/bin/python -m pytest -p no:cacheprovider -c /dev/null -ra tests/cluster
