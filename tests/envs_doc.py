"""Runs the example of docs/envs.md tagged for one framework (a
```python <tag> block) as a user pasting it would: a fresh Python, from a
folder holding the samples (schemes/). Shared by the framework tests that
each run in their own venv (tests/mjx, tests/frameworks, tests/genesis,
tests/isaaclab3)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def run_example(tag: str, folder: Path) -> None:
    page = (REPO / "docs" / "envs.md").read_text()
    blocks = re.findall(rf"^```python {tag}\n(.*?)^```", page, flags=re.S | re.M)
    assert len(blocks) == 1, f"docs/envs.md has {len(blocks)} ```python {tag} blocks"
    (folder / "schemes").symlink_to(REPO / "schemes")
    (folder / "example.py").write_text(blocks[0])
    done = subprocess.run([sys.executable, "example.py"], cwd=folder, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-3000:]
