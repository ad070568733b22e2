"""The ``rse-gen`` command of the wheel: the Rust command line compiled
into ``rse._rse``, run in this process (no Rust toolchain needed)."""

from __future__ import annotations

import sys


def main() -> int:
    """``rse-gen`` with this process's arguments; returns its exit status."""
    from rse._rse import _main

    return _main(["rse-gen", *sys.argv[1:]])


if __name__ == "__main__":
    sys.exit(main())
