"""Isaac Lab 3.0's own rough-terrain velocity task for the Unitree Go2
(`Isaac-Velocity-Rough-UnitreeGo2`: Newton's MuJoCo Warp solver, on the
CPU, no Isaac Sim) on rse tiles through `rse.isaaclab.use_stepfield`
(.venv-isaaclab3, make test-frameworks).

The task's robot USD lives on NVIDIA's Nucleus server, which cannot be
reached here: the Go2 is Unitree's URDF as Genesis's wheel ships it
(scripts/test-frameworks.sh copies it to target/assets/go2), converted by
Isaac Lab's own `UrdfConverter` (isaaclab[importers]). The converter nests
each link under its parent, where Isaac Lab's go2.usd has them side by
side, so two sensor paths of the task are pointed at the nested links;
every other term is the task's. Tested: each Go2's feet touch rse's mesh;
the height scanner sees rse's tops; the task's terrain curriculum is kept;
one iteration of rsl-rl's PPO runs through Isaac Lab's wrapper."""

from __future__ import annotations

import subprocess
import sys
from importlib import metadata
from pathlib import Path

import numpy as np
import pytest
import rse.isaaclab
import torch
import trimesh
from isaaclab.envs import ManagerBasedRLEnv
from isaaclab.terrains import TerrainGenerator
from isaaclab.utils import replace
from isaaclab_rl.rsl_rl import RslRlVecEnvWrapper, handle_deprecated_rsl_rl_cfg
from isaaclab_tasks.core.velocity.config.go2.agents.rsl_rl_ppo_cfg import UnitreeGo2RoughPPORunnerCfg
from isaaclab_tasks.core.velocity.config.go2.rough_env_cfg import UnitreeGo2RoughEnvCfg
from rsl_rl.runners import OnPolicyRunner

GO2_URDF = Path(__file__).resolve().parents[2] / "target" / "assets" / "go2" / "urdf" / "go2.urdf"
# 2 m tiles of 10 cm blocks (small fields build fast on the CPU): 2.5 cm
# steps under a hill.
SCHEME = "# size: 20x20\n# block_size: 0.1\n# step_height: 0.025\ntype,height,angle,x1,y1\nrandom,0..2,,,\npeak,2..5,30,5..15,5..15\n"
N_ENVS = 4
FOOT_RADIUS = 0.022  # the URDF's foot spheres


# Isaac Lab's converter, run in a process of its own as Isaac Lab's
# convert_urdf.py tool runs it: after a SimulationContext has lived in this
# process (test_isaaclab3.py), the importer no longer finds the PhysX
# schemas it applies.
CONVERT = """
import sys
from isaaclab.sim.converters import UrdfConverter, UrdfConverterCfg
drive = UrdfConverterCfg.JointDriveCfg(gains=UrdfConverterCfg.JointDriveCfg.PDGainsCfg(stiffness=0.0, damping=0.0))
cfg = UrdfConverterCfg(asset_path=sys.argv[1], usd_dir=sys.argv[2], fix_base=False, merge_fixed_joints=False, joint_drive=drive)
print(UrdfConverter(cfg).usd_path)
"""


def go2_usd(out: Path) -> str:
    """The Go2's USD from its URDF (joint gains 0: the task's DC motor
    actuators drive the joints)."""
    if not GO2_URDF.is_file():
        pytest.fail(f"{GO2_URDF}: missing; scripts/test-frameworks.sh copies Genesis's Go2 there")
    run = subprocess.run([sys.executable, "-c", CONVERT, str(GO2_URDF), str(out)], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    return run.stdout.strip().splitlines()[-1]


def task_cfg(scheme: Path, usd: str) -> UnitreeGo2RoughEnvCfg:
    cfg = UnitreeGo2RoughEnvCfg()
    cfg.seed = 1
    cfg.scene.num_envs = N_ENVS
    cfg.sim.device = "cpu"
    cfg.sim.physics = cfg.sim.physics.newton_mjwarp  # the task's Newton preset
    cfg.sim.physics.use_cuda_graph = False
    generator = cfg.scene.terrain.terrain_generator
    generator.size, generator.num_rows, generator.num_cols, generator.seed = (2.0, 2.0), 2, 2, 7
    rse.isaaclab.use_stepfield(cfg, scheme)
    cfg.scene.robot = replace(cfg.scene.robot, spawn=replace(cfg.scene.robot.spawn, usd_path=usd))
    cfg.scene.height_scanner.prim_path = "{ENV_REGEX_NS}/Robot/Geometry/base"
    cfg.scene.contact_forces.prim_path = "{ENV_REGEX_NS}/Robot/.*"
    return cfg


@pytest.fixture(scope="module")
def task(tmp_path_factory):
    folder = tmp_path_factory.mktemp("go2")
    scheme = folder / "scheme.csv"
    scheme.write_text(SCHEME)
    cfg = task_cfg(scheme, go2_usd(folder / "usd"))
    env = ManagerBasedRLEnv(cfg)
    mesh = TerrainGenerator(cfg.scene.terrain.terrain_generator, device="cpu").terrain_mesh
    yield env, mesh, cfg
    env.close()


@pytest.fixture(scope="module")
def stood(task):
    """Half a second of zero actions (the default joint pose) after a reset."""
    env, _, _ = task
    env.reset()
    for _ in range(25):
        env.step(torch.zeros(env.action_space.shape))
    return env


def tensor(value) -> np.ndarray:
    return (value.torch if hasattr(value, "torch") else torch.as_tensor(value)).cpu().numpy().astype(np.float64)


def test_the_generator_is_rse_and_the_tasks_other_terms_are_kept(task) -> None:
    env, _, cfg = task
    (tile,) = cfg.scene.terrain.terrain_generator.sub_terrains.values()
    assert isinstance(tile, rse.isaaclab.RseTerrainCfg) and tile.rank == 0
    assert "terrain_levels" in env.curriculum_manager.active_terms
    assert {"feet_air_time", "base_height_l2", "track_lin_vel_xy_exp"} <= set(env.reward_manager.active_terms)


def test_each_go2s_feet_touch_rse_mesh(task, stood) -> None:
    env, mesh, _ = task
    robot = env.scene["robot"]
    feet = [i for i, name in enumerate(robot.data.body_names) if name.endswith("_foot")]
    assert len(feet) == 4, robot.data.body_names
    pos = tensor(robot.data.body_pos_w)[:, feet].reshape(-1, 3)
    forces = np.linalg.norm(tensor(env.scene["contact_forces"].data.net_forces_w), axis=-1)
    sensor_names = env.scene["contact_forces"].sensor_names
    loaded = forces[:, [sensor_names.index(robot.data.body_names[i]) for i in feet]].reshape(-1) > 1.0
    assert loaded.sum() >= 2 * N_ENVS, f"most feet carry the robots: {loaded.reshape(N_ENVS, 4)}"
    _, distance, _ = trimesh.proximity.closest_point(mesh, pos[loaded])
    # 5 mm: the soft contact lets a 15 kg robot's feet sink a little.
    assert np.allclose(distance, FOOT_RADIUS, atol=5e-3), distance
    assert len(set(np.round(pos[loaded, 2], 3))) > 1, "the feet stand on different tops"


def test_the_height_scanner_sees_rse_tops(task, stood) -> None:
    env, mesh, _ = task
    hits = tensor(env.scene["height_scanner"].data.ray_hits_w).reshape(-1, 3)
    hits = hits[np.isfinite(hits).all(axis=1)]
    assert len(hits) > 100
    origins = np.column_stack([hits[:, :2], np.full(len(hits), 50.0)])
    locations, rays, _ = mesh.ray.intersects_location(origins, np.tile([0.0, 0.0, -1.0], (len(hits), 1)), multiple_hits=False)
    top = np.full(len(hits), np.nan)
    top[rays] = locations[:, 2]
    assert np.allclose(hits[:, 2], top, atol=1e-2, equal_nan=False), np.abs(hits[:, 2] - top).max()


def test_rsl_rl_ppo_runs_an_iteration_through_isaac_labs_wrapper(task, tmp_path) -> None:
    env, _, _ = task
    # As Isaac Lab's train script prepares it for the installed rsl-rl.
    agent = handle_deprecated_rsl_rl_cfg(UnitreeGo2RoughPPORunnerCfg(), metadata.version("rsl-rl-lib"))
    agent.max_iterations = 1
    runner = OnPolicyRunner(RslRlVecEnvWrapper(env), agent.to_dict(), str(tmp_path), device="cpu")
    runner.learn(num_learning_iterations=1)
    assert list(tmp_path.glob("model_*.pt")), "the runner saved its policy"
