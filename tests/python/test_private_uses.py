"""Every private name of a framework that rse's Python package touches is on
the registry (`rse._adapters.private.USES`) and reached through its checked
accessors, found by reading the package's source (its syntax trees), not by
running any framework: a private use added without listing it fails here,
naming the file and line.

A name is rse's own when rse defines it (a function, class or module
global, or an attribute its own code assigns; in Rust, as its stub
declares it) and the registry does not list it; anything else reached as
`obj._name` belongs to someone else."""

import ast
from pathlib import Path

import pytest
from conftest import REPO
from rse._adapters import private

PACKAGE = REPO / "crates" / "rse-py" / "python" / "rse"
REGISTERED = {use.attribute for use in private.USES}
REGISTERED_MODULES = {use.owner.partition(":")[0] for use in private.USES}
CHECKED = {"getattr_checked", "setattr_checked"}


def modules() -> dict[Path, ast.Module]:
    return {path: ast.parse(path.read_text(), str(path)) for path in sorted(PACKAGE.rglob("*.py"))}


def private_name(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def own_names(trees: dict[Path, ast.Module]) -> set[str]:
    """The private names rse's own code defines or assigns."""
    names: set[str] = set()
    for tree in trees.values():
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                names.add(node.name)
            elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                for target in targets:
                    for part in ast.walk(target):
                        if isinstance(part, ast.Name):
                            names.add(part.id)
                        elif isinstance(part, ast.Attribute):
                            names.add(part.attr)
            elif isinstance(node, ast.alias):
                names.add((node.asname or node.name).split(".")[0])
    return {name for name in names if private_name(name)} - REGISTERED


def stubs() -> dict[Path, ast.Module]:
    """The extension's stubs: what rse's Rust code defines (a private
    method of ``EnvTerrains`` is rse's own)."""
    return {path: ast.parse(path.read_text(), str(path)) for path in sorted(PACKAGE.rglob("*.pyi"))}


def test_every_private_use_is_registered_and_checked() -> None:
    trees = modules()
    own = own_names({**trees, **stubs()})
    problems = []
    for path, tree in trees.items():
        where = path.relative_to(PACKAGE)
        if where == Path("_adapters/private.py"):
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and private_name(node.attr) and node.attr not in own:
                registered = node.attr in REGISTERED
                fix = "reach it through private.getattr_checked" if registered else "list it in USES"
                problems.append(f"{where}:{node.lineno}: {ast.unparse(node)} ({fix})")
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                top, *rest = node.module.split(".")
                listed = any(m == node.module or m.startswith(node.module + ".") for m in REGISTERED_MODULES)
                if top != "rse" and any(map(private_name, rest)) and not listed:
                    names = ", ".join(alias.name for alias in node.names)
                    problems.append(f"{where}:{node.lineno}: from {node.module} import {names} (list it in USES)")
                for alias in node.names:
                    if top != "rse" and private_name(alias.name) and alias.name not in REGISTERED:
                        problems.append(f"{where}:{node.lineno}: imports {node.module}.{alias.name} (list it in USES)")
            elif (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr in CHECKED
                and len(node.args) >= 2
                and isinstance(node.args[1], ast.Constant)
                and node.args[1].value not in REGISTERED
            ):
                problems.append(f"{where}:{node.lineno}: {node.func.attr} of {node.args[1].value!r}, not in USES")
    assert not problems, "private names of frameworks used outside the registry:\n" + "\n".join(problems)


@pytest.mark.parametrize(
    "source",
    [
        "def f(env):\n    return env._hidden_state\n",
        "from somepkg._internal.mod import Thing\n",
        "def f(x):\n    return private.getattr_checked(x, '_not_listed', 'mjlab')\n",
    ],
)
def test_the_scan_finds_an_unlisted_use(source: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The scan over a package holding one more module with the use.
    trees = modules()
    extra = tmp_path / "extra.py"
    extra.write_text(source)
    trees[PACKAGE / "extra.py"] = ast.parse(source)
    monkeypatch.setattr(__import__(__name__), "modules", lambda: trees)
    with pytest.raises(AssertionError, match="extra.py:"):
        test_every_private_use_is_registered_and_checked()
