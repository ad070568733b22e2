#!/usr/bin/env bash
# The sizes of the two wheels: `rse-gen` (the extension) with the physics
# smoke test (the default) and without it (`--no-default-features`), the
# extension inside each, and `rse-gen-cli` (the command line's binary)
# (docs/python.md, "Wheels").
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x target/wheel-venv/bin/pip ] || python3 -m venv target/wheel-venv
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for variant in physics no-physics; do
    args=""
    [ "$variant" = no-physics ] && args="--no-default-features"
    MATURIN_PEP517_ARGS="$args" target/wheel-venv/bin/pip wheel --quiet --disable-pip-version-check \
        --no-deps -w "$out/$variant" ./crates/rse-py
    wheel=$(ls "$out/$variant"/*.whl)
    extension=$(python3 -c 'import sys, zipfile
z = zipfile.ZipFile(sys.argv[1])
print(sum(i.file_size for i in z.infolist() if "/_rse" in i.filename and i.filename.endswith(".so")))' "$wheel")
    printf '%-10s  wheel %9d bytes  extension %9d bytes\n' "$variant" "$(stat -c %s "$wheel")" "$extension"
done
target/wheel-venv/bin/pip wheel --quiet --disable-pip-version-check --no-deps -w "$out/cli" ./crates/rse-cli
wheel=$(ls "$out/cli"/*.whl)
binary=$(python3 -c 'import sys, zipfile
z = zipfile.ZipFile(sys.argv[1])
print(sum(i.file_size for i in z.infolist() if i.filename.endswith("/scripts/rse-gen")))' "$wheel")
printf '%-10s  wheel %9d bytes  binary    %9d bytes
' "cli" "$(stat -c %s "$wheel")" "$binary"
