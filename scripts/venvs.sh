#!/usr/bin/env bash
# Every venv the tests use, from one set of recipes, each kept outside the
# clone in a cache keyed by its pinned requirements (scripts/cached_venv.sh):
#
#   scripts/venvs.sh test         .venv and .venv-mjx (make test)
#   scripts/venvs.sh frameworks   .venv-frameworks, -genesis, -isaaclab3, -newton, -playground
#   scripts/venvs.sh cluster      .venv-cluster (make test-cluster)
#   scripts/venvs.sh all          every one
#
# Venvs that do not depend on each other install in parallel (pip waits on
# the network and the disk more than on a core), each into a log of its own
# under target/venv-logs/ (NAME.PID.log: CI and make test may run this at
# once), shown when it fails. A venv present already
# costs nothing. Sourced by the make targets' scripts for `test_install`.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/cached_venv.sh
. scripts/cached_venv.sh

test_install() { pip_install "$1" -r tests/requirements.txt; }
# MJX pins its own MuJoCo (3.17; .venv has 4.0).
mjx_install() { pip_install "$1" -r tests/mjx/requirements.txt; }
# mjlab brings torch and MuJoCo 3.11; Isaac Lab 2.3 without its dependencies
# (they pull Isaac Sim; its terrain generator needs none of them).
frameworks_install() {
    pip_install "$1" -r tests/frameworks/requirements.txt
    pip_install "$1" --no-deps -r tests/frameworks/no-deps.txt
}
# Genesis pulls its own torch and compilers (8.5 GB).
genesis_install() { pip_install "$1" -r tests/genesis/requirements.txt; }
# Isaac Lab 3.0 (Python 3.12) and its URDF importer, over Isaac Lab's
# usd-exchange pin (see tests/isaaclab3/importers.txt): pip prints the
# known conflict; only its failure stops the run.
isaaclab3_install() {
    pip_install "$1" -r tests/isaaclab3/requirements.txt
    local log
    log=$(mktemp)
    if ! pip_install "$1" -r tests/isaaclab3/importers.txt >"$log" 2>&1; then
        cat "$log" >&2
        return 1
    fi
}
# Newton (newton[sim] pins MuJoCo Warp 3.17).
newton_install() { pip_install "$1" -r tests/newton/requirements.txt; }
# MuJoCo Playground: JAX, Brax and MJX pinned together. Playground
# git-clones MuJoCo Menagerie from GitHub on first use, and the
# mujoco-menagerie package downloads its robots from GitHub too: neither is
# reachable from the package registries alone. The Go1's meshes (visual
# only) are Menagerie's unitree_go1 assets, which mjlab's wheel ships.
playground_install() {
    pip_install "$1" -r tests/playground/requirements.txt
    local menagerie go1
    menagerie=$("$1" -c 'from mujoco_playground._src import mjx_env; print(mjx_env.MENAGERIE_PATH)')
    go1=$(.venv-frameworks/bin/python -c 'import mjlab, pathlib; print(pathlib.Path(mjlab.__file__).parent / "asset_zoo/robots/unitree_go1/xmls/assets")')
    mkdir -p "$menagerie/unitree_go1/assets"
    cp "$go1"/*.stl "$menagerie/unitree_go1/assets/"
}
# Ray with its dashboard (the state API the cluster tests read).
cluster_install() { pip_install "$1" -r tests/cluster/requirements.txt; }

# The first Python 3.12 that runs: on PATH, else pyenv's (its shim for
# python3.12 is on PATH even when 3.12 is not the selected version, and
# then fails, so each candidate is tried).
python312() {
    local candidate
    for candidate in "$(command -v python3.12 || true)" $(ls -d "$HOME"/.pyenv/versions/3.12*/bin/python 2>/dev/null | sort -rV); do
        if [ -n "$candidate" ] && "$candidate" -c 'import sys; assert sys.version_info[:2] == (3, 12)' 2>/dev/null; then
            echo "$candidate"
            return
        fi
    done
    echo "scripts/venvs.sh: Isaac Lab 3.0 needs Python 3.12: install it (e.g. pyenv install 3.12) and rerun" >&2
    return 2
}

# `venv NAME PYTHON RECIPE FILES...`: cached_venv in the background, its
# output in target/venv-logs/NAME.log.
pids=()
names=()
venv() {
    local link=$1
    mkdir -p target/venv-logs
    cached_venv "$@" >"target/venv-logs/${link#.}.$$.log" 2>&1 &
    pids+=($!)
    names+=("$link")
}
wait_all() {
    local i failed=0
    for i in "${!pids[@]}"; do
        if ! wait "${pids[$i]}"; then
            echo "scripts/venvs.sh: making ${names[$i]} failed:" >&2
            cat "target/venv-logs/${names[$i]#.}.$$.log" >&2
            failed=1
        fi
    done
    pids=()
    names=()
    return $failed
}

make_test() {
    venv .venv python3 test_install tests/requirements.txt
    venv .venv-mjx python3 mjx_install tests/mjx/requirements.txt
}
make_frameworks() {
    local py312
    py312=$(python312)
    venv .venv-frameworks python3 frameworks_install tests/frameworks/requirements.txt tests/frameworks/no-deps.txt
    venv .venv-genesis python3 genesis_install tests/genesis/requirements.txt
    venv .venv-isaaclab3 "$py312" isaaclab3_install tests/isaaclab3/requirements.txt tests/isaaclab3/importers.txt
    venv .venv-newton python3 newton_install tests/newton/requirements.txt
    wait_all
    # Playground takes the Go1's meshes from .venv-frameworks.
    venv .venv-playground python3 playground_install tests/playground/requirements.txt tests/frameworks/requirements.txt
}
make_cluster() {
    venv .venv-cluster python3 cluster_install tests/cluster/requirements.txt
}

# Run as a script (not sourced): make the named set.
if [ "${BASH_SOURCE[0]}" = "$0" ]; then
    case "${1:-}" in
        test) make_test ;;
        frameworks) make_frameworks ;;
        cluster) make_cluster ;;
        all)
            make_test
            make_cluster
            make_frameworks
            ;;
        *)
            echo "usage: scripts/venvs.sh test|frameworks|cluster|all" >&2
            exit 2
            ;;
    esac
    wait_all
fi
