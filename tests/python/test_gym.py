"""`rse.gym`: Gymnasium's Ant on a new stepfield every episode,
checked with Gymnasium's own env checker and with ray casts under the
robot; episode e's terrain is the same in fresh processes."""

import hashlib
import subprocess
import sys

import gymnasium as gym
import mujoco
import numpy as np
import pytest
import rse
import rse.gym
from conftest import SCHEMES
from gymnasium.utils.env_checker import check_env

SIX = str(SCHEMES / "six_obstacles.csv")


def make(**kwargs):
    return gym.make(rse.gym.ENV_ID, scheme=SIX, **kwargs)


# Cell centres around the start: the 50x50 field of 10 cm cells is centred
# on the origin, so cell (i, j) is centred at (-2.45 + 0.1 i, -2.45 + 0.1 j).
CELLS = np.arange(17, 34, 2)


def ground_under_robot(env) -> np.ndarray:
    """Ray casts straight down at 9x9 cell centres within 0.8 m of the
    start, hitting the terrain's geom only (group 2), as (y, x) rows."""
    model, data = env.unwrapped.model, env.unwrapped.data
    terrain = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "terrain")
    geomgroup = np.zeros(6, dtype=np.uint8)
    geomgroup[model.geom_group[terrain]] = 1
    hits = []
    geomid = np.zeros(1, dtype=np.int32)
    for y in -2.45 + 0.1 * CELLS:
        for x in -2.45 + 0.1 * CELLS:
            d = mujoco.mj_ray(model, data, np.array([x, y, 5.0]), np.array([0, 0, -1.0]), geomgroup, 1, -1, geomid)
            hits.append(5.0 - d if geomid[0] == terrain else np.nan)
    return np.array(hits)


def test_gymnasiums_env_checker_passes() -> None:
    env = make(difficulty=0.5)
    try:
        check_env(env.unwrapped, skip_render_check=True)  # no display here: rendering is not checked
    finally:
        env.close()


def test_every_reset_lays_a_new_terrain_under_the_robot_in_the_same_model() -> None:
    env = make()
    try:
        env.reset(seed=3)
        model = env.unwrapped.model
        seen = []
        for e in range(20):
            if e:
                _, info = env.reset()
            else:
                info = {"episode": 0}
            assert env.unwrapped.model is model  # no new model, no recompile
            assert info["episode"] == e
            ground = ground_under_robot(env)
            assert not np.isnan(ground).any()
            # The ground under the robot is the episode's world, exactly.
            terrain = rse.Scheme.load(SIX).generate(index=e)
            np.testing.assert_allclose(ground, terrain.elevation[np.ix_(CELLS, CELLS)].ravel(), atol=1e-5)
            assert env.unwrapped.data.qpos[2] == pytest.approx(terrain.spawn_origin(0.6)[2] + 0.75, abs=1e-9)
            seen.append(ground.round(4).tobytes())
        assert len(set(seen)) == 20
    finally:
        env.close()


def test_difficulty_zero_is_flat_ground() -> None:
    env = make(difficulty=0.0)
    try:
        env.reset(seed=0)
        np.testing.assert_allclose(ground_under_robot(env), 0.0, atol=1e-6)
    finally:
        env.close()


PROBE = """
import hashlib, gymnasium as gym, numpy as np, rse.gym, sys
sys.path.insert(0, {tests!r})
from test_gym import ground_under_robot
env = gym.make(rse.gym.ENV_ID, scheme={six!r})
env.reset(seed=1, options={{"episode": 7}})
print(hashlib.sha256(ground_under_robot(env).round(6).tobytes()).hexdigest())
"""


def test_episode_e_is_the_same_terrain_in_fresh_processes() -> None:
    from pathlib import Path

    code = PROBE.format(tests=str(Path(__file__).parent), six=SIX)
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()]
    runs.append(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip())
    env = make()
    try:
        env.reset(seed=9, options={"episode": 7})
        here = hashlib.sha256(ground_under_robot(env).round(6).tobytes()).hexdigest()
    finally:
        env.close()
    assert runs[0] == runs[1] == here


MISSING_ANT = """
import sys
sys.modules["gymnasium.envs.mujoco.ant_v5"] = None  # as without mujoco or imageio
import gymnasium as gym, rse.gym
assert rse.gym.ENV_ID in gym.registry, "registered all the same"
try:
    gym.make(rse.gym.ENV_ID)
except ImportError as e:
    print(e)
else:
    raise SystemExit("gym.make did not fail")
"""


def test_without_gymnasiums_mujoco_extras_make_names_the_install_line() -> None:
    # Once: nothing registered, and gym.make said "Namespace rse not found".
    said = subprocess.run([sys.executable, "-c", MISSING_ANT], capture_output=True, text=True, check=True).stdout
    assert rse.gym.ENV_ID in said and 'pip install "gymnasium[mujoco]"' in said, said
