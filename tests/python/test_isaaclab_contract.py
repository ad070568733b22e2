"""`rse.isaaclab` against Isaac Lab's documented sub-terrain contract
(`SubTerrainBaseCfg`: `function(difficulty, cfg) -> (list[trimesh.Trimesh],
origin)`, meshes spanning (0, 0)-`cfg.size`, Z up, origin of shape (3,)),
driven the way Isaac Lab's `TerrainGenerator` drives it (a copy of the cfg
with the generator's seed, a jittered curriculum difficulty per tile).
Isaac Lab itself cannot run here: see `tests/frameworks/` and
docs/frameworks.md for what was tried and measured."""

import copy

import numpy as np
import pytest
import rse
import trimesh
from conftest import SCHEMES
from rse._adapters.tiles import fit, tile_index
from rse.isaaclab import RseTerrainCfg, rse_terrain

SIX = str(SCHEMES / "six_obstacles.csv")


def curriculum(cfg: RseTerrainCfg, rows: int, seed: int) -> list[tuple[float, list[trimesh.Trimesh], np.ndarray]]:
    """Isaac Lab's `_generate_curriculum_terrains` for one column."""
    rng = np.random.default_rng(seed)
    out = []
    for row in range(rows):
        d = (row + rng.uniform()) / rows
        tile = copy.deepcopy(cfg)
        tile.seed = seed
        meshes, origin = tile.function(d, tile)
        out.append((d, meshes, origin))
    return out


def surface_z(meshes: list[trimesh.Trimesh], xy: np.ndarray) -> np.ndarray:
    """The first hit of a ray cast straight down at each point."""
    mesh = trimesh.util.concatenate(meshes)
    origins = np.column_stack([xy, np.full(len(xy), 50.0)])
    directions = np.tile([0.0, 0.0, -1.0], (len(xy), 1))
    locations, ray_ids, _ = mesh.ray.intersects_location(origins, directions, multiple_hits=True)
    z = np.full(len(xy), -np.inf)
    np.maximum.at(z, ray_ids, locations[:, 2])
    return z


def test_tiles_follow_the_contract_and_match_rse_heights() -> None:
    cfg = RseTerrainCfg(scheme=SIX, size=(8.0, 8.0))
    for d, meshes, origin in curriculum(cfg, rows=4, seed=3):
        assert all(isinstance(m, trimesh.Trimesh) for m in meshes)
        lo, hi = trimesh.util.concatenate(meshes).bounds
        assert lo[:2] == pytest.approx([0, 0]) and hi[:2] == pytest.approx([8, 8])
        assert origin.shape == (3,) and origin.dtype == np.float64
        assert origin[:2] == pytest.approx([4.0, 4.0])
        # The tile is the rse world the adapter says it draws.
        scheme = fit(rse.Scheme.load(SIX), (8.0, 8.0))
        assert scheme.grid == (80, 80)
        index = tile_index(3, d, scheme.to_csv())
        terrain = scheme.generate(index=index, difficulty=d)
        xs, ys = np.meshgrid(np.arange(80) + 0.5, np.arange(80) + 0.5)
        pick = np.random.default_rng(0).choice(80 * 80, 300, replace=False)
        xy = np.column_stack([xs.ravel()[pick], ys.ravel()[pick]]) * 0.1
        want = terrain.elevation.ravel()[pick]
        np.testing.assert_allclose(surface_z(meshes, xy), want, atol=1e-5)
        assert origin[2] >= terrain.elevation[37:43, 37:43].max() - 1e-9


def test_the_same_configuration_gives_the_same_terrains() -> None:
    cfg = RseTerrainCfg(scheme=SIX, size=(5.0, 5.0))
    one = curriculum(cfg, rows=3, seed=7)
    two = curriculum(cfg, rows=3, seed=7)
    other = curriculum(cfg, rows=3, seed=8)
    for (_, a, oa), (_, b, ob), (_, c, _) in zip(one, two, other):
        assert np.array_equal(a[0].vertices, b[0].vertices) and np.array_equal(oa, ob)
        assert not (len(a[0].vertices) == len(c[0].vertices) and np.array_equal(a[0].vertices, c[0].vertices))


def test_difficulty_zero_is_the_flat_ground_and_out_of_range_is_refused() -> None:
    """The library's rule: a difficulty outside 0..1 (a difficulty_range
    past 1 in Isaac Lab's generator) is an error naming it, not clamped."""
    cfg = RseTerrainCfg(scheme=SIX, size=(5.0, 5.0), index=4)
    meshes, origin = rse_terrain(0.0, cfg)
    assert len(meshes) == 1 and origin[2] == 0.0
    hard, _ = rse_terrain(1.0, cfg)
    assert len(hard) == 2 and hard[0].vertices[:, 2].max() > 0
    with pytest.raises(ValueError, match="difficulty 1.7: expected a number from 0 to 1"):
        rse_terrain(1.7, cfg)


def test_a_missing_scheme_is_a_clear_error() -> None:
    with pytest.raises(ValueError, match="scheme"):
        rse_terrain(0.5, RseTerrainCfg())


def test_a_framework_that_fails_to_import_is_not_hidden(tmp_path, monkeypatch) -> None:
    """Isaac Lab absent: the plain dataclass, silently. Installed but broken
    (here a stand-in whose `terrains` raises): the same fallback, and a
    warning naming the reason (it used to be silent)."""
    import importlib
    import sys

    import rse.isaaclab

    package = tmp_path / "isaaclab"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "terrains.py").write_text("raise ImportError('no module named omni.isaac (stand-in)')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        with pytest.warns(RuntimeWarning, match=r"rse.isaaclab: isaaclab is installed but .*omni.isaac"):
            importlib.reload(rse.isaaclab)
        assert rse.isaaclab.RseTerrainCfg().scheme is None  # the plain dataclass
    finally:
        for name in [n for n in sys.modules if n == "isaaclab" or n.startswith("isaaclab.")]:
            del sys.modules[name]
        monkeypatch.undo()
        importlib.reload(rse.isaaclab)


def test_each_rank_draws_other_tiles_and_rank_zero_draws_as_one_process(monkeypatch) -> None:
    """Many processes (torchrun, Isaac Lab's --distributed): RANK picks the
    tiles; rank 0 and no launcher draw the same; an explicit rank wins."""
    monkeypatch.delenv("RANK", raising=False)
    alone = [m for _, meshes, _ in curriculum(RseTerrainCfg(scheme=SIX, size=(8.0, 8.0)), 3, 5) for m in meshes]
    monkeypatch.setenv("RANK", "0")
    zero = [m for _, meshes, _ in curriculum(RseTerrainCfg(scheme=SIX, size=(8.0, 8.0)), 3, 5) for m in meshes]
    monkeypatch.setenv("RANK", "1")
    one = [m for _, meshes, _ in curriculum(RseTerrainCfg(scheme=SIX, size=(8.0, 8.0)), 3, 5) for m in meshes]
    explicit = [m for _, meshes, _ in curriculum(RseTerrainCfg(scheme=SIX, size=(8.0, 8.0), rank=0), 3, 5) for m in meshes]
    same = lambda a, b: all(np.array_equal(x.vertices, y.vertices) for x, y in zip(a, b))  # noqa: E731
    assert same(alone, zero) and same(alone, explicit)
    assert not same(alone, one), "rank 1 draws other tiles"
    monkeypatch.setenv("RANK", "two")
    with pytest.raises(ValueError, match="^RANK"):
        curriculum(RseTerrainCfg(scheme=SIX, size=(8.0, 8.0)), 1, 5)


def test_use_stepfield_replaces_the_generators_sub_terrains_and_refuses_a_task_without_one(monkeypatch) -> None:
    from types import SimpleNamespace

    from rse.isaaclab import use_stepfield

    monkeypatch.setenv("RANK", "3")
    generator = SimpleNamespace(sub_terrains={"boxes": object()}, num_rows=10, num_cols=20)
    cfg = SimpleNamespace(scene=SimpleNamespace(terrain=SimpleNamespace(terrain_type="generator", terrain_generator=generator)))
    assert use_stepfield(cfg, SIX, spawn_radius=0.4) is cfg
    (tile,) = generator.sub_terrains.values()
    assert (tile.scheme, tile.rank, tile.spawn_radius, tile.proportion) == (SIX, 3, 0.4, 1.0)
    assert (generator.num_rows, generator.num_cols) == (10, 20), "the grid is the task's"
    plane = SimpleNamespace(scene=SimpleNamespace(terrain=SimpleNamespace(terrain_type="plane", terrain_generator=None)))
    with pytest.raises(ValueError, match=r"^env_cfg\.scene\.terrain\.terrain_type"):
        use_stepfield(plane, SIX)
    with pytest.raises(ValueError, match=r"^env_cfg\.scene\.terrain:"):
        use_stepfield(SimpleNamespace(scene=SimpleNamespace(terrain=None)), SIX)
