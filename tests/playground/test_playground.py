"""`rse.playground` inside MuJoCo Playground 0.2 on the CPU (.venv-playground,
make test-frameworks): its Go1 joystick rough-terrain task on rse's field,
every world its own terrain (MJX, JAX implementation). Each world's Go1's
feet rest on its own terrain as MuJoCo collides it; bad input is named; Brax's
PPO, with Playground's own wrapper and network settings, trains one
iteration on it."""

from __future__ import annotations

import functools

import jax

jax.config.update("jax_platforms", "cpu")

import jax.numpy as jp  # noqa: E402
import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
import rse  # noqa: E402
import rse.playground  # noqa: E402
from brax.training.agents.ppo import networks as ppo_networks  # noqa: E402
from brax.training.agents.ppo import train as ppo  # noqa: E402
from mujoco_playground import wrapper  # noqa: E402
from mujoco_playground.config import locomotion_params  # noqa: E402

# 3 m slots: 2.5 cm steps under a hill, around the Go1's spawn disc.
SCHEME = "# size: 30x30\n# block_size: 0.1\n# step_height: 0.025\ntype,height,angle,x1,y1\nrandom,0..2,,,\npeak,2..5,30,5..25,5..25\n"
N_ENVS = 4
STEPS = 50  # 1 s at the task's 50 Hz


def make_envs(n: int = N_ENVS, **kwargs) -> rse.EnvTerrains:
    return rse.EnvTerrains(rse.Scheme.from_csv(SCHEME), n, seed=2, spawn_radius=rse.playground.SPAWN_RADIUS, **kwargs)


@pytest.fixture(scope="module")
def task():
    envs = make_envs()
    env = rse.playground.go1_joystick(envs)
    return envs, env


@pytest.fixture(scope="module")
def rollout(task):
    """Each step's feet centres ``(N_ENVS, 4, 3)`` and Playground's own
    foot-floor contact sensors ``(N_ENVS, 4)`` over a second of zero
    actions (an untrained Go1 does not stand for long: Playground resets it
    with random velocities; it falls on flat ground too)."""
    envs, env = task
    vec = wrapper.wrap_for_brax_training(env, episode_length=1000, randomization_fn=rse.playground.terrains_fn(env, envs))
    state = jax.jit(vec.reset)(jax.random.split(jax.random.PRNGKey(0), N_ENVS))
    step = jax.jit(vec.step)
    adr = env.mj_model.sensor_adr[env._feet_floor_found_sensor]
    steps = []
    for _ in range(STEPS):
        state = step(state, jp.zeros((N_ENVS, env.action_size)))
        feet = np.asarray(state.data.geom_xpos)[:, env._feet_geom_id].astype(np.float64)
        found = np.asarray(state.data.sensordata)[:, adr] > 0
        steps.append((feet, found, np.asarray(state.done, dtype=bool)))
    return steps


def world_model(env, envs: rse.EnvTerrains, w: int) -> mujoco.MjModel:
    """World ``w``'s model on the CPU: env w's samples, its floor moved by
    -origins[w] (what terrains_fn batches)."""
    m = env.mj_model.__copy__()
    hid, gid = m.hfield(rse.playground.FIELD).id, m.geom(rse.playground.FLOOR).id
    adr = m.hfield_adr[hid]
    m.hfield_data[adr : adr + envs.samples[w].size] = envs.samples[w].ravel()
    m.geom_pos[gid] -= envs.origins[w]
    return m


def floor_distance(m: mujoco.MjModel, d: mujoco.MjData, centre: np.ndarray, reach: float) -> float:
    """The distance from ``centre`` (x, y, z) to the floor of ``m`` as
    MuJoCo triangulates it (rays down onto the floor geom every 1.5 mm
    within ``reach`` of the centre's x, y)."""
    gid = m.geom(rse.playground.FLOOR).id
    down = np.array([0.0, 0.0, -1.0])
    best = np.inf
    for dx in np.arange(-reach, reach + 1e-9, 1.5e-3):
        for dy in np.arange(-reach, reach + 1e-9, 1.5e-3):
            dist = mujoco.mj_rayHfield(m, d, gid, np.array([centre[0] + dx, centre[1] + dy, 10.0]), down)
            assert dist >= 0, "the ray hits the floor"
            best = min(best, np.sqrt(dx * dx + dy * dy + (centre[2] - (10.0 - dist)) ** 2))
    return best


def test_each_go1s_feet_rest_on_its_own_worlds_terrain(task, rollout) -> None:
    """Wherever Playground's contact sensors say a foot touches the floor,
    it touches its own world's terrain as MuJoCo triangulates rse's
    samples, within a step of rse's exact tops."""
    envs, env = task
    radius = float(env.mj_model.geom_size[env._feet_geom_id[0], 0])
    models = [world_model(env, envs, w) for w in range(N_ENVS)]
    datas = [mujoco.MjData(m) for m in models]
    for m, d in zip(models, datas):
        mujoco.mj_kinematics(m, d)
    touching = np.zeros(N_ENVS, dtype=int)
    own, others = [], []
    for feet, found, done in rollout[10::5]:  # after the drop, every 0.1 s
        for w, f in zip(*np.nonzero(found & ~done[:, None])):
            touching[w] += 1
            gaps = [floor_distance(models[v], datas[v], feet[w, f], radius + 0.01) - radius for v in range(N_ENVS)]
            # 1 cm: a moving 12 kg robot's feet sink into the soft contact.
            assert abs(gaps[w]) < 0.01, (w, f, feet[w, f], gaps[w])
            own.append(abs(gaps[w]))
            others += [abs(g) for v, g in enumerate(gaps) if v != w]
            # rse's tops in the world frame: origin w is at (0, 0, 0).
            o = envs.origins[w]
            top = envs.heights_at([w], (feet[w, f, :2] + o[:2])[None, None])[0, 0] - o[2]
            assert abs(feet[w, f, 2] - radius - top) <= envs.terrain(w).step_height + 0.01, (w, f, feet[w, f], top)
    assert np.all(touching >= 8), f"every world's feet touch its floor: {touching}"
    assert np.mean(own) < 3e-3 and np.mean(own) < np.mean(others) / 3, (np.mean(own), np.mean(others))
    assert len({tuple(np.round(envs.origins[w], 4)) for w in range(N_ENVS)}) > 1, "the worlds have other terrains"


def test_bad_input_is_named(task) -> None:
    envs, env = task
    with pytest.raises(ValueError, match="^envs"):
        rse.playground.go1_joystick(make_envs(layout="tiles"))
    with pytest.raises(ValueError, match="^num_envs"):
        rse.playground.terrains_fn(env, envs)(env.mjx_model, rng=jax.random.split(jax.random.PRNGKey(0), N_ENVS + 1))
    other = rse.EnvTerrains(rse.Scheme.from_csv("# size: 20x20\ntype,height\nrandom,0..2\n"), N_ENVS)
    with pytest.raises(ValueError, match="^env: height field .hfield. holds"):
        rse.playground.terrains_fn(env, other)


def test_brax_ppo_trains_an_iteration_on_it(task) -> None:
    envs, env = task
    cfg = locomotion_params.brax_ppo_config("Go1JoystickRoughTerrain")
    network = functools.partial(ppo_networks.make_ppo_networks, **cfg.network_factory)
    progress = []
    ppo.train(
        environment=env, num_timesteps=1, num_envs=N_ENVS, batch_size=N_ENVS, num_minibatches=1, unroll_length=5,
        num_updates_per_batch=1, episode_length=100, num_evals=1, num_eval_envs=N_ENVS, run_evals=False,
        network_factory=network,
        wrap_env_fn=wrapper.wrap_for_brax_training, randomization_fn=rse.playground.terrains_fn(env, envs),
        progress_fn=lambda steps, metrics: progress.append((steps, metrics)),
    )  # fmt: skip
    assert progress and progress[-1][0] > 0, progress
    assert np.isfinite(float(progress[-1][1]["training/policy_loss"])), progress[-1][1]
