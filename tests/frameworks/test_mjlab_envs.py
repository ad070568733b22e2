"""`rse.mjlab.use_env_terrains` inside mjlab's own `ManagerBasedRlEnv`,
its simulation (MuJoCo Warp) on the CPU device: a ball dropped
at each env's origin rests on that env's own terrain; resetting some envs
through `env.reset(env_ids=...)` gives them new terrains (the balls rest on
the new tops, the other worlds' balls and fields stay as they were); the
curriculum term moves the difficulty of the envs that reset, and the next
terrains are drawn at it."""

from __future__ import annotations

import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest
import rse
import torch
from mjlab.entity import EntityCfg
from mjlab.envs import ManagerBasedRlEnv, ManagerBasedRlEnvCfg
from mjlab.scene import SceneCfg
from rse.mjlab import EnvTerrainsEvent, env_terrains, use_env_terrains

SCHEME = rse.Scheme.from_csv(
    "# size: 10x8\n# base: 0.05\ntype,height,angle,x1,y1\nrandom,0..3,,,\npeak,2..5,45,2..7,2..5\n"
)
NUM_ENVS = 4
RADIUS = 0.02
# The ball starts above the centre of the block beside each env's origin
# (the slot's centre, a block corner here): on a block centre at k = 2 a
# 2 cm ball touches that block's flat top only.
DROP = (0.05, 0.05, 0.2)


def ball() -> mujoco.MjSpec:
    spec = mujoco.MjSpec()
    body = spec.worldbody.add_body(name="ball")
    body.add_freejoint()
    body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[RADIUS, 0, 0])
    return spec


def make_env(**options) -> ManagerBasedRlEnv:
    cfg = ManagerBasedRlEnvCfg(
        decimation=4,
        scene=SceneCfg(
            num_envs=NUM_ENVS,
            entities={"robot": EntityCfg(spec_fn=ball, init_state=EntityCfg.InitialStateCfg(pos=DROP))},
        ),
    )
    use_env_terrains(cfg, SCHEME, seed=11, **options)
    return ManagerBasedRlEnv(cfg, device="cpu")


def settle(env: ManagerBasedRlEnv, steps: int = 60) -> np.ndarray:
    """Steps with no actions; every env's ball position."""
    for _ in range(steps):
        env.step(torch.zeros((env.num_envs, 0)))
    return env.scene["robot"].data.root_link_pos_w.cpu().numpy().astype(np.float64)


def under(envs: rse.EnvTerrains, pos: np.ndarray) -> np.ndarray:
    return np.array([envs.heights_at([e], pos[e : e + 1, None, :2])[0, 0] for e in range(len(pos))])


@pytest.fixture(scope="module")
def env():
    env = make_env()
    yield env
    env.close()


def test_each_ball_rests_on_its_envs_terrain_and_a_reset_renews_only_the_named(env) -> None:
    envs = env_terrains(env)
    env.reset()
    assert envs.episode.tolist() == [1] * NUM_ENVS
    origins = env.scene.env_origins.cpu().numpy()
    assert np.allclose(origins, envs.origins, atol=1e-6)
    pos = settle(env)
    assert np.allclose(pos[:, :2], origins[:, :2] + DROP[:2], atol=2e-3), "each ball comes down where it was dropped"
    assert np.allclose(pos[:, 2], under(envs, pos) + RADIUS, atol=5e-3), (pos, under(envs, pos))
    assert len(set(np.round(pos[:, 2], 4))) > 1, "the worlds stand on different terrains"
    samples = envs.samples.copy()

    env.reset(env_ids=torch.tensor([1, 2]))
    assert envs.episode.tolist() == [1, 2, 2, 1]
    assert np.array_equal(envs.samples[[0, 3]], samples[[0, 3]])
    assert not np.array_equal(envs.samples[1], samples[1]) and not np.array_equal(envs.samples[2], samples[2])
    hfield = env.sim.wp_model.hfield_data.numpy()
    adr = env.sim.mj_model.hfield_adr
    first = mujoco.mj_name2id(env.sim.mj_model, mujoco.mjtObj.mjOBJ_HFIELD, "rse_env0")
    for e in range(NUM_ENVS):
        slot = hfield[adr[first + e] : adr[first + e] + envs.samples[e].size]
        assert np.array_equal(slot, envs.samples[e].ravel()), f"env {e}'s field in the simulation"
    after = settle(env)
    assert np.allclose(after[[0, 3]], pos[[0, 3]], atol=1e-4), "worlds 0 and 3 untouched"
    assert np.allclose(after[:, 2], under(envs, after) + RADIUS, atol=5e-3)


def test_every_env_terrain_is_the_pure_function_of_its_id_and_episode(env) -> None:
    envs = env_terrains(env)
    twin = rse.EnvTerrains(SCHEME, NUM_ENVS, seed=11)
    for e in range(NUM_ENVS):
        for _ in range(int(envs.episode[e])):
            twin.reset([e])
    assert np.array_equal(twin.samples, envs.samples)


def test_the_curriculum_moves_the_difficulty_of_the_envs_that_reset() -> None:
    env = make_env(curriculum=True, difficulty=0.5)
    try:
        envs = env_terrains(env)
        env.reset()
        assert envs.difficulty.tolist() == [0.5] * NUM_ENVS, "frozen at the first reset"
        settle(env, 10)  # the balls stay near their origins: they walked less than a quarter slot
        env.reset(env_ids=torch.tensor([0, 3]))
        assert np.allclose(envs.difficulty, [0.4, 0.5, 0.5, 0.4])
        twin = rse.EnvTerrains(SCHEME, NUM_ENVS, seed=11, difficulty=0.5)
        twin.reset([0, 1, 2, 3])
        twin.reset([0, 3], difficulty=[0.4, 0.4])
        assert np.array_equal(twin.samples, envs.samples), "the new terrains are drawn at the new difficulty"
    finally:
        env.close()


def test_bad_configurations_are_named() -> None:
    from mjlab.terrains import TerrainEntityCfg

    # mjlab's own terrain is replaced; anything else in its place is named.
    cfg = ManagerBasedRlEnvCfg(decimation=1, scene=SceneCfg(num_envs=2, terrain=TerrainEntityCfg()))
    use_env_terrains(cfg, SCHEME)
    assert type(cfg.scene.terrain).__name__ == "EnvTerrainCfg" and cfg.scene.terrain.scheme == SCHEME.to_csv()
    cfg = ManagerBasedRlEnvCfg(decimation=1, scene=SceneCfg(num_envs=2, terrain="a mesh of my own"))
    with pytest.raises(ValueError, match="^env_cfg.scene.terrain: a str is not"):
        use_env_terrains(cfg, SCHEME)
    cfg = ManagerBasedRlEnvCfg(decimation=1, scene=SceneCfg(num_envs=2, entities={"terrain": EntityCfg(spec_fn=ball)}))
    with pytest.raises(ValueError, match=r"^env_cfg.scene.entities\['terrain'\]"):
        use_env_terrains(cfg, SCHEME)
    cfg.scene.entities = {}
    with pytest.raises(OSError, match="no/such/scheme.csv"):
        use_env_terrains(cfg, Path("no/such/scheme.csv"))
    assert isinstance(EnvTerrainsEvent, type)


def test_the_pool_is_the_one_of_the_config_mjlab_builds_whatever_copied_it() -> None:
    """The scene's ``spec_fn`` is bound to the scene config that holds it,
    read afresh: the copy tyro makes from the command line (as ``train``
    does), ``dataclasses.replace`` and ``copy.deepcopy`` each build the
    pool of their own settings, with the task's own ``spec_fn`` run first,
    and a logged config has the scene once (nothing read off the stack)."""
    import copy
    import dataclasses

    import mjlab
    import tyro
    import yaml

    calls = []
    cfg = ManagerBasedRlEnvCfg(
        decimation=1,
        scene=SceneCfg(num_envs=2, entities={"robot": EntityCfg(spec_fn=ball)}, spec_fn=lambda spec: calls.append(spec)),
    )
    use_env_terrains(cfg, SCHEME, seed=3)
    built = tyro.cli(type(cfg), args=["--scene.num-envs", "3", "--scene.terrain.seed", "9"], default=cfg, config=mjlab.TYRO_FLAGS)
    assert type(built.scene) is type(cfg.scene) and built.scene.spec_fn.scene is built.scene
    env = ManagerBasedRlEnv(built, device="cpu")
    try:
        envs = env_terrains(env)
        assert envs.num_envs == 3 and envs.terrain(0).seed == rse.EnvTerrains(SCHEME, 1, seed=9).terrain(0).seed
        assert len(calls) == 1, "the task's own spec_fn ran first, once"
    finally:
        env.close()
    deep = copy.deepcopy(cfg)
    assert deep.scene.spec_fn.scene is deep.scene and deep.scene.terrain is not cfg.scene.terrain
    moved = dataclasses.replace(cfg.scene, num_envs=5)
    assert moved.spec_fn.scene is moved and moved.spec_fn.earlier is cfg.scene.spec_fn.earlier
    logged = yaml.dump(dataclasses.asdict(cfg))
    assert "spec_fn: !!python/object:rse._adapters.mjlab.spec_fn.PoolSpec" in logged
    assert logged.count("scheme_sha256:") == 1, "the scene once in the logged config, not again in its spec_fn"



def test_the_docs_example_runs_as_written(tmp_path) -> None:
    """docs/envs.md's ```python mjlab block runs as written."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from envs_doc import run_example

    run_example("mjlab", tmp_path)


def test_each_launched_process_draws_other_terrains(monkeypatch) -> None:
    """A launcher's RANK sets the env offset (explicit env_offset wins): two
    processes of 4 envs are the terrains of one of 8."""
    whole = rse.EnvTerrains(SCHEME, 2 * NUM_ENVS, seed=11)
    monkeypatch.setenv("RANK", "1")
    env = make_env()
    try:
        envs = env_terrains(env)
        for e in range(NUM_ENVS):
            assert np.array_equal(envs.terrain(e).heights, whole.terrain(NUM_ENVS + e).heights), e
    finally:
        env.close()
    env = make_env(env_offset=0)
    try:
        assert np.array_equal(env_terrains(env).terrain(0).heights, whole.terrain(0).heights)
    finally:
        env.close()
    monkeypatch.setenv("RANK", "one")
    with pytest.raises(ValueError, match="^RANK"):
        make_env()
