#!/usr/bin/env bash
# The edit–test loop: what a change most often breaks, in a few minutes on
# a warm tree, with no apt, no browser and no simulator parser. `make test`
# (CI) runs all of this and the rest; docs/development.md says which is which.
#   - format;
#   - every Rust test but the command line's (those drive the release
#     binary through whole batches: `cargo test --release -p rse-cli`);
#   - the Python package's own tests (pytest -m "not thirdparty": no
#     libsdformat, gz-physics, Chromium or wheel build), against the
#     extension built in debug-free release as `make test` builds it.
set -euo pipefail
cd "$(dirname "$0")/.."
say() { printf '\n== %s\n' "$*" >&2; }

say "format"
cargo fmt --all --check
say "Rust tests (all crates but rse-cli)"
cargo test --workspace --exclude rse-cli --locked --quiet
say "the Python package (maturin, release)"
scripts/venvs.sh test
say "the Python package's lint and types (ruff, mypy)"
scripts/lint-python.sh
rm -rf target/py-wheel
.venv/bin/python -m pip wheel --quiet --disable-pip-version-check --no-deps -w target/py-wheel ./crates/rse-py
.venv/bin/python -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/py-wheel/rse_gen-*.whl
cargo build --locked --quiet -p rse-cli
say "pytest (not the third-party tools make test installs)"
RSE_GEN="$PWD/target/debug/rse-gen" .venv/bin/python -m pytest -q -n "${PYTEST_JOBS:-auto}" -m "not thirdparty"
