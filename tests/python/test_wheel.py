"""The wheels as a user installs them: built with the README's one command
(`make wheel`), installed into a clean venv, `rse-gen` brings `import rse`
and depends on `rse-gen-cli`, the `rse-gen` command as a plain binary
wheel, which writes the same worlds as the binary. The extension links no
part of the command line."""

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
import rse
from conftest import REPO, SCHEMES, rse_gen_path

# Needs what only `make test` installs (Debian packages, a browser, or
# the wheels' build): not in `make test-quick`.
pytestmark = pytest.mark.thirdparty


def test_the_wheel_installs_rse_and_the_rse_gen_command(tmp_path: Path) -> None:
    built = subprocess.run(["make", "--no-print-directory", "wheel"], cwd=REPO, capture_output=True, text=True)
    assert built.returncode == 0, built.stderr
    # manylinux2014: any glibc from 2.17, what a package index takes.
    tags = "manylinux2014_x86_64.manylinux_2_17_x86_64"
    wheel = REPO / "dist" / f"rse_gen-{rse.__version__}-cp39-abi3-{tags}.whl"
    cli_wheel = REPO / "dist" / f"rse_gen_cli-{rse.__version__}-py3-none-{tags}.whl"
    assert wheel.exists() and cli_wheel.exists(), built.stdout + built.stderr
    with zipfile.ZipFile(wheel) as z:
        metadata = z.read(f"rse_gen-{rse.__version__}.dist-info/METADATA").decode()
        # No console script (the command is rse-gen-cli's); one plug-in:
        # mjlab imports rse's task registrations through its group.
        entry_points = z.read(f"rse_gen-{rse.__version__}.dist-info/entry_points.txt").decode()
        assert "console_scripts" not in entry_points, entry_points
        assert entry_points.replace(" ", "").splitlines()[:2] == ["[mjlab.tasks]", "rse=rse.mjlab_tasks"], entry_points
    assert "Name: rse-gen\n" in metadata
    assert f"Requires-Dist: rse-gen-cli=={rse.__version__}\n" in metadata, "the pin follows the version"
    with zipfile.ZipFile(cli_wheel) as z:
        scripts = [name for name in z.namelist() if ".data/scripts/" in name]
        assert scripts == [f"rse_gen_cli-{rse.__version__}.data/scripts/rse-gen"], z.namelist()
        assert z.read(scripts[0])[:4] == b"\x7fELF", "a plain binary, no Python launcher"

    published_from_an_index(tmp_path / "index", [wheel, cli_wheel])

    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    # No Rust toolchain on the PATH: the wheels need none.
    no_rust = ":".join(p for p in os.environ.get("PATH", "").split(":") if not (Path(p) / "cargo").exists())
    pip = subprocess.run(
        [str(venv / "bin" / "pip"), "install", "--quiet", "--disable-pip-version-check", str(wheel), str(cli_wheel)],
        capture_output=True,
        text=True,
        env={**os.environ, "PATH": no_rust},
    )
    assert pip.returncode == 0, pip.stderr

    python = venv / "bin" / "python"
    imported = subprocess.run(
        [str(python), "-c", "import rse; print(rse.__version__, rse.__file__)"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert imported.returncode == 0, imported.stderr
    version, where = imported.stdout.split()
    assert version == rse.__version__ and where.startswith(str(venv)), "the venv's own copy, not the repository's"

    command = venv / "bin" / "rse-gen"
    shown = subprocess.run([str(command), "--version"], capture_output=True, text=True)
    assert shown.returncode == 0 and shown.stdout == f"rse-gen {rse.__version__}\n", shown

    # The command is the whole command line: same worlds, same exit statuses.
    scheme = str(SCHEMES / "wall.csv")
    for tool, out in [(command, tmp_path / "wheel"), (rse_gen_path(), tmp_path / "binary")]:
        done = subprocess.run(
            [str(tool), "batch", scheme, "-o", str(out), "--amount", "2", "--target", "mujoco,urdf"],
            capture_output=True,
            text=True,
        )
        assert done.returncode == 0, done.stderr
    for f in sorted((tmp_path / "binary").rglob("*")):
        if f.is_file():
            assert f.read_bytes() == (tmp_path / "wheel" / f.relative_to(tmp_path / "binary")).read_bytes(), f
    # The built wheels carry the physics smoke test.
    physics = subprocess.run(
        [str(python), "-c", f"import rse; print(rse.check({str(tmp_path / 'wheel')!r}, physics=True).ok)"],
        capture_output=True, text=True, cwd=tmp_path,
    )
    assert physics.returncode == 0 and physics.stdout.strip() == "True", physics.stderr[-2000:]
    bad = subprocess.run([str(command), "heightmap", str(tmp_path / "missing.csv")], capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.startswith("rse-gen: cannot read ") and "missing.csv" in bad.stderr
    usage = subprocess.run([str(command), "no-such-command"], capture_output=True, text=True)
    assert usage.returncode == 2 and "unrecognized subcommand" in usage.stderr


def published_from_an_index(folder: Path, wheels: list[Path]) -> None:
    """`make publish` uploads the two wheels in one step to a package index
    (a local pypiserver, as PyPI takes them through maturin), which then
    serves them byte for byte; a second run skips what is there."""
    import socket
    import time
    import urllib.request

    folder.mkdir()
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    server = subprocess.Popen(
        [str(Path(sys.executable).parent / "pypi-server"), "run", "-i", "127.0.0.1", "-p", str(port), "-a", ".", "-P", ".", str(folder)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    url = f"http://127.0.0.1:{port}/"
    try:
        for _ in range(100):
            try:
                urllib.request.urlopen(url, timeout=1).close()
                break
            except OSError:
                time.sleep(0.1)
        env = {**os.environ, "MATURIN_REPOSITORY_URL": url, "MATURIN_USERNAME": "rse", "MATURIN_PASSWORD": "rse"}
        for _ in range(2):
            done = subprocess.run(["make", "--no-print-directory", "publish"], cwd=REPO, capture_output=True, text=True, env=env)
            assert done.returncode == 0, done.stdout + done.stderr
        got = folder.parent / "downloaded"
        names = [f"rse-gen=={rse.__version__}", f"rse-gen-cli=={rse.__version__}"]
        pip = subprocess.run(
            [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps", "--disable-pip-version-check", "--index-url", f"{url}simple/", "-d", str(got), *names],
            capture_output=True,
            text=True,
        )
        assert pip.returncode == 0, pip.stderr
        for wheel in wheels:
            assert (got / wheel.name).read_bytes() == wheel.read_bytes(), wheel.name
    finally:
        server.terminate()
        server.wait(timeout=10)


def cargo_features(package: str) -> dict[str, str]:
    """Each package of `package`'s build graph, with the features it gets."""
    tree = subprocess.run(
        ["cargo", "tree", "-q", "--locked", "-p", package, "-e", "normal,build", "--prefix", "none",
         "--format", "{p} [{f}]"],
        cwd=REPO, capture_output=True, text=True, check=True,
    ).stdout
    lines = {line.removesuffix(" (*)") for line in tree.splitlines() if line.strip()}
    return {line.split(" [")[0]: line for line in lines}


def test_the_extension_links_no_command_line() -> None:
    """`import rse` loads no argument parser, HTTP server, signal handler or
    editor page: those are the binary's (ARCHITECTURE.md)."""
    names = {package.split()[0] for package in cargo_features("rse-py")}
    assert {"rse-core", "rse-world", "rse-verify", "rse-physics", "pyo3"} <= names, names
    linked = names & {"rse-cli", "rse-edit", "clap", "hyper", "tokio", "ctrlc", "signal-hook", "indicatif"}
    assert not linked, linked


def test_rse_gen_and_the_wheel_share_their_release_build() -> None:
    """Every package both graphs hold gets the same features (the
    workspace-hack crate, generated by cargo-hakari, unifies them), so
    `make test` compiles the physics stack once in release; a new
    dependency that turns on another feature breaks this, and names the
    package."""
    cli, wheel = cargo_features("rse-cli"), cargo_features("rse-py")
    shared = sorted(set(cli) & set(wheel) - {p for p in cli if p.startswith("rse-cli ")})
    assert len(shared) > 50, shared
    differ = [(cli[p], wheel[p]) for p in shared if cli[p] != wheel[p]]
    assert not differ, f"run `cargo hakari generate` (docs/development.md): {differ}"
