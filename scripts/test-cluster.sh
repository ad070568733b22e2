#!/usr/bin/env bash
# Mass generation on clusters the tests start and stop themselves, on this
# machine only: Slurm (Debian's slurmctld, slurmd and munge, installed here
# when missing: 16 s) and Ray (a head and a worker node from Ray's
# cluster_utils; its own venv, .venv-cluster: ray[default], 480 MB, 40 s).
# See docs/guide.md.
set -euo pipefail
cd "$(dirname "$0")/.."
say() { printf '\n== %s\n' "$*"; }

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
    say "Slurm and munge (apt)"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -q
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends slurmctld slurmd slurm-client munge
fi
say "rse-gen (the array jobs run it)"
cargo build --release --locked --quiet -p rse-cli
say "Ray (.venv-cluster, kept outside the clone: scripts/venvs.sh)"
scripts/venvs.sh cluster
say "the rse package"
rm -rf target/py-wheel-cluster
.venv-cluster/bin/python -m pip wheel --quiet --disable-pip-version-check --no-deps -w target/py-wheel-cluster ./crates/rse-py
.venv-cluster/bin/python -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/py-wheel-cluster/rse_gen-*.whl
say "tests/cluster (a one-node Slurm and a two-node Ray cluster on this machine)"
.venv-cluster/bin/python -m pytest tests/cluster
