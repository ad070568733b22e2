"""`rse.mjlab` inside mjlab's own `TerrainGenerator` (run by `make
test-frameworks`, in `.venv-frameworks`: mjlab pins MuJoCo 3.11 and pulls
torch, so it cannot share `make test`'s environment). The generator builds
the terrain into an `MjSpec`, MuJoCo compiles it, and rays cast with
`mujoco.mj_ray` at cell centres must hit rse's heights; origins and flat
patches must sit on the tops."""

from pathlib import Path

import mujoco
import numpy as np
import pytest
import rse
from mjlab.terrains import TerrainGenerator, TerrainGeneratorCfg
from mjlab.terrains.terrain_generator import FlatPatchSamplingCfg
from rse._adapters.tiles import fit
from rse.mjlab import RseTerrainCfg

SIX = Path(__file__).resolve().parents[2] / "schemes" / "six_obstacles.csv"
ROWS, SIZE, SEED = 4, (5.0, 5.0), 3


@pytest.fixture(scope="module")
def built():
    cfg = TerrainGeneratorCfg(
        size=SIZE,
        num_rows=ROWS,
        num_cols=1,
        curriculum=True,
        seed=SEED,
        sub_terrains={
            "stepfield": RseTerrainCfg(
                scheme=str(SIX),
                flat_patch_sampling={
                    "spawn": FlatPatchSamplingCfg(num_patches=6, patch_radius=0.2, max_height_diff=0.0)
                },
            )
        },
    )
    return compiled(cfg)


def compiled(cfg: TerrainGeneratorCfg):
    """mjlab's generator of ``cfg`` compiled into a model, forwarded once:
    ``(generator, model, data)``."""
    generator = TerrainGenerator(cfg)
    spec = mujoco.MjSpec()
    generator.compile(spec)
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return generator, model, data


def tile_terrains():
    """The worlds the adapter draws: mjlab calls it column by column, row by
    row, with one rng seeded by the generator's seed; it draws one index each."""
    rng = np.random.default_rng(SEED)
    scheme = fit(rse.Scheme.load(SIX), SIZE)
    for row in range(ROWS):
        index = int(rng.integers(0, 2**62))
        yield row, scheme.generate(index=index, difficulty=row / (ROWS - 1))


def corner(row: int) -> np.ndarray:
    """mjlab centres the grid on the world origin."""
    return np.array([-ROWS * SIZE[0] / 2 + row * SIZE[0], -SIZE[1] / 2])


def ray_down(model, data, x: float, y: float) -> float:
    geomid = np.zeros(1, dtype=np.int32)
    dist = mujoco.mj_ray(model, data, np.array([x, y, 10.0]), np.array([0.0, 0.0, -1.0]), None, 1, -1, geomid)
    assert dist >= 0, (x, y)
    return 10.0 - dist


def test_rays_hit_rse_heights_in_every_tile(built) -> None:
    _, model, data = built
    checked = 0
    for row, terrain in tile_terrains():
        ny, nx = terrain.heights.shape
        pick = np.random.default_rng(row).choice(nx * ny, 200, replace=False)
        for k in pick:
            y, x = divmod(int(k), nx)
            at = corner(row) + (np.array([x, y]) + 0.5) * terrain.block_size
            assert ray_down(model, data, *at) == pytest.approx(terrain.elevation[y, x], abs=1e-6)
            checked += 1
    assert checked == ROWS * 200


def test_origins_and_flat_patches_sit_on_the_tops(built) -> None:
    generator, model, data = built
    for row, terrain in tile_terrains():
        origin = generator.terrain_origins[row, 0]
        np.testing.assert_allclose(origin, [*(corner(row) + np.array(SIZE) / 2), terrain.spawn_origin(0.3)[2]])
        mine = terrain.flat_patches(6, 0.2, 0)
        mine = mine[~np.isnan(mine[:, 0])]
        patches = generator.flat_patches["spawn"][row, 0]
        np.testing.assert_allclose(patches[: len(mine)], mine + [*corner(row), 0.0])
        for x, y, z in patches[: len(mine)]:
            assert ray_down(model, data, x, y) == pytest.approx(z, abs=1e-6)


def test_bodies_spawned_at_the_origins_start_inside_no_block() -> None:
    cfg = TerrainGeneratorCfg(
        size=SIZE, num_rows=ROWS, num_cols=1, curriculum=True, seed=SEED,
        sub_terrains={"stepfield": RseTerrainCfg(scheme=str(SIX), spawn_radius=0.1)},
    )  # fmt: skip
    generator = TerrainGenerator(cfg)
    spec = mujoco.MjSpec()
    generator.compile(spec)
    for i, (x, y, z) in enumerate(generator.terrain_origins.reshape(-1, 3)):
        body = spec.worldbody.add_body(name=f"robot_{i}", pos=[x, y, z + 0.1 + 1e-4])
        body.add_freejoint()
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.1, 0, 0], mass=1.0)
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert all(data.contact[k].dist > -1e-6 for k in range(data.ncon))


RAMPS = """# size: 50x50
# step_height: 0.05
type,height,angle,x1,y1,x2,y2
ramp,10..16,,2,2,30,20
crossing_ramps,4..8,,34,2,47,47
"""


def test_a_ramps_tile_collides_with_its_planes(tmp_path) -> None:
    """A ramp in mjlab's own generator: its wedge a convex mesh geom over
    the boxes of its staircase, so a ray finds the plane."""
    scheme = tmp_path / "ramps.csv"
    scheme.write_text(RAMPS)
    cfg = TerrainGeneratorCfg(
        size=SIZE, num_rows=2, num_cols=1, curriculum=True, seed=SEED,
        sub_terrains={"ramps": RseTerrainCfg(scheme=str(scheme))},
    )  # fmt: skip
    _, model, data = compiled(cfg)
    assert model.nmesh == 3, "three wedges in the harder tile, none at difficulty 0 (no rise)"
    rng = np.random.default_rng(SEED)
    loaded = rse.Scheme.load(scheme)
    for row in range(2):
        terrain = loaded.generate(index=int(rng.integers(0, 2**62)), difficulty=float(row))
        s = terrain.block_size
        origin = np.array([-2 * SIZE[0] / 2 + row * SIZE[0], -SIZE[1] / 2])
        for ramp in terrain.ramps:
            x0, y0, x1, y1 = ramp["cells"]
            for x, y in np.random.default_rng(row).uniform([x0 * s + 1e-3, y0 * s + 1e-3], [(x1 + 1) * s - 1e-3, (y1 + 1) * s - 1e-3], (30, 2)):
                assert ray_down(model, data, *(origin + [x, y])) == pytest.approx(terrain.height_at(x, y), abs=1e-6)
