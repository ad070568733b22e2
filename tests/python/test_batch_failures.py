"""`rse-gen batch` when the disk is full: a clear message, exit 2, and no
half-written world."""

import subprocess
from pathlib import Path

import pytest
from conftest import SCHEMES, rse_gen_path


@pytest.fixture
def tiny_disk(tmp_path: Path):
    """A 300 KiB tmpfs: room for a few files, not for a world with meshes."""
    mount = tmp_path / "tiny"
    mount.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=300k", "tmpfs", str(mount)], capture_output=True)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {done.stderr.decode().strip()}")
    yield mount
    subprocess.run(["umount", str(mount)], check=True)


def test_a_full_disk_stops_the_batch_with_the_path_and_leaves_no_partial_world(tiny_disk: Path) -> None:
    out = tiny_disk / "out"
    done = subprocess.run(
        [str(rse_gen_path()), "batch", str(SCHEMES / "six_obstacles.csv"), "-o", str(out), "--amount", "4", "--target", "obj,gazebo"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 2
    assert "No space left on device" in done.stderr and str(out) in done.stderr, done.stderr
    assert done.stderr.count("No space left") == 1, done.stderr
    # Whatever was written is whole: no world folder without its manifest,
    # no temporary folder left behind (and no output folder at all when no
    # world was written: a failed command leaves nothing it made).
    for entry in out.iterdir() if out.exists() else []:
        assert not entry.name.startswith("."), entry
        assert (entry / "rse.json").is_file(), entry
