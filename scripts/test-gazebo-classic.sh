#!/usr/bin/env bash
# Gazebo classic 11 loading our `gazebo-classic` worlds, for real: a Debian
# bullseye chroot (the last Debian release with Gazebo 11) made once under
# target/gazebo11-root by debootstrap and apt (about 2 minutes and 1.3 GB here), then
# gzserver --verbose on sample worlds, failing on any SDF error or warning,
# and spheres dropped on the default collider. Needs root (chroot, and
# debootstrap from Debian's packages). Not part of `make test`.
set -euo pipefail
cd "$(dirname "$0")/.."
say() { printf '\n== %s\n' "$*"; }

if [ "$(id -u)" -ne 0 ]; then
    echo "make test-gazebo-classic needs root (debootstrap, chroot): run it with sudo" >&2
    exit 2
fi
if ! command -v debootstrap >/dev/null; then
    say "debootstrap (apt)"
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends debootstrap
fi
say "rse-gen (the worlds)"
cargo build --release --locked --quiet -p rse-cli
say "pytest (target/gazebo-classic-venv)"
venv=target/gazebo-classic-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "$(grep -E '^pytest==' tests/requirements.txt)"
say "Gazebo 11 in a bullseye chroot (made once), and the tests in it"
"$venv/bin/python" -m pytest -p no:cacheprovider tests/gazebo_classic "$@"
