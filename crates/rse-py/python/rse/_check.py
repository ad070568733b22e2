"""``rse.check``: verify world folders, as ``rse-gen check`` does.

The checks are Rust (``rse_verify``); this module turns their report into
dataclasses. A fault's ``kind`` is the same snake-case name as in
``rse-gen check --json``; its other fields are in ``details``.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Optional, Sequence, Union

from rse._rse import _check_json

PathLike = Union[str, "os.PathLike[str]"]


@dataclass(frozen=True)
class Fault:
    """One finding: what (``kind``), where (``file``, relative to the world
    or, for a batch fault, the batch folder) and the kind's fields."""

    kind: str
    file: Optional[str]
    message: str
    details: dict[str, Any] = field(default_factory=dict)

    def __str__(self) -> str:
        return f"{self.file}: {self.message}" if self.file else self.message

    @classmethod
    def _from_json(cls, raw: dict[str, Any]) -> Fault:
        raw = dict(raw)
        kind, file, message = raw.pop("kind"), raw.pop("file", None), raw.pop("message")
        return cls(kind=kind, file=file, message=message, details=raw)


@dataclass(frozen=True)
class WorldReport:
    """What ``check`` found in one world folder."""

    world: str
    ok: bool
    faults: list[Fault]
    hashed_only: list[str]
    seed: Optional[int] = None
    index: Optional[int] = None
    estimate: Optional[dict[str, float]] = None
    """What the rebuild was estimated to cost before it ran (``bytes``,
    ``visits``, ``seconds`` on one core): what the budget was held to."""
    physics: list[dict[str, Any]] = field(default_factory=list)
    """The rapier smoke test of each exact collider the world's simulators
    load (``collider``: ``"mesh <file>"`` or ``"boxes"``), with
    ``physics=True``."""

    def __bool__(self) -> bool:
        return self.ok


@dataclass(frozen=True)
class CheckReport:
    """Every world checked, and the faults of batches as wholes."""

    worlds: list[WorldReport]
    batch_faults: list[Fault]
    checked: int
    failed: int
    worlds_hashed_only: int = 0
    """Good worlds some of whose files could be compared only with their
    hashes in ``rse.json`` (rendered from templates this check did not have)."""

    @property
    def ok(self) -> bool:
        """True when no world and no batch has a fault."""
        return self.failed == 0 and not self.batch_faults

    def __bool__(self) -> bool:
        return self.ok


def check(
    path: Union[PathLike, Sequence[PathLike]],
    physics: bool = False,
    *,
    jobs: Optional[int] = None,
    strict: bool = False,
    template: Optional[PathLike] = None,
    budget: Optional[float] = None,
) -> CheckReport:
    """Check world folders, or batch folders of them, as ``rse-gen check``:
    every file rebuilt from ``rse.json`` and compared byte for byte, meshes
    re-read, with ``physics=True`` the rapier smoke test too.

    ``template``: the folder of templates custom worlds were made with, so
    their files are rebuilt and compared byte for byte too; ``strict``:
    fail every world some of whose files could be compared only with their
    hashes; ``budget``: a multiple of the rebuild budget (a world whose
    ``rse.json`` asks for more is a fault, not rebuilt; default 1, the
    library's ``check`` budget; a finite number above 0).

    Raises ``NotADirectoryError`` for a path that is not a folder and
    ``ValueError`` for a folder that holds no world.
    """
    paths = [path] if isinstance(path, (str, os.PathLike)) else list(path)
    raw = json.loads(_check_json(paths, physics, jobs, strict, template, budget))
    worlds = [
        WorldReport(
            world=w["world"],
            ok=w["ok"],
            faults=[Fault._from_json(f) for f in w["faults"]],
            hashed_only=w["hashed_only"],
            seed=w.get("seed"),
            index=w.get("index"),
            estimate=w.get("estimate"),
            physics=w.get("physics", []),
        )
        for w in raw["worlds"]
    ]
    return CheckReport(
        worlds=worlds,
        batch_faults=[Fault._from_json(f) for f in raw["batch_faults"]],
        checked=raw["checked"],
        failed=raw["failed"],
        worlds_hashed_only=raw["worlds_hashed_only"],
    )
