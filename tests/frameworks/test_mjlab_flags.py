"""Mistakes on mjlab's ``train`` command line answered at the flag: a
missing scheme file, a bad row, a difficulty past 1, a bad level, a flag
rse's terrain cannot honour — each refused while the command line is
parsed (``EnvTerrainCfg.__post_init__``, which tyro runs), naming the
``--env.scene.terrain.…`` flag (and the file, line and field of a bad row),
exit 2, no traceback, and no scene built. One case runs ``train`` as a
process; the rest run its ``main`` in this one (they end while parsing,
and each process would spend its time importing torch)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from mjlab_cli import train_main

TRAIN = Path(sys.executable).parent / "train"
TASK = "Rse-Velocity-Rough-Unitree-Go1"


def train(cwd: Path, *flags: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(TRAIN), TASK, "--env.scene.num-envs", "2", "--agent.max-iterations", "1", *flags],
        cwd=cwd, capture_output=True, text=True, timeout=600,
        env={**os.environ, "CUDA_VISIBLE_DEVICES": "", "COLUMNS": "200"},
    )


def refused(done: subprocess.CompletedProcess[str]) -> str:
    """The error's words, once the run is known to have stopped at parsing."""
    out = done.stdout + done.stderr
    assert done.returncode == 2, out[-3000:]
    assert "Traceback" not in out, out[-3000:]
    # Nothing was built: no scene, no pool, no log folder.
    assert "Base Environment" not in out and "rse terrains" not in out, out[-3000:]
    return " ".join(out.replace("│", " ").split())


def test_a_missing_scheme_stops_a_train_process_at_the_flag(tmp_path) -> None:
    text = refused(train(tmp_path, "--env.scene.terrain.scheme", "no/such.csv"))
    assert "--env.scene.terrain.scheme no/such.csv: cannot read it" in text, text[-2000:]
    assert not (tmp_path / "logs").exists()


@pytest.mark.parametrize(
    ("flags", "words"),
    [
        (["--env.scene.terrain.difficulty", "1.5"], ["--env.scene.terrain.difficulty 1.5: expected a number from 0 to 1"]),
        (["--env.scene.terrain.oversample", "0"], ["--env.scene.terrain.oversample 0"]),
        (["--env.scene.terrain.spawn-radius", "-1"], ["--env.scene.terrain.spawn-radius -1"]),
        (["--env.scene.terrain.max-init-terrain-level", "10"], ["--env.scene.terrain.max-init-terrain-level 10", "from 0 to 9"]),
        (["--env.scene.terrain.terrain-levels", "1"], ["--env.scene.terrain.terrain-levels 1"]),
    ],
)
def test_a_bad_terrain_flag_is_named_before_anything_is_built(tmp_path, monkeypatch, capsys, flags, words) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("COLUMNS", "200")
    text = refused(train_main(capsys, *flags))
    for w in words:
        assert w in text, text[-2000:]
    assert not (tmp_path / "logs").exists()


def test_a_bad_row_names_the_flag_the_file_the_line_and_the_field(tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("COLUMNS", "200")
    scheme = tmp_path / "steps.csv"
    scheme.write_text("# size: 30x30\ntype,height,angle,x1,y1\npeak,3,45,15,15\npeak,abc,45,15,15\n")
    text = refused(train_main(capsys, "--env.scene.terrain.scheme", str(scheme)))
    assert "--env.scene.terrain.scheme" in text and f"{scheme}:4" in text and "height" in text, text[-2000:]


def test_help_lists_only_terrain_flags_that_work(tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("COLUMNS", "200")
    done = train_main(capsys, "--help")
    assert done.returncode == 0, done.stderr[-2000:]
    for works in ("--env.scene.terrain.scheme", "--env.scene.terrain.seed", "--env.scene.terrain.difficulty",
                  "--env.scene.terrain.terrain-levels", "--env.scene.terrain.max-init-terrain-level"):
        assert works in done.stdout, works
    for fixed in ("--env.scene.terrain.terrain-type", "--env.scene.terrain.terrain-generator",
                  "--env.scene.terrain.env-spacing", "--env.scene.terrain.num-envs", "--env.scene.terrain.scheme-csv",
                  "--env.scene.terrain.init-state", "--env.scene.terrain.geoms", "--env.scene.terrain.debug-vis"):
        assert fixed not in done.stdout, fixed
    # The other way to use rse in mjlab, named where the flags are.
    assert "RseTerrainCfg" in done.stdout
    # Once rse's terrain fixes it, mjlab's generator cannot be asked for.
    assert train_main(capsys, "--env.scene.terrain.terrain-type", "generator").returncode == 2
