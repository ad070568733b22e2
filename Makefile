# Targets named in the README. `make test` is what CI runs.

SCHEME ?= schemes/nist_hill.csv
AMOUNT ?= 5
SEED ?= 0
OUT ?= out
RSE_GEN := target/release/rse-gen

.PHONY: test lint bench demo build

## Run every test (format, lint, docs, Rust unit/property/golden/CLI tests, the README command).
test:
	scripts/test.sh

## fmt, clippy -D warnings, rustdoc -D warnings.
lint:
	cargo fmt --all --check
	cargo clippy --workspace --all-targets --locked -- -D warnings
	RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked --quiet

## Criterion benchmarks of the generator (figures in target/criterion).
bench:
	cargo bench -p rse-core --bench generate

build:
	cargo build --release --locked -p rse-cli

## Generate AMOUNT worlds of SCHEME into OUT/world_NNNN/ (heightmap.csv, preview.png).
demo: build
	@for i in $$(seq 0 $$(( $(AMOUNT) - 1 ))); do \
		dir=$(OUT)/$$(printf 'world_%04d' $$i); mkdir -p $$dir; \
		$(RSE_GEN) heightmap $(SCHEME) --seed $(SEED) --index $$i > $$dir/heightmap.csv.tmp && \
		mv $$dir/heightmap.csv.tmp $$dir/heightmap.csv && \
		$(RSE_GEN) preview $(SCHEME) --seed $(SEED) --index $$i -o $$dir/preview.png || exit $$?; \
	done
	@echo "wrote $(AMOUNT) worlds of $(SCHEME) to $(OUT)/"
