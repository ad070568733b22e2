"""Writes the part of `crates/rse-py/python/rse/_rse.pyi` that rse-core's
table of global keys defines: `Scheme.__new__`, from the installed
extension's `inspect.signature(rse.Scheme)` (built from the table, with
`Globals::default`'s defaults) and each keyword's type
(`rse._rse._global_keywords()`, by the key's Rust type). `--check` compares instead of writing, for
the tests: a key added to the table without the stub fails them.

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


def updated(text: str) -> str:
    """`text` (the stub) with its generated part rewritten."""
    start = text.index(BEGIN)
    end = text.index(END, start) + len(END)
    return text[:start] + scheme_new() + text[end:]


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
