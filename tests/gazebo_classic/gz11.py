"""Gazebo classic 11 in a Debian bullseye chroot (the last Debian release
that ships it): built once with debootstrap and apt, then `gzserver` and
the `gz` tool run inside it on world folders copied in. Needs root (chroot
and mount). Used by tests/gazebo_classic/test_gzserver.py and
bench/gazebo_classic_contacts.py."""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import socket
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
# Kept under target/ (ignored, shared by every run on this clone): ~1.3 GB.
DEFAULT_ROOT = REPO / "target" / "gazebo11-root"
MIRROR = "http://deb.debian.org/debian"
SUITE = "bullseye"

# What gzserver prints here whatever the world: rendering is off without X,
# audio without ALSA, and the contacts topic (published every step) drops
# messages when its transport thread falls behind on a busy machine —
# Gazebo's own worlds/empty.world prints that too on this 2-core machine
# under load, and none of these is about the world's files, so they are not
# judged. Everything else Gazebo or libsdformat calls an error or a warning
# fails the load.
ENVIRONMENT_NOISE = (
    re.compile(r"\[RenderEngine\.cc:\d+\] (Can't open display|Unable to create X window|Cannot initialize render engine)"),
    re.compile(r"\[OpenAL\.cc:\d+\] Unable to open audio device"),
    re.compile(r"\[Publisher\.cc:\d+\] Queue limit reached for topic /gazebo/[^/]+/physics/contacts,"),
)
PROBLEM = re.compile(r"\[(Err|Wrn)\]|\b(Error|Warning)\b")
ANSI = re.compile(r"\x1b\[[0-9;]*m")


def ensure_root(root: Path = DEFAULT_ROOT) -> Path:
    """A bullseye chroot with Gazebo 11 at `root`, made if it is not there
    (debootstrap --variant=minbase, then apt-get install gazebo: about 2
    minutes and 1.3 GB here). A half-made one is made again."""
    done = root / ".rse-gazebo11-ready"
    if done.exists():
        return root
    if root.exists():
        shutil.rmtree(root)
    root.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run(["debootstrap", "--variant=minbase", SUITE, str(root), MIRROR], check=True)
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    subprocess.run(["chroot", str(root), "apt-get", "update", "-q"], check=True, env=env)
    subprocess.run(
        ["chroot", str(root), "apt-get", "install", "-y", "-q", "--no-install-recommends", "gazebo"],
        check=True,
        env=env,
    )
    # Gazebo's transport resolves `localhost`; a minbase chroot has no hosts file.
    (root / "etc" / "hosts").write_text("127.0.0.1 localhost\n::1 localhost\n")
    done.write_text(gazebo_version(root) + "\n")
    return root


def gazebo_version(root: Path) -> str:
    """The Debian version of the chroot's gazebo package."""
    return subprocess.run(
        ["chroot", str(root), "dpkg-query", "-W", "-f", "${Version}", "gazebo"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextlib.contextmanager
def staged(root: Path, folder: Path) -> Iterator[str]:
    """`folder` copied into the chroot; yields its path as the chroot sees it."""
    work = root / "work"
    work.mkdir(exist_ok=True)
    inside = Path(tempfile.mkdtemp(dir=work))
    try:
        shutil.copytree(folder, inside / folder.name)
        yield "/" + str((inside / folder.name).relative_to(root))
    finally:
        shutil.rmtree(inside)


class Gzserver:
    """A `gzserver --verbose` on one world in the chroot, on a master port of
    its own, run in the world's folder (or `cwd`: Gazebo also finds models
    there) with `GAZEBO_MODEL_PATH` the world's folder (or `model_path`);
    stopped (and its log kept in `.log`) when the block ends."""

    def __init__(
        self,
        root: Path,
        world_dir: str,
        world_file: str,
        model_path: str | None = None,
        record: bool = False,
        cwd: str | None = None,
        extra: tuple[str, ...] = (),
    ) -> None:
        self.root = root
        # Gazebo's state log (`-r`): on stop, the world as Gazebo loaded it.
        self.record = f"{world_dir}/.gz11-record" if record else None
        self.port = free_port()
        env = [
            "PATH=/usr/sbin:/usr/bin:/sbin:/bin",
            "HOME=/root",
            f"GAZEBO_MODEL_PATH={world_dir if model_path is None else model_path}",
            "GAZEBO_IP=127.0.0.1",
            f"GAZEBO_MASTER_URI=http://127.0.0.1:{self.port}",
            # No online model database: everything a world names is in it.
            "GAZEBO_MODEL_DATABASE_URI=",
        ]
        recording = ["-r", "--record_encoding", "txt", "--record_path", self.record] if self.record else []
        args = ["gzserver", "--verbose", *recording, *extra, world_file]
        # To a file, not a pipe: nobody reads a pipe while it runs, and a
        # full one would stop gzserver mid-write.
        self.output = tempfile.TemporaryFile(mode="w+")
        self.process = subprocess.Popen(
            ["chroot", str(root), "env", "-i", *env, "sh", "-c", 'cd "$0" && exec "$@"', cwd or world_dir, *args],
            stdout=self.output,
            stderr=subprocess.STDOUT,
            text=True,
        )
        self.log = ""

    def stop(self) -> str:
        """Stops the server (SIGINT, as Ctrl+C); its whole output, colours off."""
        if self.output.closed:
            return self.log
        if self.process.poll() is None:
            self.process.send_signal(2)
            try:
                self.process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.output.seek(0)
        self.log = ANSI.sub("", self.output.read())
        self.output.close()
        return self.log

    def recorded(self) -> str:
        """After `stop`: the state log, which opens with the world as Gazebo
        loaded it (every model included, every collision). Empty if none."""
        if self.record is None:
            return ""
        found = sorted((self.root / self.record.lstrip("/")).rglob("state.log"))
        return found[0].read_text() if found else ""

    def __enter__(self) -> Gzserver:
        return self

    def __exit__(self, *_: object) -> None:
        self.stop()


def problems(log: str) -> list[str]:
    """The lines of a gzserver log that are errors or warnings about what it
    loaded (the environment's own, `ENVIRONMENT_NOISE`, left out)."""
    return [
        line
        for line in log.splitlines()
        if PROBLEM.search(line) and not any(noise.search(line) for noise in ENVIRONMENT_NOISE)
    ]
