"""Writes docs/python.md, the Python API reference, from the installed
package's docstrings and signatures (the Rust doc comments pyo3 exports and
the Python modules' own). `--check` compares instead of writing, for CI:
a docstring changed without the page fails the tests.

    .venv/bin/python scripts/python_api_docs.py           # write docs/python.md
    .venv/bin/python scripts/python_api_docs.py --check   # exit 1 if it is stale
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import sys
import textwrap
from pathlib import Path

PAGE = Path(__file__).resolve().parents[1] / "docs" / "python.md"
MODULES = ["rse", "rse.mujoco", "rse.mujoco_warp", "rse.mjx", "rse.gym", "rse.isaaclab", "rse.mjlab", "rse.mjlab_eval", "rse.genesis", "rse.newton", "rse.playground", "rse.ray"]

HEADER = """\
# Python API reference

Generated from the docstrings of the installed package by
`scripts/python_api_docs.py` (the tests fail when it is stale: run
`.venv/bin/python scripts/python_api_docs.py` after changing a docstring).
Install, from a clone's root: `pip install ./crates/rse-cli ./crates/rse-py`
(`pip install rse-gen` once published; guide.md, "Python"); import: `import rse`.
Lengths are metres, heights are whole steps, arrays are numpy, `(lo, hi)`
pairs are inclusive ranges drawn per world.
"""


def doc(obj: object) -> str:
    text = inspect.getdoc(obj) or ""
    return textwrap.dedent(text).strip()


def signature(name: str, obj: object) -> str:
    try:
        sig = str(inspect.signature(obj))
    except (TypeError, ValueError):
        return name
    for bound in ["(self, /, ", "(self, ", "(/, "]:
        sig = sig.replace(bound, "(")
    for empty in ["(self, /)", "(self)", "(/)"]:
        sig = sig.replace(empty, "()")
    return f"{name}{sig}"


def is_property(member: object) -> bool:
    return isinstance(member, property) or type(member).__name__ == "getset_descriptor"


def members(cls: type) -> list[tuple[str, object]]:
    """Public properties, then methods, each by name: the order of a pyo3
    class's `vars` is not fixed from one build to the next."""
    public = [(n, m) for n, m in vars(cls).items() if not n.startswith("_")]
    return sorted(public, key=lambda item: (not is_property(item[1]), item[0]))


def bullet(head: str, text: str) -> str:
    """A list item whose further lines stay in it."""
    body = f": {text}" if text else ""
    return f"- {head}{body}".replace("\n", "\n  ")


def document_class(qualname: str, cls: type, out: list[str]) -> None:
    out.append(f"### `{qualname}`\n")
    if dataclasses.is_dataclass(cls):
        fields = ", ".join(f.name for f in dataclasses.fields(cls))
        out.append(f"```python\n{qualname}({fields})\n```\n")
    else:
        out.append(f"```python\n{signature(qualname, cls)}\n```\n")
    if doc(cls):
        out.append(doc(cls) + "\n")
    for name, member in members(cls):
        if dataclasses.is_dataclass(cls) and name in {f.name for f in dataclasses.fields(cls)}:
            continue
        target = member.__func__ if isinstance(member, (staticmethod, classmethod)) else member
        if is_property(member):
            out.append(bullet(f"**`.{name}`** (property)", doc(member)))
        elif callable(target):
            out.append(bullet(f"**`.{signature(name, target)}`**", doc(target)))
    out.append("")


def document_module(module_name: str, out: list[str]) -> None:
    module = importlib.import_module(module_name)
    out.append(f"## `{module_name}`\n")
    if module_name != "rse" and doc(module):
        out.append(doc(module) + "\n")
    for name in module.__all__:
        if name.startswith("_") or name == "__version__":
            continue
        obj = getattr(module, name)
        qualname = f"{module_name}.{name}"
        if inspect.isclass(obj):
            document_class(qualname, obj, out)
        elif callable(obj):
            out.append(f"### `{qualname}`\n")
            out.append(f"```python\n{signature(qualname, obj)}\n```\n")
            if doc(obj):
                out.append(doc(obj) + "\n")
        else:
            out.append(f"### `{qualname}`\n\n`{obj!r}`\n")


def page() -> str:
    out = [HEADER]
    for module_name in MODULES:
        document_module(module_name, out)
    text = "\n".join(line.rstrip() for line in "\n".join(out).splitlines())
    return text.rstrip() + "\n"


def main() -> int:
    text = page()
    if "--check" in sys.argv[1:]:
        if PAGE.read_text() != text:
            print(f"{PAGE} is stale: run .venv/bin/python scripts/python_api_docs.py", file=sys.stderr)
            return 1
        return 0
    PAGE.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
