"""`rse.genesis` inside Genesis 1.4.5 on the CPU, in its own
venv (.venv-genesis, make test-frameworks): each env's ball rests on its
own tile of the shared terrain; after resetting some envs and rewriting the
field in the built scene, those envs' balls rest on their new tops and the
others exactly where they did; Genesis's own height query sees the new
map."""

from __future__ import annotations

import sys
from pathlib import Path

import genesis as gs
import numpy as np
import pytest
import rse
import rse.genesis

SCHEME = rse.Scheme.from_csv(
    "# size: 10x8\n# base: 0.05\ntype,height,angle,x1,y1\nrandom,0..3,,,\npeak,2..5,45,2..7,2..5\n"
)
N_ENVS = 4
RESET = [1, 2]
RADIUS = 0.02
# Each env's ball drops on the centre of the block beside its origin (the
# tile's centre, a block corner here): on a block centre at k = 2 a 2 cm
# ball touches that block's flat top only.
OFFSET = np.array([0.05, 0.05])
STEPS = 150


@pytest.fixture(scope="module")
def world():
    gs.init(backend=gs.cpu, logging_level="warning", precision="32")
    envs = rse.EnvTerrains(SCHEME, N_ENVS, layout="tiles", cols=2, border=2, seed=4)
    scene = gs.Scene(sim_options=gs.options.SimOptions(dt=0.005), show_viewer=False)
    terrain = scene.add_entity(rse.genesis.terrain_morph(envs))
    ball = scene.add_entity(gs.morphs.Sphere(radius=RADIUS, pos=(0.0, 0.0, 1.0)))
    scene.build(n_envs=N_ENVS)
    yield envs, scene, terrain, ball
    gs.destroy()


def drop(scene, ball, envs: rse.EnvTerrains) -> np.ndarray:
    """Resets the scene, drops each env's ball over its origin's block, and
    returns where they rest."""
    scene.reset()
    start = np.zeros((N_ENVS, 3), dtype=np.float32)
    start[:, :2] = envs.origins[:, :2] + OFFSET
    start[:, 2] = envs.origins[:, 2] + 0.2
    ball.set_pos(start)
    for _ in range(STEPS):
        scene.step()
    return ball.get_pos().cpu().numpy().astype(np.float64)


def tops(envs: rse.EnvTerrains, pos: np.ndarray) -> np.ndarray:
    return np.array([envs.heights_at([e], pos[e : e + 1, None, :2])[0, 0] for e in range(N_ENVS)])


def test_each_env_rests_on_its_tile_and_a_rewrite_changes_only_the_reset_envs(world) -> None:
    envs, scene, terrain, ball = world
    before = drop(scene, ball, envs)
    assert np.allclose(before[:, :2], envs.origins[:, :2] + OFFSET, atol=2e-3)
    assert np.allclose(before[:, 2], tops(envs, before) + RADIUS, atol=5e-3), (before, tops(envs, before))
    assert len(set(np.round(before[:, 2], 4))) > 1, "the envs stand on different tiles"

    old = tops(envs, before)
    envs.reset(RESET)
    rse.genesis.sync(scene, terrain, envs)
    after = drop(scene, ball, envs)
    new = tops(envs, after)
    assert not np.allclose(new[RESET], old[RESET]), "the reset envs' tops changed under their balls"
    assert np.allclose(after[:, 2], new + RADIUS, atol=5e-3), (after, new)
    kept = [e for e in range(N_ENVS) if e not in RESET]
    assert np.allclose(after[kept], before[kept], atol=1e-5), "the other envs' balls rest where they did"

    points = after[:, :2]
    seen = terrain.get_terrain_height(points).cpu().numpy().reshape(-1)[: N_ENVS]
    assert np.allclose(seen, new, atol=1e-5), "Genesis's own height query sees the rewritten map"


def test_a_reset_writes_its_envs_tiles_alone_and_leaves_what_a_whole_rewrite_would(world, monkeypatch) -> None:
    """``rse.genesis.reset`` writes the reset envs' tiles into Genesis's
    own field (a torch view of it) where the map was rewritten whole
    once: the collider's field, its bounds and the height queries end as
    a whole rewrite leaves them, and the balls rest on the new tops."""
    envs, scene, terrain, ball = world
    info = scene.sim.rigid_solver.collider.collider_info
    rse.genesis.sync(scene, terrain, envs)
    before = drop(scene, ball, envs)

    def whole(*_: object) -> None:
        raise AssertionError("the whole map was written")

    monkeypatch.setattr(info.terrain_hf, "from_numpy", whole)
    mask = np.zeros(N_ENVS, dtype=bool)
    mask[[0, 3]] = True
    assert list(rse.genesis.reset(scene, terrain, envs, mask)) == [0, 3]
    monkeypatch.undo()

    new = rse.genesis.heights(envs)
    assert np.array_equal(info.terrain_hf.to_numpy(), new), "the collider's field is the new map"
    bounds = info.terrain_xyz_maxmin.to_numpy()
    assert (bounds[2], bounds[5]) == (new.max(), new.min() - 1.0), "the bounds Genesis sets at build"
    assert np.array_equal(terrain._terrain_height_field.cpu().numpy(), new)

    after = drop(scene, ball, envs)
    tops_now = tops(envs, after)
    assert np.allclose(after[:, 2], tops_now + RADIUS, atol=5e-3), (after, tops_now)
    assert np.allclose(after[[1, 2]], before[[1, 2]], atol=1e-5), "the other envs' balls rest where they did"
    seen = terrain.get_terrain_height(after[:, :2]).cpu().numpy().reshape(-1)[:N_ENVS]
    assert np.allclose(seen, tops_now, atol=1e-5)


def test_bad_input_is_named(world) -> None:
    envs, scene, terrain, _ = world
    with pytest.raises(ValueError, match="^envs"):
        rse.genesis.terrain_morph(rse.EnvTerrains(SCHEME, 2))
    other = rse.EnvTerrains(SCHEME, N_ENVS + 2, layout="tiles", cols=2, border=2)
    with pytest.raises(ValueError, match="^terrain"):
        rse.genesis.sync(scene, terrain, other)



def test_the_docs_example_runs_as_written(tmp_path) -> None:
    """docs/envs.md's ```python genesis block runs as written."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from envs_doc import run_example

    run_example("genesis", tmp_path)
