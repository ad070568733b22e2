"""The documentation as a newcomer follows it: the README and the user
guide walked top to bottom (`make demo`, then every Python block but the two
that need Isaac Lab or mjlab, in one session, in the folder `make demo`
wrote into), the generated Python API page up to date, and every relative
link of the README and docs/ pointing at a file that exists."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import REPO

README = REPO / "README.md"
GUIDE = REPO / "docs" / "guide.md"
PAGES = [README, REPO / "schemes" / "README.md", REPO / "templates" / "README.md", *sorted((REPO / "docs").rglob("*.md"))]
# Blocks that need a framework this venv does not have (tests/frameworks
# runs them in its own: make test-frameworks), or a cluster (make
# test-cluster runs rse.ray on one).
NEEDS_FRAMEWORK = ("from isaaclab", "from mjlab", "import ray")


def python_blocks(text: str) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def test_the_readme_walk_through_runs_as_written(tmp_path: Path) -> None:
    """`make demo` writes out/ where the user is; the Python blocks then run
    there, in order, sharing their names, as a user pasting them would."""
    (tmp_path / "schemes").symlink_to(REPO / "schemes")
    demo = subprocess.run(
        ["make", "--no-print-directory", "-C", str(REPO), "demo", f"OUT={tmp_path / 'out'}"],
        capture_output=True,
        text=True,
    )
    assert demo.returncode == 0, demo.stderr
    assert len(list((tmp_path / "out").glob("world_*"))) == 5
    text = README.read_text() + GUIDE.read_text()
    blocks = [b for b in python_blocks(text) if not any(f in b for f in NEEDS_FRAMEWORK)]
    assert len(blocks) >= 5
    script = tmp_path / "walk_through.py"
    script.write_text("\n\n".join(f"# --- README/guide block {i}\n{b}" for i, b in enumerate(blocks)))
    done = subprocess.run(
        [sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True, env={**os.environ, "MUJOCO_GL": "egl"}
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert (tmp_path / "worlds" / "world_0099" / "rse.json").exists()
    assert (tmp_path / "episodes" / "world_7" / "mujoco" / "rse.xml").exists()
    assert len(list((tmp_path / "out").glob("world_*"))) == 5, "the demo's worlds untouched"


def test_the_env_terrains_page_runs_as_written(tmp_path: Path) -> None:
    """docs/envs.md: its Python blocks, in order, from a folder with the samples."""
    (tmp_path / "schemes").symlink_to(REPO / "schemes")
    blocks = python_blocks((REPO / "docs" / "envs.md").read_text())
    assert blocks
    script = tmp_path / "envs_page.py"
    script.write_text("\n\n".join(blocks))
    done = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-3000:]


def test_the_python_api_page_is_up_to_date() -> None:
    done = subprocess.run(
        [sys.executable, str(REPO / "scripts" / "python_api_docs.py"), "--check"], capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_relative_links_point_at_files(page: Path) -> None:
    for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", page.read_text()):
        if re.match(r"[a-z]+://", target):
            continue
        assert (page.parent / target).exists(), f"{page.relative_to(REPO)} links to {target}, which is not there"


def test_no_page_or_docstring_cites_the_spec_we_do_not_ship() -> None:
    """SPEC.md is the team's contract, not in the repository: users are
    pointed at docs/ instead."""
    tracked = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    for name in tracked:
        if name.endswith((".md", ".rs", ".py", ".pyi", ".j2", ".toml")) and name != "tests/python/test_docs.py":
            assert "SPEC" not in (REPO / name).read_text(errors="replace"), name


def test_the_module_map_is_generated_from_the_sources() -> None:
    """docs/modules.md names every module with its own first paragraph;
    generated, so a module added, moved or redocumented must regenerate it."""
    done = subprocess.run([sys.executable, str(REPO / "scripts" / "modules_map.py"), "--check"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_architecture_names_every_crate() -> None:
    # ARCHITECTURE.md is the map a newcomer reads first.
    text = (REPO / "ARCHITECTURE.md").read_text()
    crates = sorted(p.name for p in (REPO / "crates").iterdir() if (p / "Cargo.toml").is_file())
    assert len(crates) >= 7, crates
    for crate in crates:
        assert f"`{crate}`" in text, crate


def test_no_file_cites_an_issue_the_repository_does_not_hold() -> None:
    """Issues live in the team's tracker, not here: a reader of the code
    cannot follow "issue 23", so comments and pages say what they mean."""
    tracked = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    cited = re.compile(r"\bissues? (?:#?\d|\")")
    found = [
        f"{name}:{number}"
        for name in tracked
        if name.endswith((".md", ".rs", ".py", ".pyi", ".sh", ".toml", ".j2", "Makefile"))
        and name != "tests/python/test_docs.py"
        for number, line in enumerate((REPO / name).read_text(errors="replace").splitlines(), 1)
        if cited.search(line)
    ]
    assert not found, found


def test_every_install_instruction_is_the_one_line_that_works_from_a_clone() -> None:
    """One install line, the same on every page a newcomer reads; the
    package index's name only beside "once published" (it is not there)."""
    line = "pip install ./crates/rse-cli ./crates/rse-py"
    for page in ["README.md", "docs/guide.md", "docs/python.md", "docs/train.md", "docs/frameworks.md"]:
        text = (REPO / page).read_text()
        assert line in text, page
        for number, row in enumerate(text.splitlines(), 1):
            command = row.split("#")[0]
            asks_the_index = "pip install rse-gen" in row or (
                "pip install" in command and "rse-gen" in command.replace("`", " ").split()
            )
            if asks_the_index:
                assert "once published" in row, f"{page}:{number}: {row}"
