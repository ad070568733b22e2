"""Curricula (issue 12): difficulty from Python is the CLI's, and bad
difficulties are refused."""

from pathlib import Path

import numpy as np
import pytest
import rse
from conftest import SCHEMES, heights

SAMPLES = sorted(SCHEMES.glob("*.csv"))


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_difficulty_matches_rse_gen_heightmap(scheme: Path) -> None:
    loaded = rse.Scheme.load(scheme)
    full = loaded.generate(seed=3, index=2).heights
    for d in [0.0, 0.25, 0.5, 0.9]:
        terrain = loaded.generate(seed=3, index=2, difficulty=d)
        assert terrain.difficulty == d
        np.testing.assert_array_equal(terrain.heights, heights(scheme, 3, 2, d))
        assert (terrain.heights <= full).all()
    assert loaded.generate(seed=3, index=2, difficulty=1).difficulty == 1.0


def test_generate_batch_and_write_worlds_take_a_difficulty(tmp_path: Path) -> None:
    scheme = rse.Scheme.load(SCHEMES / "six_obstacles.csv")
    batch = rse.generate_batch(scheme, 3, seed=1, difficulty=0.4)
    for i, terrain in enumerate(batch):
        np.testing.assert_array_equal(terrain.heights, scheme.generate(seed=1, index=i, difficulty=0.4).heights)
    rse.write_worlds(scheme, tmp_path, amount=2, seed=1, targets="obj", difficulty=0.4)
    report = rse.check(tmp_path)
    assert report.ok and report.checked == 2, report
    text = (tmp_path / "world_0001" / "heightmap.csv").read_text()
    written = np.array([[int(v) for v in line.split(",")] for line in text.splitlines()])
    np.testing.assert_array_equal(written, heights(SCHEMES / "six_obstacles.csv", 1, 1, 0.4))


@pytest.mark.parametrize("bad", [-0.1, 1.5, float("nan"), float("inf")])
def test_bad_difficulties_are_refused(bad: float) -> None:
    scheme = rse.Scheme.load(SCHEMES / "wall.csv")
    with pytest.raises(ValueError, match="from 0 to 1"):
        scheme.generate(difficulty=bad)
    with pytest.raises(ValueError, match="from 0 to 1"):
        rse.generate_batch(scheme, 1, difficulty=bad)


def test_a_difficulty_that_is_text_is_a_type_error() -> None:
    with pytest.raises(TypeError):
        rse.Scheme.load(SCHEMES / "wall.csv").generate(difficulty="hard")  # type: ignore[arg-type]
