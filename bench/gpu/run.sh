#!/bin/bash
# Runs on the device tool's GPU machine (no network), from the repository's root there (see bench/gpu/README.md):
#   bench/gpu/run.sh stash .gpu/00          a first call: keeps this call's part in /tmp/parts for the next call
#   bench/gpu/run.sh bench .gpu/01 SECONDS  the last call: joins the parts, installs them in /tmp/site, lays this
#                                           tree's Python sources over rse's wheel, and runs the benches within SECONDS
# What the benches print is also written under $OUT (the tool brings it back).
set -u
verb=$1 dir=$2
mkdir -p /tmp/parts && cp "$dir"/part.* /tmp/parts/ || exit 1
[ "$verb" = stash ] && { ls -la /tmp/parts; nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader; exit 0; }
budget=${3:-500}
start=$SECONDS
if [ ! -d /tmp/site ]; then
    cat /tmp/parts/part.* | xz -d -T0 | tar -C /tmp -xf - || exit 1
fi
# The wheel's compiled extension with this tree's Python modules: the bench runs the code under review.
cp -r crates/rse-py/python/rse/. /tmp/site/rse/
export PYTHONPATH=/tmp/site PYTHONUNBUFFERED=1 MUJOCO_GL=disable
python3 -c "import torch, warp, mujoco, mujoco_warp, mjlab, rse; print('torch', torch.__version__, 'warp', warp.__version__, 'mujoco', mujoco.__version__, 'rse', rse.__version__, torch.cuda.get_device_name(0))" 2>&1 | tail -2
echo "installed in $((SECONDS - start)) s"
left() { echo $((budget - (SECONDS - start))); }
# The first env build compiles MuJoCo Warp's kernels cold (282 s on an H200, 2026-11-28); later builds reuse Warp's cache.
timeout $(( $(left) - 100 )) python3 bench/mjlab_tasks.py --device cuda:0 --num-envs 4096 --steps 50 --rounds 5 --episode-s 1 20 2>&1 \
    | grep -v "^Module \|^Warp \|^  \|^Could not find git\|^#####\|Learning iteration\|^Episode_\|^ Curriculum\|^----" | tee "$OUT/bench_4096.log"
echo "bench ended after $((SECONDS - start)) s"
[ "$(left)" -gt 30 ] && timeout $(( $(left) - 5 )) python3 bench/mjlab_tasks.py --device cuda:0 --num-envs 16384 --memory-only --episode-s 1 2>&1 \
    | grep -v "^Module \|^Warp " | tee "$OUT/memory_16384.log"
echo "all ended after $((SECONDS - start)) s"
