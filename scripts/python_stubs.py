"""Writes the parts of `crates/rse-py/python/rse/_rse.pyi` that the tables
of options define: `Scheme.__new__`, from rse-core's table of global keys
(the installed extension's `inspect.signature(rse.Scheme)`, built from the
table with `Globals::default`'s defaults, and each keyword's type,
`rse._rse._global_keywords()`, by the key's Rust type); and the world
options of every writer (`write_worlds`, `write_world`, `Atlas.write`),
from rse-world's table (`rse._rse._world_keywords()`), after each
`# The world options:` line; and `EnvTerrains`' per-env options, from
rse-core's table (`_env_keywords()`), after the `# The per-env options:`
line. `--check` compares instead of writing, for
the tests: an option added to a table without the stub fails them.

    .venv/bin/python scripts/python_stubs.py           # rewrite the stub
    .venv/bin/python scripts/python_stubs.py --check   # exit 1 if it is stale
"""

from __future__ import annotations

import inspect
import sys
from pathlib import Path

STUB = Path(__file__).resolve().parents[1] / "crates" / "rse-py" / "python" / "rse" / "_rse.pyi"
BEGIN = "    # Generated from rse-core's table of global keys by scripts/python_stubs.py.\n"
END = "    ) -> Scheme: ...\n"


def scheme_new() -> str:
    """`Scheme.__new__` as the stub writes it."""
    import rse
    from rse import _rse

    types = {"obstacles": "list[Obstacle]", **{name: kind for name, kind, *_ in _rse._global_keywords()}}
    lines = [BEGIN, "    def __new__(\n", "        cls,\n"]
    keyword_only = False
    for p in inspect.signature(rse.Scheme).parameters.values():
        if p.kind is inspect.Parameter.KEYWORD_ONLY and not keyword_only:
            lines.append("        *,\n")
            keyword_only = True
        kind = types[p.name]
        if p.default is None and not kind.startswith("Optional["):
            kind = f"Optional[{kind}]"
        lines.append(f"        {p.name}: {kind} = {p.default!r},\n")
    lines.append(END)
    return "".join(lines)


# Each generated block: its marker line, the table's keywords as
# `(name, type)`, and the caller's own keywords after them.
BLOCKS = {
    "# The world options: scripts/python_stubs.py writes them from rse-world's table.\n": (
        "_world_keywords",
        ("template: Optional[Union[str, os.PathLike[str]]] = None,\n", "force: Optional[bool] = None,\n"),
    ),
    "# The per-env options: scripts/python_stubs.py writes them from rse-core's table.\n": (
        "_env_keywords",
        ("proportions: Optional[Sequence[float]] = None,\n",),
    ),
}


def keywords(table: str, own: tuple[str, ...], indent: str) -> str:
    """A table's keywords (all defaulting to None), then the caller's own, at `indent`."""
    from rse import _rse

    rows = getattr(_rse, table)()
    lines = [f"{indent}{row[0]}: Optional[{row[1]}] = None,\n" for row in rows]
    return "".join(lines + [indent + line for line in own])


def updated(text: str) -> str:
    """`text` (the stub) with its generated parts rewritten."""
    start = text.index(BEGIN)
    end = text.index(END, start) + len(END)
    text = text[:start] + scheme_new() + text[end:]
    for marker, (table, own) in BLOCKS.items():
        at = 0
        while (found := text.find(marker, at)) >= 0:
            indent = text[text.rindex("\n", 0, found) + 1 : found]
            body = found + len(marker)
            last = indent + own[-1]
            end = text.index(last, body) + len(last)
            text = text[:body] + keywords(table, own, indent) + text[end:]
            at = body
    return text


def main() -> int:
    text = STUB.read_text()
    new = updated(text)
    if "--check" in sys.argv[1:]:
        if new != text:
            print(f"{STUB} is stale: run .venv/bin/python scripts/python_stubs.py", file=sys.stderr)
            return 1
        return 0
    STUB.write_text(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())
