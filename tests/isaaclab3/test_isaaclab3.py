"""`rse.isaaclab` inside Isaac Lab 3.0 (Python 3.12, no Isaac Sim; make
test-frameworks, venv .venv-isaaclab3): Isaac Lab's own `TerrainGenerator`
and `TerrainImporter` build a curriculum terrain of rse tiles, converted to
a height field for its Newton physics (the MuJoCo Warp solver) on the CPU
(at a quarter of a block: Newton rasterizes the mesh on a grid that puts
samples on the block edges, so a block's top is flat between its first
and last inner samples only; with a border at height 0: without one,
Newton 1.6's converted height field sits lower by its lowest sample, here
the scheme's 5 cm base, see docs/envs.md);
a ball dropped over each env's origin rests on rse's top there, and the
envs stand on different tiles."""

from __future__ import annotations

from pathlib import Path

import sys

import numpy as np
import pytest
import rse
import torch
from rse._adapters.tiles import fit, tile_index
from rse.isaaclab import RseTerrainCfg

import isaaclab.sim as sim_utils
import isaaclab.terrains as tg
from isaaclab.assets import AssetBaseCfg, RigidObjectCfg
from isaaclab.cloner import CloneCfg, clone_plan_from_env_0, replicate
from isaaclab.sim import SimulationCfg, SimulationContext
from isaaclab_newton.assets import RigidObject
from isaaclab_newton.physics import MJWarpSolverCfg, NewtonCfg

SCHEME = rse.Scheme.from_csv(
    "# size: 10x8\n# base: 0.05\ntype,height,angle,x1,y1\nrandom,0..3,,,\npeak,2..5,45,2..7,2..5\n"
)
ROWS, COLS, SIZE, SEED = 1, 4, (1.0, 0.8), 7  # env e on tile (0, e)
N_ENVS = 4
RADIUS = 0.02
# Over the centre of the block beside each origin (the tile's centre, a
# block corner here): there a 2 cm ball touches that block's top only.
OFFSET = np.array([0.05, 0.05, 0.2])
DT = 0.005


def generator_cfg(scheme_file: Path) -> tg.TerrainGeneratorCfg:
    return tg.TerrainGeneratorCfg(
        size=SIZE, num_rows=ROWS, num_cols=COLS, curriculum=True, seed=SEED, use_cache=False,
        horizontal_scale=0.025, vertical_scale=0.005, slope_threshold=None, border_width=0.1,
        sub_terrains={"stepfield": RseTerrainCfg(proportion=1.0, scheme=str(scheme_file), convert_to_heightfield=True)},
    )  # fmt: skip


def tile(row: int, col: int) -> rse.Terrain:
    """Isaac Lab's curriculum draws tile (row, col)'s difficulty as (row +
    U)/rows from its seeded rng, column by column; rse derives the world."""
    rng = np.random.default_rng(SEED)
    fitted = fit(SCHEME, SIZE)
    for c in range(COLS):
        for r in range(ROWS):
            d = (r + rng.uniform()) / ROWS
            if (r, c) == (row, col):
                return fitted.generate(index=tile_index(SEED, d, fitted.to_csv()), difficulty=d)
    raise AssertionError((row, col))


@pytest.fixture(scope="module")
def dropped(tmp_path_factory):
    scheme_file = tmp_path_factory.mktemp("scheme") / "scheme.csv"
    scheme_file.write_text(SCHEME.to_csv())
    cfg = generator_cfg(scheme_file)
    sim_cfg = SimulationCfg(device="cpu", dt=DT, physics=NewtonCfg(solver_cfg=MJWarpSolverCfg(), use_cuda_graph=False))
    sim = SimulationContext(sim_cfg)
    importer = tg.TerrainImporter(
        tg.TerrainImporterCfg(prim_path="/World/ground", terrain_type="generator", terrain_generator=cfg,
                              num_envs=N_ENVS, env_spacing=2.0, visual_material=None)
    )  # fmt: skip
    origins = importer.env_origins.cpu().numpy().astype(np.float64)
    start = (origins + OFFSET).astype(np.float32)
    sim_utils.create_prim("/World/Env_0", "Xform", translation=tuple(float(v) for v in start[0]))
    ball_cfg = RigidObjectCfg(
        prim_path="/World/Env_[^/]*/Ball",
        spawn=sim_utils.SphereCfg(
            radius=RADIUS, rigid_props=sim_utils.UsdPhysicsRigidBodyCfg(),
            mass_props=sim_utils.MassCfg(mass=0.1), collision_props=sim_utils.UsdPhysicsCollisionCfg(),
        ),
    )  # fmt: skip
    # The terrain is declared in the clone plan as a shared asset: one
    # missing from it is missing from Newton's model (bodies fall through).
    plan = (ball_cfg, AssetBaseCfg(prim_path="/World/ground"))
    clone_plan_from_env_0(CloneCfg(clone_template="/World/Env_{}"), plan, N_ENVS, 1.0, positions=start)
    ball = RigidObject(ball_cfg)
    replicate(sim.get_clone_plan())
    sim.reset()
    for _ in range(200):
        sim.step()
    ball.update(DT)
    pos = ball.data.root_pos_w
    pos = pos.torch if hasattr(pos, "torch") else torch.as_tensor(pos)
    levels = importer.terrain_levels.cpu().numpy()
    types = importer.terrain_types.cpu().numpy()
    yield origins, pos.cpu().numpy().astype(np.float64), levels, types
    sim.clear_instance()


def test_each_ball_rests_on_rse_tops_over_its_origin(dropped) -> None:
    origins, pos, levels, types = dropped
    # Newton rasterizes the tiles with samples on the block edges: a ball
    # may roll a little before it settles, never off its tile.
    assert np.all(np.abs(pos[:, :2] - (origins[:, :2] + OFFSET[:2])) < 0.1), pos
    tops = []
    for e in range(N_ENVS):
        terrain = tile(levels[e], types[e])
        # The tile's corner: Isaac Lab centres the grid on the origin, rows along x.
        corner = np.array([levels[e] * SIZE[0] - ROWS * SIZE[0] / 2, types[e] * SIZE[1] - COLS * SIZE[1] / 2])
        want = np.asarray(terrain.spawn_origin(0.3)) + [*corner, 0.0]
        assert np.allclose(origins[e], want, atol=1e-5), "the env's origin is rse's spawn point"
        cx, cy = ((pos[e, :2] - corner) / terrain.block_size).astype(int)
        tops.append(terrain.elevation[cy, cx])
    assert np.allclose(pos[:, 2], np.array(tops) + RADIUS, atol=5e-3), (pos, tops)
    assert len(set(np.round(tops, 4))) > 1, "the envs stand on different tops"



def test_the_docs_example_runs_as_written(tmp_path) -> None:
    """docs/envs.md's ```python isaaclab3 block runs as written."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from envs_doc import run_example

    run_example("isaaclab3", tmp_path)
