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

# Debian's OSMesa: rse.mjlab_video renders offscreen on the CPU (MUJOCO_GL=osmesa).
if ! ldconfig -p | grep -q libOSMesa; then
    sudo=""
    [ "$(id -u)" = 0 ] || sudo="sudo"
    say "installing libosmesa6 (Debian)"
    $sudo apt-get install -y -q libosmesa6 >/dev/null 2>&1 \
        || { $sudo apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q libosmesa6 >/dev/null; }
fi

# Every framework's venv, kept outside the clone and keyed by its pins
# (scripts/venvs.sh), made in parallel where missing; CI starts this at its
# beginning, beside make test.
scripts/venvs.sh frameworks

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
