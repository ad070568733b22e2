"""Batches that cannot write: `rse-gen batch` on a full disk (a clear
message, exit 2, no half-written world), and `rse.write_worlds` on a shard
another live run holds (`rse.ShardBusyError`)."""

import subprocess
import sys
import time
from pathlib import Path

import pytest
import rse
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


def test_a_shard_another_run_holds_is_a_shard_busy_error(tmp_path: Path) -> None:
    # A run holding shard 0 of 1 (a million worlds: it is still writing when
    # the second call comes); once it has placed a world, it holds the lock.
    out = tmp_path / "worlds"
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "import rse, sys; rse.write_worlds(rse.Scheme.load(sys.argv[1]), sys.argv[2], amount=10**6, targets='obj', jobs=1)",
            str(SCHEMES / "wall.csv"),
            str(out),
        ]
    )
    try:
        deadline = time.monotonic() + 60
        while not (out.is_dir() and any(not p.name.startswith(".") for p in out.iterdir())):
            assert holder.poll() is None, "the holding run ended early"
            assert time.monotonic() < deadline, "the holding run placed no world in 60 s"
            time.sleep(0.05)
        with pytest.raises(rse.ShardBusyError, match="another rse-gen batch is writing shard 0/1") as busy:
            rse.write_worlds(rse.Scheme.load(SCHEMES / "wall.csv"), out, amount=10**6, targets="obj", jobs=1)
        # Code that caught the ValueError it was before still does.
        assert isinstance(busy.value, ValueError)
        assert holder.poll() is None, "the holding run must still be writing"
    finally:
        holder.kill()
        holder.wait()
