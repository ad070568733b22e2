#!/bin/bash
# Packs what bench/gpu/run.sh needs on a GPU machine with no network (the device tool's H200; see bench/gpu/README.md):
# mjlab 1.6 and its stack for CPython 3.12 on manylinux x86-64, and rse's abi3 wheel, installed into one folder here,
# stripped of what a CUDA run never loads (warp-clang.so compiles CPU kernels; warp's examples and tests), then one
# tar.xz split into parts of at most 58 MB, since one device call carries at most 64 MiB with the working tree.
#   bench/gpu/pack.sh [RSE_WHEEL]      -> .gpu/00/part.00, .gpu/01/part.01, ... (.gpu is ignored by git)
set -euo pipefail
cd "$(dirname "$0")/../.."
wheel=${1:-$(ls -t target/py-wheel/rse_gen-*.whl | head -1)}
out=.gpu; site=$out/site
rm -rf "$out" && mkdir -p "$out/wheels"
platforms=(--platform manylinux_2_28_x86_64 --platform manylinux_2_27_x86_64 --platform manylinux_2_17_x86_64
           --platform manylinux2014_x86_64 --platform manylinux1_x86_64 --platform linux_x86_64 --platform any)
python3 -m pip download -q --no-deps --only-binary=:all: --python-version 3.12 --implementation cp "${platforms[@]}" \
    -d "$out/wheels" mjlab==1.6.0 mujoco==3.11.0 mujoco-warp==3.11.0 warp-lang==1.19.0 tyro==1.0.17 \
    docstring-parser shtab typeguard tensordict==0.15.3 pyvers==0.2.3 orjson rsl-rl-lib==5.4.2 gitpython gitdb smmap \
    prettytable wcwidth trimesh glfw pyopengl
python3 -m pip install -q --no-deps --no-compile --only-binary=:all: --python-version 3.12 --implementation cp \
    "${platforms[@]}" --target "$site" "$out"/wheels/*.whl "$wheel"
rm -rf "$site"/warp/bin/warp-clang.so "$site"/warp/examples "$site"/warp/tests "$site"/bin
# mjlab imports at import time what such a machine lacks and no bench run uses (seen 2026-11-28): wandb (its
# runners; the bench logs to tensorboard), imageio_ffmpeg and mediapy (video), viser and mjviser (the viewer,
# answered by stub_viewer.py as sitecustomize).
mkdir -p "$site"/wandb "$site"/imageio_ffmpeg "$site"/mediapy
: > "$site"/wandb/__init__.py
printf 'def get_ffmpeg_exe():\n    return "ffmpeg"\n' > "$site"/imageio_ffmpeg/__init__.py
printf 'def set_ffmpeg(*a, **k):\n    pass\n' > "$site"/mediapy/__init__.py
cp bench/gpu/stub_viewer.py "$site"/sitecustomize.py
tar -C "$out" -cf - site | xz -T0 -9 > "$out"/site.tar.xz
split -b 58000000 -d "$out"/site.tar.xz "$out"/part.
# One folder a call: the device tool's carry names folders.
for part in "$out"/part.*; do mkdir -p "$out/${part##*.}" && mv "$part" "$out/${part##*.}/"; done
rm -rf "$site" "$out"/wheels "$out"/site.tar.xz
ls -la "$out"
