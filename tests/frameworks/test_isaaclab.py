"""`rse.isaaclab` inside Isaac Lab's own `TerrainGenerator` (run by `make
test-frameworks`). Isaac Lab's pip package bootstraps Isaac Sim on import,
and its `isaaclab.terrains` package imports the USD importer, which needs
Isaac Sim's `carb`; neither installs here (no GPU, Isaac Sim is not on
PyPI's reach for this machine). The terrain generator itself needs only
numpy, torch, trimesh and warp, so this test loads `isaaclab` from the
wheel's source folder and the modules of `isaaclab.terrains` without running
that package's `__init__`, then lets Isaac Lab build a curriculum terrain of
rse tiles and checks it with ray casts."""

import importlib
import sys
import types
from pathlib import Path

import numpy as np
import pytest
import trimesh

ISAACLAB_SOURCE = Path(importlib.util.find_spec("isaaclab").origin).parent / "source" / "isaaclab"
sys.path.insert(0, str(ISAACLAB_SOURCE))
for name in [n for n in sys.modules if n == "isaaclab" or n.startswith("isaaclab.")]:
    del sys.modules[name]
import isaaclab  # noqa: E402  (now the framework's own package, not the Isaac Sim launcher)

_terrains = types.ModuleType("isaaclab.terrains")
_terrains.__path__ = [str(Path(isaaclab.__file__).parent / "terrains")]
sys.modules["isaaclab.terrains"] = _terrains
_sub = importlib.import_module("isaaclab.terrains.sub_terrain_cfg")
_terrains.SubTerrainBaseCfg = _sub.SubTerrainBaseCfg
_terrains.FlatPatchSamplingCfg = _sub.FlatPatchSamplingCfg
TerrainGenerator = importlib.import_module("isaaclab.terrains.terrain_generator").TerrainGenerator
TerrainGeneratorCfg = importlib.import_module("isaaclab.terrains.terrain_generator_cfg").TerrainGeneratorCfg

import rse  # noqa: E402
from rse._adapters.tiles import fit, tile_index  # noqa: E402
from rse.isaaclab import RseTerrainCfg  # noqa: E402

SIX = str(Path(__file__).resolve().parents[2] / "schemes" / "six_obstacles.csv")
ROWS, COLS, SIZE, SEED = 3, 2, (8.0, 8.0), 1


@pytest.fixture(scope="module")
def generator():
    cfg = TerrainGeneratorCfg(
        size=SIZE, num_rows=ROWS, num_cols=COLS, curriculum=True, seed=SEED, use_cache=False,
        horizontal_scale=0.1, vertical_scale=0.005, slope_threshold=None, border_width=0.0,
        sub_terrains={"stepfield": RseTerrainCfg(
            proportion=1.0, scheme=SIX,
            flat_patch_sampling={"spawn": _sub.FlatPatchSamplingCfg(num_patches=4, patch_radius=0.3, max_height_diff=0.01)},
        )},
    )  # fmt: skip
    return TerrainGenerator(cfg, device="cpu")


def test_our_cfg_is_isaac_labs_sub_terrain_class() -> None:
    assert issubclass(RseTerrainCfg, _sub.SubTerrainBaseCfg)


def tiles():
    """Isaac Lab's curriculum: column by column, row by row, difficulty
    (row + U)/rows from its generator's seeded rng; the tile's rse world
    follows from that difficulty and the seed (`rse._adapters.tiles.tile_index`)."""
    rng = np.random.default_rng(SEED)
    scheme = fit(rse.Scheme.load(SIX), SIZE)
    for col in range(COLS):
        for row in range(ROWS):
            d = (row + rng.uniform()) / ROWS
            yield row, col, scheme.generate(index=tile_index(SEED, d, scheme.to_csv()), difficulty=d)


def corner(row: int, col: int) -> np.ndarray:
    """Isaac Lab centres the whole grid on the origin; rows run along x."""
    return np.array([row * SIZE[0] - ROWS * SIZE[0] / 2, col * SIZE[1] - COLS * SIZE[1] / 2])


def test_rays_hit_rse_heights_in_every_tile(generator) -> None:
    mesh = generator.terrain_mesh
    for row, col, terrain in tiles():
        ny, nx = terrain.heights.shape
        pick = np.random.default_rng(row * COLS + col).choice(nx * ny, 150, replace=False)
        ys, xs = np.divmod(pick, nx)
        xy = corner(row, col) + (np.column_stack([xs, ys]) + 0.5) * terrain.block_size
        origins = np.column_stack([xy, np.full(len(xy), 20.0)])
        hits, ray_ids, _ = mesh.ray.intersects_location(origins, np.tile([0, 0, -1.0], (len(xy), 1)))
        z = np.full(len(xy), -np.inf)
        np.maximum.at(z, ray_ids, hits[:, 2])
        np.testing.assert_allclose(z, terrain.elevation[ys, xs], atol=1e-5)


def test_origins_are_rse_spawn_points(generator) -> None:
    for row, col, terrain in tiles():
        want = terrain.spawn_origin(0.3) + [*corner(row, col), 0.0]
        np.testing.assert_allclose(generator.terrain_origins[row, col], want, atol=1e-6)


def test_isaac_labs_own_flat_patches_lie_on_rse_tops(generator) -> None:
    patches = generator.flat_patches["spawn"].cpu().numpy()
    assert patches.shape == (ROWS, COLS, 4, 3)
    for row, col, terrain in tiles():
        for x, y, z in patches[row, col]:
            cx, cy = ((np.array([x, y]) - corner(row, col)) / terrain.block_size).astype(int)
            tops = terrain.elevation[max(cy - 1, 0) : cy + 2, max(cx - 1, 0) : cx + 2]
            assert tops.min() - 0.011 <= z <= tops.max() + 0.011, (row, col, x, y, z)
