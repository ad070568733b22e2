"""Shared fixtures: the real rse-gen binary and the sample schemes."""

import os
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
SCHEMES = REPO / "schemes"

# The editors the tests start keep their drafts and last ports in a folder
# of this run's, not the user's (~/.local/state/rse).
os.environ.setdefault("RSE_STATE_DIR", tempfile.mkdtemp(prefix="rse-test-state-"))


def rse_gen_path() -> Path:
    """The binary under test: $RSE_GEN, else the workspace's debug build."""
    path = Path(os.environ.get("RSE_GEN", REPO / "target" / "debug" / "rse-gen")).resolve()
    if not path.exists():
        pytest.fail(f"{path} does not exist: run `cargo build -p rse-cli` (make test does)")
    return path


def rse_gen_release_path() -> Path:
    """The optimised binary ($RSE_GEN_RELEASE, else target/release/rse-gen),
    for tests that time what users run."""
    path = Path(os.environ.get("RSE_GEN_RELEASE", REPO / "target" / "release" / "rse-gen")).resolve()
    if not path.exists():
        pytest.fail(f"{path} does not exist: run `cargo build --release -p rse-cli` (make test does)")
    return path


def run(*args: str) -> str:
    """Runs rse-gen, failing the test with its stderr when it fails."""
    done = subprocess.run([str(rse_gen_path()), *args], capture_output=True, text=True, cwd=REPO)
    assert done.returncode == 0, f"rse-gen {' '.join(args)}: {done.stderr}"
    return done.stdout


def heights(scheme: Path, seed: int = 0, index: int = 0, difficulty: float = 1.0) -> np.ndarray:
    """The heightmap in steps, shape (ny, nx), a[y, x]."""
    text = run(
        "heightmap", str(scheme), "--seed", str(seed), "--index", str(index), "--difficulty", repr(difficulty)
    )
    return np.array([[int(v) for v in line.split(",")] for line in text.splitlines()])


@pytest.fixture
def out(tmp_path: Path) -> Path:
    return tmp_path


@pytest.fixture
def page():
    """A page in Debian's headless Chromium, for the editor's browser tests
    (Playwright is imported here only: `make test-quick` has no browser)."""
    from editor_harness import chromium_page

    with chromium_page() as page:
        yield page


@pytest.fixture
def editor(tmp_path: Path):
    """A running `rse-gen edit` (release, as users run it) on a small
    scheme, `start.csv` in its own folder; yields (url, folder). A test
    module needing another scheme defines its own `editor`."""
    from editor_harness import running_editor

    scheme = tmp_path / "start.csv"
    scheme.write_text("# size: 20x16\ntype,height\nrandom,1\n")
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as url:
        yield url, tmp_path


def units(scheme: Path) -> dict:
    """The scheme's block_size, step_height and base (metres), with defaults."""
    found = {"block_size": 0.1, "step_height": 0.1, "base": 0.0}
    for line in scheme.read_text().splitlines():
        key, _, value = line.lstrip("# ").partition(":")
        if line.startswith("#") and key.strip() in found:
            found[key.strip()] = float(value)
    return found


def wedges_volume(terrain) -> float:
    """The volume of `terrain`'s ramps' wedges (`rse.Terrain`): shells of
    their own in the single mesh, each from the ground to its plane."""
    s, step, base = terrain.block_size, terrain.step_height, terrain.base
    total = 0.0
    for ramp in terrain.ramps:
        if ramp["rise"] > 0:
            x0, y0, x1, y1 = ramp["cells"]
            total += (x1 - x0 + 1) * (y1 - y0 + 1) * s * s * (base + ramp["rise"] * step / 2)
    return total


def ramps_top(terrain) -> float:
    """The highest top of `terrain`'s ramps (0 without any)."""
    return max(
        (terrain.base + r["rise"] * terrain.step_height for r in terrain.ramps if r["rise"] > 0),
        default=0.0,
    )
