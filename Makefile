# Targets named in the README. `make test` is what CI runs.

SCHEME ?= schemes/nist_hill.csv
AMOUNT ?= 5
SEED ?= 0
OUT ?= out
TARGETS ?= gazebo,webots,mujoco,urdf,usd
RSE_GEN := target/release/rse-gen

.PHONY: test test-quick lint bench bench-robots bench-frameworks demo build fuzz test-frameworks test-cluster test-gazebo-classic wheel publish

## Run every test (format, lint, docs, Rust unit/property/golden/CLI tests, the README command).
test:
	scripts/test.sh

## The edit-test loop (a few minutes warm; no apt, no browser): fmt, the Rust tests but the CLI's, the Python package's own tests.
test-quick:
	scripts/test-quick.sh

## The RL framework adapters inside the frameworks themselves (mjlab, Isaac Lab 2.3 and 3.0, Genesis, Newton, Playground; docs/frameworks.md).
## Heavy (torch, JAX, gigabytes): venvs of their own, kept outside the clone (scripts/venvs.sh); CI runs it after `make test`.
test-frameworks:
	scripts/test-frameworks.sh

## Mass generation on clusters started and stopped by the tests: Slurm, and rse.ray on a two-node Ray cluster (its own venv, .venv-cluster). See docs/guide.md.
test-cluster:
	scripts/test-cluster.sh

## Gazebo classic 11 (gzserver, from a Debian bullseye chroot made once under target/: about 2 min, 1.3 GB here) loading gazebo-classic worlds with no SDF error or warning, and bodies resting on its default collider. Needs root; not in `make test`.
test-gazebo-classic:
	scripts/test-gazebo-classic.sh

## mjlab's Go1 rough task on mjlab's terrain and on rse's (steps/s, a PPO iteration, the height scans), in .venv-frameworks, and a Genesis reset's rewrite, whole map against the reset tiles, in .venv-genesis (make test-frameworks makes both). On a GPU: .venv-frameworks/bin/python bench/mjlab_tasks.py --device cuda --num-envs 4096
bench-frameworks:
	.venv-frameworks/bin/python bench/mjlab_tasks.py
	.venv-genesis/bin/python bench/genesis_sync.py

## Every fuzz target for FUZZ_SECONDS each (default 12), libFuzzer's random seed, a growing corpus (make test runs a seeded, fixed-length pass instead).
fuzz:
	scripts/fuzz.sh

## fmt, clippy -D warnings, rustdoc -D warnings.
lint:
	cargo fmt --all --check
	cargo clippy --workspace --all-targets --locked -- -D warnings
	RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked --quiet

## Benchmarks: generator (criterion), meshes (table), physics, one world's stages, batch throughput beside cp -r, Python, editor round trip.
bench:
	cargo bench -p rse-core --bench generate
	cargo bench -p rse-core --bench mesh
	cargo bench -p rse-core --bench boxes
	cargo bench -p rse-core --bench atlas
	cargo bench -p rse-core --bench env_terrains
	cargo bench -p rse-physics --bench physics
	cargo bench -p rse-world --bench world
	bench/batch.sh
	bench/check.sh
	python3 bench/budget.py
	.venv/bin/python -m pip install --quiet ./crates/rse-py && .venv/bin/python bench/python.py
	.venv/bin/python bench/hfield.py
	.venv/bin/python bench/envs.py
	[ ! -x .venv-mjx/bin/python ] || { .venv-mjx/bin/python -m pip install --quiet --no-deps ./crates/rse-py && .venv-mjx/bin/python bench/envs_mjx.py; }
	.venv/bin/python bench/boxes.py
	.venv/bin/python bench/editor.py

## Robots and dropped bodies in MuJoCo, PyBullet and gz-physics, per collider (~25 min).
bench-robots:
	.venv/bin/python -m pip install --quiet ./crates/rse-py
	.venv/bin/python bench/robots.py
	.venv/bin/python bench/gz_physics.py

build:
	cargo build --release --locked -p rse-cli

## The two wheels into dist/, for machines without Rust (pip install dist/rse_gen-*.whl dist/rse_gen_cli-*.whl): rse-gen (import rse; abi3, one for every Python 3.9+) and rse-gen-cli (the command). manylinux2014 (glibc 2.17+), linked by zig as maturin's own CI action builds them, so they are what a package index takes.
wheel:
	[ -x target/wheel-venv/bin/maturin ] || { python3 -m venv target/wheel-venv && target/wheel-venv/bin/pip install --quiet --disable-pip-version-check maturin==1.16.0 ziglang==0.17.1; }
	rm -f dist/rse_gen-*.whl dist/rse_gen_cli-*.whl
	for crate in rse-py rse-cli; do \
		PATH="$(CURDIR)/target/wheel-venv/bin:$$PATH" target/wheel-venv/bin/maturin build --quiet --release --locked \
			--zig --compatibility manylinux2014 --manifest-path crates/$$crate/Cargo.toml -o dist || exit 1; \
	done
	@ls dist/rse_gen-*.whl dist/rse_gen_cli-*.whl

## Publish, in one step, the two wheels `make wheel` built (dist/): maturin upload to PyPI with the token in MATURIN_PYPI_TOKEN, or to MATURIN_REPOSITORY_URL (MATURIN_USERNAME, MATURIN_PASSWORD); a version already there is skipped, so a rerun after a failure finishes the job.
publish:
	@ls dist/rse_gen-*.whl dist/rse_gen_cli-*.whl >/dev/null 2>&1 || { echo "make publish: no wheels in dist/ (make wheel builds them)" >&2; exit 2; }
	target/wheel-venv/bin/maturin upload --non-interactive --skip-existing dist/rse_gen-*.whl dist/rse_gen_cli-*.whl

## Generate AMOUNT worlds of SCHEME into OUT/world_NNNN/ for TARGETS (rse-gen batch; a rerun resumes).
demo: build
	$(RSE_GEN) batch $(SCHEME) -o $(OUT) --amount $(AMOUNT) --seed $(SEED) --target $(TARGETS)
