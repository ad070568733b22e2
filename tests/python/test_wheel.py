"""The wheel as a user installs it (issue 15, item 8): built with the
README's one command, installed into a clean venv, it brings `import rse`
and the `rse-gen` command, which writes the same worlds as the binary."""

import subprocess
import sys
import zipfile
from pathlib import Path

import rse
from conftest import REPO, SCHEMES, rse_gen_path


def test_the_wheel_installs_rse_and_the_rse_gen_command(tmp_path: Path) -> None:
    built = subprocess.run(["make", "--no-print-directory", "wheel"], cwd=REPO, capture_output=True, text=True)
    assert built.returncode == 0, built.stderr
    wheel = REPO / "dist" / f"rse_gen-{rse.__version__}-cp39-abi3-linux_x86_64.whl"
    assert wheel.exists(), built.stdout
    with zipfile.ZipFile(wheel) as z:
        metadata = z.read(f"rse_gen-{rse.__version__}.dist-info/METADATA").decode()
        entry_points = z.read(f"rse_gen-{rse.__version__}.dist-info/entry_points.txt").decode()
    assert "Name: rse-gen\n" in metadata
    assert "rse-gen=rse._cli:main" in entry_points.replace(" ", "")

    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    pip = subprocess.run(
        [str(venv / "bin" / "pip"), "install", "--quiet", "--disable-pip-version-check", str(wheel)],
        capture_output=True,
        text=True,
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
    bad = subprocess.run([str(command), "heightmap", str(tmp_path / "missing.csv")], capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.startswith("rse-gen: cannot read ") and "missing.csv" in bad.stderr
    usage = subprocess.run([str(command), "no-such-command"], capture_output=True, text=True)
    assert usage.returncode == 2 and "unrecognized subcommand" in usage.stderr


def test_rse_gen_and_the_wheel_share_their_release_build() -> None:
    """Every package both graphs hold gets the same features (rse-cli's
    feature-unifying dependencies), so `make test` compiles the physics
    stack once in release; a new dependency of the extension that turns on
    another feature breaks this, and names the package."""

    def features(package: str) -> dict[str, str]:
        tree = subprocess.run(
            ["cargo", "tree", "-q", "--locked", "-p", package, "-e", "normal,build", "--prefix", "none",
             "--format", "{p} [{f}]"],
            cwd=REPO, capture_output=True, text=True, check=True,
        ).stdout
        lines = {line.removesuffix(" (*)") for line in tree.splitlines() if line.strip()}
        return {line.split(" [")[0]: line for line in lines}

    cli, wheel = features("rse-cli"), features("rse-py")
    shared = sorted(set(cli) & set(wheel) - {p for p in cli if p.startswith("rse-cli ")})
    assert len(shared) > 50, shared
    differ = [(cli[p], wheel[p]) for p in shared if cli[p] != wheel[p]]
    assert not differ, f"add these features to rse-cli's feature-unifying dependencies: {differ}"
