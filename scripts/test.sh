#!/usr/bin/env bash
# Runs every test of the project, from a fresh clone, installing what it needs.
# This is the README's test command (`make test`) and what CI runs.
set -euo pipefail
cd "$(dirname "$0")/.."

say() { printf '\n== [%d s] %s\n' "$SECONDS" "$*" >&2; }

if ! command -v cargo >/dev/null; then
    echo "scripts/test.sh: needs Rust: install rustup (https://rustup.rs), then rerun" >&2
    exit 2
fi
if [ "${CI:-}" = "true" ]; then
    export CARGO_INCREMENTAL=0  # CI builds once from clean: incremental state is waste
fi

# Debian packages the tests need: libsdformat (`ign sdf -k`, and
# tests/sdf_check built against it), gz-physics 5 with its DART and Bullet
# engines (tests/gz_physics/harness.cc: Gazebo's own physics on our worlds)
# and Chromium (the editor's browser tests; Playwright drives it, never
# downloads one). Installed only when missing.
apt_packages=()
command -v ign >/dev/null || apt_packages+=(ignition-tools)
pkg-config --exists sdformat12 2>/dev/null || apt_packages+=(libsdformat-dev pkg-config)
pkg-config --exists ignition-physics5 ignition-common4 2>/dev/null \
    && compgen -G "/usr/lib/*/ign-physics-5/engine-plugins/libignition-physics-dartsim-plugin.so" >/dev/null \
    && compgen -G "/usr/lib/*/ign-physics-5/engine-plugins/libignition-physics-bullet-plugin.so" >/dev/null \
    || apt_packages+=(libignition-physics-dev libignition-physics5-dartsim-plugin5
        libignition-physics5-bullet-plugin5 libignition-common-dev)
command -v g++ >/dev/null || apt_packages+=(g++)
command -v chromium >/dev/null || apt_packages+=(chromium)  # the editor's browser tests
# Installed in the background while the Rust checks build (nothing before
# the Python tests needs them); waited for, and its log shown on failure,
# before those.
apt_pid=""
apt_log=$(mktemp)
if [ ${#apt_packages[@]} -gt 0 ]; then
    say "installing ${apt_packages[*]} (Debian, in the background)"
    sudo=""
    [ "$(id -u)" = 0 ] || sudo="sudo"
    (
        $sudo apt-get update -q
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q "${apt_packages[@]}"
    ) >"$apt_log" 2>&1 &
    apt_pid=$!
fi

log=$(mktemp)
pip_log=$(mktemp)
machete_log=$(mktemp)
fuzz_log=$(mktemp)
# A run that stops early stops what it started in the background too (a
# venv half made is remade: scripts/cached_venv.sh marks the ready ones),
# but apt, which is left to finish: a dpkg cut off needs repairing.
# Each runs in a process group of its own (setsid), killed whole.
background=()
stop_background() {
    local pid
    for pid in "${background[@]}"; do
        kill -- "-$pid" 2>/dev/null || true
    done
}
trap 'stop_background; rm -f "$log" "$apt_log" "$pip_log" "$machete_log" "$fuzz_log"' EXIT

# The Python test dependencies download from the start, beside the Rust
# work, into venvs kept outside the clone and keyed by their pins
# (scripts/venvs.sh): a fresh clone on this machine reuses them. MJX pins
# its own MuJoCo (3.17; .venv has 4.0): rse.mjx's tests get their own venv.
setsid scripts/venvs.sh test >"$pip_log" 2>&1 &
pip_pid=$!
background+=("$pip_pid")

# cargo-machete is built once per machine into the cache, beside clippy
# (which leaves a core idle while it links and waits on single crates).
machete_root=${XDG_CACHE_HOME:-$HOME/.cache}/rse/cargo-machete-0.9.2
machete_pid=""
if [ ! -x "$machete_root/bin/cargo-machete" ]; then
    setsid cargo install --quiet --locked cargo-machete --version 0.9.2 --root "$machete_root" >"$machete_log" 2>&1 &
    machete_pid=$!
    background+=("$machete_pid")
fi

say "format"
cargo fmt --all --check

say "lint (clippy, warnings are errors; also the build without physics)"
cargo clippy --workspace --all-targets --locked -- -D warnings
cargo clippy -p rse-cli -p rse-py --no-default-features --locked -- -D warnings

say "docs (warnings are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked --quiet

say "unused dependencies (cargo-machete)"
if [ -n "$machete_pid" ]; then
    wait "$machete_pid" || { cat "$machete_log" >&2; echo "scripts/test.sh: cargo install cargo-machete failed" >&2; exit 1; }
fi
"$machete_root/bin/cargo-machete"

# The fuzz targets (their own workspace, target and flags: nothing to
# share) build and run seeded beside the Rust tests, filling the cores
# their links and single-threaded tests leave idle; their report is
# shown, and waited for, after them.
FUZZ_MODE=seeded setsid scripts/fuzz.sh >"$fuzz_log" 2>&1 &
fuzz_pid=$!
background+=("$fuzz_pid")

# One build for every Rust test: release, the profile the command line's
# tests need (whole batches, checks and physics, a fifth of the time of a
# debug build), and the one the Python package, the wheel (the same
# dependencies, held so by the workspace-hack crate) and `make demo` use.
# The debug build it replaces cost more to build and to run than the
# release test binaries do (docs/testing.md, "The test run's time").
say "Rust tests: every crate, the command line's included (one release build)"
cargo test --release --workspace --locked -- --include-ignored 2>&1 | tee "$log"

say "fuzzing: every target, seeded and reproducible (scripts/fuzz.sh, run beside the Rust tests; kept inputs replay in them; make fuzz explores)"
fuzz_status=0
wait "$fuzz_pid" || fuzz_status=$?
cat "$fuzz_log"
[ "$fuzz_status" = 0 ] || { echo "scripts/test.sh: fuzzing failed" >&2; exit 1; }

say "Python: the rse package, and third-party readers (trimesh, manifold3d, pygltflib, PyBullet, MuJoCo, MuJoCo Warp, MJX, usd-core; libsdformat; gz-physics)"
wait "$pip_pid" || { cat "$pip_log" >&2; echo "scripts/test.sh: pip install -r tests/requirements.txt failed" >&2; exit 1; }
if [ -n "$apt_pid" ]; then
    wait "$apt_pid" || { cat "$apt_log" >&2; echo "scripts/test.sh: apt-get install failed" >&2; exit 1; }
fi
say "the Python package's lint and types (ruff, mypy; crates/rse-py/pyproject.toml)"
scripts/lint-python.sh
say "the Python package (pip install ./crates/rse-py: maturin, release build)"
# The distribution was named `rse` before it became `rse-gen`: an old venv's
# copy would share the `rse/` folder with the new one.
if .venv/bin/python -m pip show --quiet rse >/dev/null 2>&1; then
    .venv/bin/python -m pip uninstall --quiet --yes rse
fi
rm -rf target/py-wheel
.venv/bin/python -m pip wheel --quiet --disable-pip-version-check --no-deps -w target/py-wheel ./crates/rse-py
for venv in .venv .venv-mjx; do
    $venv/bin/python -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/py-wheel/rse_gen-*.whl
done
cargo build --release --locked --quiet -p rse-cli  # built by the tests above: a no-op unless run alone
# The binary under test is a copy: tests that run cargo or maturin
# themselves (`make demo`, `make wheel`) may relink target/release/rse-gen,
# and a test on another worker once found it missing for that instant.
mkdir -p target/test-bin
cp target/release/rse-gen target/test-bin/rse-gen
say "pytest (tests/python, on every core)"
RSE_GEN="$PWD/target/test-bin/rse-gen" RSE_GEN_RELEASE="$PWD/target/test-bin/rse-gen" \
    .venv/bin/python -m pytest -n "${PYTEST_JOBS:-auto}" --durations=15 2>&1 | tee -a "$log"

say "pytest (tests/mjx: rse.mjx inside MJX, in .venv-mjx)"
JAX_PLATFORMS=cpu .venv-mjx/bin/python -m pytest tests/mjx 2>&1 | tee -a "$log"

say "the README's main command"
rm -rf target/readme-demo
make --no-print-directory demo OUT=target/readme-demo AMOUNT=2
for f in target/readme-demo/world_0000/heightmap.csv target/readme-demo/world_0001/preview.png \
    target/readme-demo/world_0001/gazebo/rse.world target/readme-demo/world_0001/mujoco/rse.xml; do
    [ -s "$f" ] || { echo "make demo did not write $f" >&2; exit 1; }
done

say "done"
# One closing line for the whole run: cargo's test binaries and pytest.
scripts/count_tests.sh "$log"
