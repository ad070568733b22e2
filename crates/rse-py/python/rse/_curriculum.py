"""``rse.check_curriculum``: a scheme checked as a curriculum, as
``rse-gen check-curriculum`` does — per difficulty level, figures over many
draws, and the levels that teach nothing (docs/schemes.md, "Checking a
curriculum")."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from rse._adapters.tiles import SchemeLike, load
from rse._rse import _check_curriculum


@dataclass(frozen=True)
class LevelStats:
    """One level's worlds; heights in metres, pallet frames left out."""

    level: int
    difficulty: float
    flat_share: float
    """Share of worlds with no cell above 0."""
    mean_height: float
    """Mean cell height over every world: the figure that must rise."""
    mean_step: float
    """Mean height difference between neighbouring cells that differ."""
    max_step: float
    """Largest height difference between neighbouring cells."""
    max_slope_deg: float
    """``atan(max_step / block_size)`` in degrees."""
    distinct: int
    """Different worlds among the draws."""


@dataclass(frozen=True)
class CurriculumReport:
    """Every level's figures; ``problems`` empty when the curriculum holds
    (no dead level, the mean height rising at every level)."""

    levels: list[LevelStats]
    problems: list[str]
    draws: int
    seed: int

    @property
    def ok(self) -> bool:
        """True when no level is dead or no higher than the one below."""
        return not self.problems

    def __bool__(self) -> bool:
        return self.ok


def check_curriculum(
    scheme: SchemeLike, levels: int = 10, draws: int = 50, seed: Optional[int] = None, budget: Optional[float] = None
) -> CurriculumReport:
    """Check ``scheme`` (a ``Scheme`` or a CSV path) as a curriculum:
    ``levels`` difficulties evenly spaced from 0 to 1 (level ``l`` is
    ``l / (levels - 1)``, as mjlab spaces its terrain levels), each over
    worlds ``0..draws`` of ``seed`` (default: the scheme's ``# seed:``) —
    the same draws at every level. ``ValueError`` for ``levels`` outside
    2–1000 or ``draws`` outside 1–100000, or a check priced over ``budget``
    times the default (some 100 s on one core), before a world is made.
    Ctrl-C stops it between worlds (``KeyboardInterrupt``)."""
    rows, problems, used_seed = _check_curriculum(load(scheme), levels, draws, seed, budget)
    return CurriculumReport(levels=[LevelStats(*row) for row in rows], problems=problems, draws=draws, seed=used_seed)
