"""No lost contacts on rse's terrains in mjlab's registered rough tasks
(`Rse-Velocity-Rough-Unitree-Go1`, `-G1`), with their default settings:
200 steps of random actions (an untrained policy's flailing and falls,
where contacts are most) raise no overflow in MuJoCo Warp (none flagged,
none printed); the robots' large geoms collide with each env's coarse
field, which holds that env's cells at their centres, and the feet with
the exact one. bench/mjlab_contacts.py gives the figures beside mjlab's own
terrain."""

from __future__ import annotations

import mjlab.tasks  # noqa: F401  (registers the tasks)
import mujoco
import numpy as np
import pytest
import rse
import torch
from mjlab.envs import ManagerBasedRlEnv
from mjlab.tasks.registry import load_env_cfg
from mujoco_warp._src.types import OverflowType
from rse._adapters import contacts
from rse._adapters.mjlab.env_cfg import NCON_HEADROOM, terrain_colliders
from rse._adapters.mjlab.scene_pool import GROUND_DROP
from rse.mjlab import env_terrains, use_env_terrains

NUM_ENVS = 16
STEPS = 200


def build(task: str, num_envs: int = NUM_ENVS) -> ManagerBasedRlEnv:
    cfg = load_env_cfg(task)
    cfg.scene.num_envs = num_envs
    # Short episodes: terrains renewed often, as in a long run's worst case.
    cfg.episode_length_s = 2.0
    env = ManagerBasedRlEnv(cfg, device="cpu")
    env.reset()
    return env


@pytest.mark.parametrize("robot", ["Go1", "G1"])
def test_no_contact_overflows_in_200_random_steps(robot, capfd) -> None:
    env = build(f"Rse-Velocity-Rough-Unitree-{robot}")
    gen = torch.Generator().manual_seed(0)
    flagged = []
    for step in range(STEPS):
        env.step(torch.rand(env.action_space.shape, generator=gen) * 2 - 1)
        flags = env.sim.wp_data.overflow.numpy()
        flagged += [(step, int(w), OverflowType(int(flags[w]))) for w in np.flatnonzero(flags)]
    env.close()
    printed = [line for line in capfd.readouterr().out.splitlines() if "overflow" in line]
    assert not flagged, f"{len(flagged)} world-steps overflowed, first: {flagged[:3]}"
    assert not printed, printed[:3]


def test_large_geoms_collide_with_each_envs_coarse_field_and_feet_with_the_exact() -> None:
    env = build("Rse-Velocity-Rough-Unitree-G1", num_envs=3)
    m = env.sim.mj_model
    envs = env_terrains(env)

    def geom(name: str) -> int:
        return mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, name)

    assert m.geom_contype[geom("robot/torso_collision")] & contacts.LARGE_BIT
    assert m.geom_contype[geom("robot/left_thigh_collision")] & contacts.LARGE_BIT
    for foot in range(1, 8):
        g = geom(f"robot/left_foot{foot}_collision")
        assert m.geom_contype[g] & contacts.SMALL_BIT and not m.geom_contype[g] & contacts.LARGE_BIT
    exact, coarse = geom("rse_terrain"), geom("rse_terrain_coarse")
    assert (m.geom_conaffinity[exact], m.geom_conaffinity[coarse]) == (contacts.SMALL_BIT, contacts.LARGE_BIT)
    # Per world, the coarse geom shows its own env's coarse field, which is
    # its cells' tops (MuJoCo's samples scaled by the elevation).
    dataid = env.sim.wp_model.geom_dataid.numpy()
    data = env.sim.wp_model.hfield_data.numpy()
    elevation = m.hfield_size[dataid[0, exact]][2]
    for w in range(envs.num_envs):
        h = int(dataid[w, coarse])
        assert mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_HFIELD, h) == f"rse_env_coarse{w}"
        t = envs.terrain(w)
        ny, nx = t.heights.shape
        samples = data[m.hfield_adr[h] : m.hfield_adr[h] + ny * nx].reshape(ny, nx)
        np.testing.assert_allclose(samples * elevation, t.heights * t.step_height, atol=1e-6)
        # The coarse samples sit at the cells' centres, where the exact
        # field's geom is centred.
        np.testing.assert_allclose(m.hfield_size[h][:2], [(nx - 1) * t.block_size / 2, (ny - 1) * t.block_size / 2])
    env.close()


@pytest.mark.parametrize("robot", ["Go1", "G1"])
def test_the_contact_budget_covers_the_fields_pairs_and_no_more(robot) -> None:
    cfg = load_env_cfg(f"Mjlab-Velocity-Rough-Unitree-{robot}")
    before = cfg.sim.nconmax
    colliders = terrain_colliders(cfg.scene)
    use_env_terrains(cfg, rse.Scheme.from_csv("# size: 20x20\ntype,height\nrandom,0..2\n"))
    # A broadphase pair per colliding geom with its env's field, a few more;
    # the task's own figure where that covers them (on the CPU each slot
    # costs every solver iteration time).
    assert cfg.sim.nconmax == max(before, colliders + NCON_HEADROOM)
    if robot == "Go1":
        assert (before, colliders, cfg.sim.nconmax) == (35, 30, 35)


def test_a_foot_on_the_terrain_touches_the_field_alone_not_the_plane_below() -> None:
    """The ground plane lies GROUND_DROP below the terrain's lowest top: a
    foot standing on a top at height 0 touched the plane too (twice the
    contacts at one point, twice the solver's work)."""
    cfg = load_env_cfg("Mjlab-Velocity-Rough-Unitree-Go1")
    cfg.scene.num_envs = 4
    # Difficulty 0: every env's terrain flat at height 0, the plane's old level.
    use_env_terrains(cfg, rse.Scheme.from_csv("# size: 40x40\ntype,height\nrandom,0..2\n"), difficulty=0.0)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    env.reset()
    m = env.sim.mj_model
    plane = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "terrain")
    field = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "rse_terrain")
    assert m.geom_type[plane] == mujoco.mjtGeom.mjGEOM_PLANE and m.geom_pos[plane][2] == pytest.approx(-GROUND_DROP)
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, g) or "" for g in range(m.ngeom)]
    feet = {g for g, n in enumerate(names) if n.endswith("_foot_collision")}
    d = env.sim.wp_data
    touched = 0
    for _ in range(25):
        env.step(torch.zeros(env.action_space.shape))
        n = int(d.nacon.numpy()[0])
        geom = d.contact.geom.numpy()[:n]
        on_feet = [tuple(g) for g in geom if feet & set(g.tolist())]
        assert not any(plane in g for g in on_feet), "a foot on the slot touched the plane under the terrain"
        touched += sum(field in g for g in on_feet)
    env.close()
    assert touched > 0, "the robots stood on nothing"


def test_arguments_are_checked_at_the_call_and_a_second_call_is_refused() -> None:
    scheme = rse.Scheme.from_csv("# size: 20x20\ntype,height\nrandom,0..2\n")
    cfg = load_env_cfg("Mjlab-Velocity-Rough-Unitree-Go1")
    with pytest.raises(ValueError, match="difficulty"):
        use_env_terrains(cfg, scheme, difficulty=1.5)
    with pytest.raises(ValueError, match="spawn_radius"):
        use_env_terrains(cfg, scheme, spawn_radius=-1.0)
    use_env_terrains(cfg, scheme)
    with pytest.raises(ValueError, match="called on it once"):
        use_env_terrains(cfg, scheme)
