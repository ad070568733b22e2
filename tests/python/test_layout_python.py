"""The Python package's layout, as docs/development.md states it: no
function over 60 lines, no module over 300 (the stubs aside), no two
modules of one name, and everything mjlab in ``rse._adapters.mjlab``, its
public modules thin faces that re-export it. Read from the source, so a
long function or a stray module fails here by name."""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "crates" / "rse-py" / "python" / "rse"
MODULES = sorted(PACKAGE.rglob("*.py"))
MJLAB_FACES = {"mjlab.py", "mjlab_tasks.py", "mjlab_eval.py", "mjlab_video.py"}


def test_no_function_is_over_60_lines_and_no_module_over_300() -> None:
    long = []
    for path in MODULES:
        source = path.read_text()
        if len(source.splitlines()) > 300:
            long.append(f"{path.relative_to(PACKAGE)}: {len(source.splitlines())} lines")
        for node in ast.walk(ast.parse(source)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lines = (node.end_lineno or node.lineno) - node.lineno + 1
                if lines > 60:
                    long.append(f"{path.relative_to(PACKAGE)}: {node.name} is {lines} lines")
    assert not long, long


def test_no_two_modules_share_a_name() -> None:
    seen: dict[str, list[str]] = {}
    for path in MODULES:
        if path.name != "__init__.py":
            seen.setdefault(path.name, []).append(str(path.relative_to(PACKAGE)))
    assert not {name: paths for name, paths in seen.items() if len(paths) > 1}


def test_mjlab_lives_in_one_home_behind_thin_faces() -> None:
    stray = [str(p.relative_to(PACKAGE)) for p in MODULES if "mjlab" in p.name and p.parent == PACKAGE and p.name not in MJLAB_FACES]
    assert not stray, f"mjlab modules outside rse/_adapters/mjlab/: {stray}"
    for name in MJLAB_FACES:
        tree = ast.parse((PACKAGE / name).read_text())
        defined = [n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))]
        assert not defined, f"rse/{name} defines {[n.name for n in defined]}: a face re-exports rse._adapters.mjlab"
        imports = [n.module for n in tree.body if isinstance(n, ast.ImportFrom) and n.module not in ("__future__",)]
        assert any(m and m.startswith("rse._adapters.mjlab.") for m in imports), name
