#!/usr/bin/env bash
# The RL framework adapters (rse.mjlab, rse.isaaclab, rse.genesis, rse.newton,
# rse.playground) run inside
# the real frameworks: their terrain generators, mjlab's own RL env, Genesis's
# scene.
# mjlab pins MuJoCo 3.11 and pulls torch (several GB), so it gets its own
# venv, .venv-frameworks, apart from make test's .venv. See docs/frameworks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
say() { printf '\n== %s\n' "$*"; }

# shellcheck source=scripts/cached_venv.sh
. scripts/cached_venv.sh

# Each venv is kept outside the clone, keyed by its pinned requirements
# (scripts/cached_venv.sh): made once per machine and pin set, reused by
# every clone after it.
frameworks_install() {
    pip_install "$1" -r tests/frameworks/requirements.txt
    # Isaac Lab without its dependencies (they pull Isaac Sim; the terrain
    # generator needs none of it).
    pip_install "$1" --no-deps -r tests/frameworks/no-deps.txt
}
say "mjlab, Isaac Lab 2.3's terrain generator (.venv-frameworks)"
cached_venv .venv-frameworks python3 frameworks_install tests/frameworks/requirements.txt tests/frameworks/no-deps.txt

# Genesis pulls its own torch and compilers (8.5 GB): a venv of its own.
genesis_install() { pip_install "$1" -r tests/genesis/requirements.txt; }
say "Genesis (.venv-genesis)"
cached_venv .venv-genesis python3 genesis_install tests/genesis/requirements.txt

# Isaac Lab 3.0 runs on Python 3.12 only (its terrain generator, importer
# and Newton physics, without Isaac Sim): a venv of its own. The first
# Python 3.12 that runs: on PATH, else pyenv's (its shim for python3.12 is
# on PATH even when 3.12 is not the selected version, and then fails, so
# each candidate is tried).
py312=""
for candidate in "$(command -v python3.12 || true)" $(ls -d "$HOME"/.pyenv/versions/3.12*/bin/python 2>/dev/null | sort -rV); do
    if [ -n "$candidate" ] && "$candidate" -c 'import sys; assert sys.version_info[:2] == (3, 12)' 2>/dev/null; then
        py312=$candidate
        break
    fi
done
if [ -z "$py312" ]; then
    echo "scripts/test-frameworks.sh: Isaac Lab 3.0 needs Python 3.12: install it (e.g. pyenv install 3.12) and rerun" >&2
    exit 2
fi
isaaclab3_install() {
    pip_install "$1" -r tests/isaaclab3/requirements.txt
    # Isaac Lab's URDF importer, over Isaac Lab's usd-exchange pin (see
    # tests/isaaclab3/importers.txt): pip prints the known conflict; only
    # its failure stops the run.
    local log
    log=$(mktemp)
    if ! pip_install "$1" -r tests/isaaclab3/importers.txt >"$log" 2>&1; then
        cat "$log" >&2
        return 1
    fi
}
say "Isaac Lab 3.0 and its URDF importer (.venv-isaaclab3)"
cached_venv .venv-isaaclab3 "$py312" isaaclab3_install tests/isaaclab3/requirements.txt tests/isaaclab3/importers.txt

# Newton (rse.newton): per-world height fields natively; its own venv
# (newton[sim] pins MuJoCo Warp 3.17; 26 s, 730 MB).
newton_install() { pip_install "$1" -r tests/newton/requirements.txt; }
say "Newton (.venv-newton)"
cached_venv .venv-newton python3 newton_install tests/newton/requirements.txt

# MuJoCo Playground (rse.playground): JAX, Brax and MJX pinned together; its
# own venv (1.4 GB, 2 min). Playground git-clones MuJoCo Menagerie from
# GitHub on first use, and the mujoco-menagerie package downloads its robots
# from GitHub too: neither is reachable from the package registries alone.
# The Go1's meshes (visual only) are Menagerie's unitree_go1 assets, which
# mjlab's wheel ships.
playground_install() {
    pip_install "$1" -r tests/playground/requirements.txt
    local menagerie go1
    menagerie=$("$1" -c 'from mujoco_playground._src import mjx_env; print(mjx_env.MENAGERIE_PATH)')
    go1=$(.venv-frameworks/bin/python -c 'import mjlab, pathlib; print(pathlib.Path(mjlab.__file__).parent / "asset_zoo/robots/unitree_go1/xmls/assets")')
    mkdir -p "$menagerie/unitree_go1/assets"
    cp "$go1"/*.stl "$menagerie/unitree_go1/assets/"
}
say "MuJoCo Playground (.venv-playground)"
cached_venv .venv-playground python3 playground_install tests/playground/requirements.txt tests/frameworks/requirements.txt

say "the rse package (one wheel for every venv)"
rm -rf target/py-wheel-frameworks
.venv-frameworks/bin/python -m pip wheel --quiet --disable-pip-version-check --no-deps -w target/py-wheel-frameworks ./crates/rse-py
for venv in .venv-frameworks .venv-genesis .venv-isaaclab3 .venv-newton .venv-playground; do
    $venv/bin/python -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/py-wheel-frameworks/rse_gen-*.whl
done
say "tests/frameworks (mjlab with its Go1 and G1 tasks, Isaac Lab 2.3)"
.venv-frameworks/bin/python -m pytest tests/frameworks
say "tests/newton (Newton 1.8 on the CPU: XPBD and its MuJoCo solver)"
.venv-newton/bin/python -m pytest tests/newton
say "tests/playground (MuJoCo Playground's Go1 joystick on rse's fields, MJX on the CPU, Brax's PPO)"
.venv-playground/bin/python -m pytest tests/playground
# Isaac Lab's Go2 USD is on NVIDIA's Nucleus server, out of reach: its Go2
# task runs on Unitree's Go2 URDF as Genesis's wheel ships it.
rm -rf target/assets/go2 && mkdir -p target/assets
cp -r "$(.venv-genesis/bin/python -c 'import genesis, pathlib; print(pathlib.Path(genesis.__file__).parent / "assets/urdf/go2")')" target/assets/go2
say "tests/isaaclab3 (Isaac Lab 3.0, Newton on the CPU: balls on rse tiles; its own Go2 rough task and rsl-rl's PPO)"
.venv-isaaclab3/bin/python -m pytest tests/isaaclab3
say "tests/genesis (Genesis on the CPU; the first run builds the terrain's SDF, a few minutes)"
.venv-genesis/bin/python -m pytest tests/genesis
