#!/usr/bin/env bash
# ruff and mypy on the rse Python package (crates/rse-py/python), with the
# settings in crates/rse-py/pyproject.toml, from make test's venv (.venv,
# where ruff and mypy are pinned in tests/requirements.txt).
set -euo pipefail
cd "$(dirname "$0")/.."
python=$PWD/.venv/bin/python
cd crates/rse-py
"$python" -m ruff check python
cd python
"$python" -m mypy rse
