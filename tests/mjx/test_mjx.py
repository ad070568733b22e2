"""`rse.mjx` inside MJX 3.17 (JAX, CPU): under ``jax.vmap``
each world's spheres come to rest on its own env's tops, and after
resetting some envs and syncing them, those worlds' spheres rest on the
new tops while the other worlds' come to rest exactly where they did, all
without tracing the jitted rollout again.

Runs in its own venv (.venv-mjx: MJX pins MuJoCo 3.17, .venv has 4.0);
scripts/test.sh runs it."""

from __future__ import annotations

import os
import sys
from pathlib import Path

os.environ.setdefault("JAX_PLATFORMS", "cpu")

import jax
import mujoco
import numpy as np
import pytest
import rse
import rse.mjx
from mujoco import mjx

SCHEME = rse.Scheme.from_csv(
    "# size: 10x8\n# base: 0.05\ntype,height,angle,x1,y1\nrandom,0..3,,,\npeak,2..5,45,2..7,2..5\n"
)
NWORLD = 4
SEED = 3
RESET = [1, 3]
# Block centres (column, row) the spheres drop on. A sphere of radius 2 cm
# at a block's centre touches only that block's flat top at k = 2 (its
# samples are 5 cm apart, the risers begin 2.5 cm from the centre).
BLOCKS = [(1, 1), (4, 2), (7, 5), (2, 6), (8, 3)]
RADIUS = 0.02
STEPS = 200


def model(envs: rse.EnvTerrains) -> tuple[mujoco.MjModel, mjx.Model]:
    spec = mujoco.MjSpec()
    spec.option.timestep = 0.005
    rse.mjx.add_terrain(spec, envs)
    s = envs.terrain(0).block_size
    for i, (c, r) in enumerate(BLOCKS):
        ball = spec.worldbody.add_body(name=f"ball{i}", pos=[(c + 0.5) * s, (r + 0.5) * s, 0.7])
        ball.add_freejoint()
        ball.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[RADIUS, 0, 0])
    mjm = spec.compile()
    return mjm, rse.mjx.put_model(mjm, envs)


def tops(envs: rse.EnvTerrains) -> np.ndarray:
    """Every world's top under every sphere: (NWORLD, len(BLOCKS))."""
    s = envs.terrain(0).block_size
    points = np.array([[(c + 0.5) * s, (r + 0.5) * s] for c, r in BLOCKS])
    return envs.heights_at(np.arange(NWORLD), np.broadcast_to(points, (NWORLD, len(BLOCKS), 2)))


def rollout(m: mjx.Model, qpos0: jax.Array) -> jax.Array:
    d = mjx.make_data(m).replace(qpos=qpos0)
    d, _ = jax.lax.scan(lambda d, _: (mjx.step(m, d), None), d, None, length=STEPS)
    return d.qpos


def resting_heights(roll, m: mjx.Model, mjm: mujoco.MjModel) -> np.ndarray:
    qpos = np.asarray(roll(m, jax.numpy.asarray(mjm.qpos0)))
    return qpos[:, 2::7]  # each free joint's z


def test_every_world_rests_on_its_own_env_and_a_reset_changes_only_its_worlds() -> None:
    envs = rse.EnvTerrains(SCHEME, NWORLD, oversample=2, seed=SEED)
    mjm, m = model(envs)
    roll = jax.jit(jax.vmap(rollout, in_axes=(rse.mjx.in_axes(m), None)))

    before = tops(envs)
    assert len({row.tobytes() for row in before}) == NWORLD, "every world its own terrain under the spheres"
    z = resting_heights(roll, m, mjm)
    assert np.allclose(z, before + RADIUS, atol=5e-3), (z, before)

    envs.reset(RESET)
    m = rse.mjx.sync(m, mjm, envs, RESET)
    after = tops(envs)
    z2 = resting_heights(roll, m, mjm)
    assert roll._cache_size() == 1, "sync must not trace the rollout again"
    assert np.allclose(z2, after + RADIUS, atol=5e-3), (z2, after)
    kept = [w for w in range(NWORLD) if w not in RESET]
    assert np.array_equal(z2[kept], z[kept]), "worlds not reset come to rest exactly as before"
    assert not np.allclose(after[RESET], before[RESET]), "the reset worlds have new tops"


def test_sync_writes_the_named_rows_only() -> None:
    envs = rse.EnvTerrains(SCHEME, NWORLD, oversample=2, seed=SEED)
    mjm, m = model(envs)
    before = np.asarray(m.hfield_data).copy()
    assert np.array_equal(before, envs.samples.reshape(NWORLD, -1))
    for ids in ([2], [0, 1, 3], None):
        envs.reset(range(NWORLD) if ids is None else ids)
        m = rse.mjx.sync(m, mjm, envs, ids)
        assert np.array_equal(np.asarray(m.hfield_data), envs.samples.reshape(NWORLD, -1))
    envs.reset([1])
    m = rse.mjx.sync(m, mjm, envs, [])  # nothing named, nothing written
    assert not np.array_equal(np.asarray(m.hfield_data)[1], envs.samples[1].ravel())


def test_bad_input_is_named() -> None:
    tiles = rse.EnvTerrains(SCHEME, 2, layout="tiles")
    with pytest.raises(ValueError, match="^envs"):
        rse.mjx.add_terrain(mujoco.MjSpec(), tiles)
    envs = rse.EnvTerrains(SCHEME, NWORLD)
    mjm, m = model(envs)
    with pytest.raises(ValueError, match="^env_ids"):
        rse.mjx.sync(m, mjm, envs, [NWORLD])
    with pytest.raises(ValueError, match="^mjm"):
        rse.mjx.put_model(mujoco.MjModel.from_xml_string("<mujoco/>"), envs)
    with pytest.raises(ValueError, match="^m: hfield_data"):
        rse.mjx.sync(mjx.put_model(mjm, impl="jax"), mjm, envs, [0])
    other = rse.EnvTerrains(SCHEME.replace(size=(12, 8)), NWORLD)
    with pytest.raises(ValueError, match="^mjm: height field"):
        rse.mjx.put_model(mjm, other)



def test_the_docs_example_runs_as_written(tmp_path) -> None:
    """docs/envs.md's ```python mjx block runs as written."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from envs_doc import run_example

    run_example("mjx", tmp_path)
