"""mjlab's ``train`` command line run in the test's own process: for the
cases that end while it parses (a refused flag, ``--help``), where a
process each would spend its time importing torch."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

TRAIN = Path(sys.executable).parent / "train"
TASK = "Rse-Velocity-Rough-Unitree-Go1"


def train_main(capsys: pytest.CaptureFixture[str], *flags: str) -> subprocess.CompletedProcess[str]:
    """mjlab's ``train`` entry point run in this process with ``flags``,
    its exit status and output as a finished process's."""
    from unittest import mock

    from mjlab.scripts import train as train_script

    argv = [str(TRAIN), TASK, *flags]
    with mock.patch.object(sys, "argv", argv), pytest.raises(SystemExit) as stopped:
        train_script.main()
    out = capsys.readouterr()
    code = stopped.value.code if isinstance(stopped.value.code, int) else 1
    return subprocess.CompletedProcess(argv, code, out.out, out.err)
