"""Writes the parts of `crates/rse-py/python/rse/_rse.pyi` that the tables
of options define: `Scheme.__new__`, from rse-core's table of global keys
(the installed extension's `inspect.signature(rse.Scheme)`, built from the
table with `Globals::default`'s defaults, and each keyword's type,
`rse._rse._global_keywords()`, by the key's Rust type); and the world
options of every writer (`write_worlds`, `write_world`, `Atlas.write`),
from rse-world's table (`rse._rse._world_keywords()`), after each
`# The world options:` line. `--check` compares instead of writing, for
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


WORLD_OPTIONS = "# The world options: scripts/python_stubs.py writes them from rse-world's table.\n"
# The writer's own keywords, after the world options.
WRITER_OWN = ("template: Optional[Union[str, os.PathLike[str]]] = None,\n", "force: Optional[bool] = None,\n")


def world_options(indent: str) -> str:
    """The world options' keywords of a writer, then the writer's own, at `indent`."""
    from rse import _rse

    lines = [f"{indent}{name}: Optional[{kind}] = None,\n" for name, kind, *_ in _rse._world_keywords()]
    return "".join(lines + [indent + line for line in WRITER_OWN])


def updated(text: str) -> str:
    """`text` (the stub) with its generated parts rewritten."""
    start = text.index(BEGIN)
    end = text.index(END, start) + len(END)
    text = text[:start] + scheme_new() + text[end:]
    at = 0
    while (found := text.find(WORLD_OPTIONS, at)) >= 0:
        line_start = text.rindex("\n", 0, found) + 1
        indent = text[line_start:found]
        body = found + len(WORLD_OPTIONS)
        last = indent + WRITER_OWN[-1]
        end = text.index(last, body) + len(last)
        text = text[:body] + world_options(indent) + text[end:]
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
