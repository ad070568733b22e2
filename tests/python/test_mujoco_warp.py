"""`rse.mujoco_warp` inside MuJoCo Warp 4.0 on the CPU device:
each world stands on its own env's terrain (rays straight down in every
world over every cell centre, and a sphere resting on its world's top),
and after resetting some envs and syncing them, those worlds change and
the others do not."""

from __future__ import annotations

import mujoco
import mujoco_warp as mjw
import numpy as np
import rse
import rse.mujoco_warp
import warp as wp

SCHEME = rse.Scheme.from_csv(
    "# size: 10x8\n# base: 0.05\ntype,height,angle,x1,y1\nrandom,0..3,,,\npeak,2..5,45,2..7,2..5\n"
)
NWORLD = 4
RADIUS = 0.03


def model(envs: rse.EnvTerrains):
    spec = mujoco.MjSpec()
    spec.option.timestep = 0.005
    rse.mujoco_warp.add_terrain(spec, envs)
    ball = spec.worldbody.add_body(name="ball", pos=[0.35, 0.35, 1.0])
    ball.add_freejoint()
    ball.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[RADIUS, 0, 0])
    mjm = spec.compile()
    return mjm, rse.mujoco_warp.put_model(mjm, envs)


def centres(envs: rse.EnvTerrains) -> np.ndarray:
    ny, nx = envs.terrain(0).heights.shape
    s = envs.terrain(0).block_size
    ys, xs = np.mgrid[0:ny, 0:nx]
    return np.stack([(xs.ravel() + 0.5) * s, (ys.ravel() + 0.5) * s], axis=1)


def rays(m, d, points: np.ndarray) -> np.ndarray:
    """Each world's terrain top under every point: (NWORLD, P)."""
    p = len(points)
    origin = np.zeros((NWORLD, p, 3))
    origin[:, :, :2] = points
    origin[:, :, 2] = 3.0
    down = np.tile([0.0, 0.0, -1.0], (NWORLD, p, 1))
    dist = wp.zeros((NWORLD, p), dtype=float)
    geom = wp.zeros((NWORLD, p), dtype=int)
    normal = wp.zeros((NWORLD, p), dtype=wp.vec3)
    every_group = wp.types.vector(length=6, dtype=float)(*[-1.0] * 6)
    nobody = wp.array(np.full(p, -1, dtype=np.int32), dtype=int)
    mjw.rays(m, d, wp.array(origin, dtype=wp.vec3), wp.array(down, dtype=wp.vec3), every_group, True, nobody, dist, geom, normal)
    assert (geom.numpy() == 0).all(), "every ray hits the terrain geom"
    return 3.0 - dist.numpy()


def test_every_world_stands_on_its_own_env_and_a_reset_changes_only_its_worlds() -> None:
    envs = rse.EnvTerrains(SCHEME, NWORLD, oversample=2, seed=4)
    mjm, m = model(envs)
    d = mjw.make_data(mjm, nworld=NWORLD, nconmax=32, njmax=64)
    # The ball far away while the rays look at the terrain.
    qpos = d.qpos.numpy()
    qpos[:, 0:3] = [50.0, 50.0, 5.0]
    d.qpos.assign(qpos)
    mjw.kinematics(m, d)
    points = centres(envs)
    expected = np.stack([envs.heights_at([w], points[None])[0] for w in range(NWORLD)])
    seen = rays(m, d, points)
    assert np.allclose(seen, expected, atol=1e-4)
    assert len({row.tobytes() for row in np.round(seen, 6)}) == NWORLD, "every world its own terrain"

    envs.reset([1, 3])
    rse.mujoco_warp.sync(m, mjm, envs, [1, 3])
    after = rays(m, d, points)
    expected = np.stack([envs.heights_at([w], points[None])[0] for w in range(NWORLD)])
    assert np.allclose(after, expected, atol=1e-4)
    assert np.array_equal(after[[0, 2]], seen[[0, 2]]), "worlds 0 and 2 untouched"
    assert not np.allclose(after[1], seen[1]) and not np.allclose(after[3], seen[3])


def test_a_ball_rests_on_its_worlds_top() -> None:
    envs = rse.EnvTerrains(SCHEME, NWORLD, oversample=2, seed=8)
    mjm, m = model(envs)
    d = mjw.make_data(mjm, nworld=NWORLD, nconmax=32, njmax=64)
    mjw.reset_data(m, d)
    for _ in range(300):
        mjw.step(m, d)
    z = d.qpos.numpy()[:, 2]
    tops = np.array([envs.heights_at([w], [[[0.35, 0.35]]])[0, 0] for w in range(NWORLD)])
    assert np.allclose(z, tops + RADIUS, atol=5e-3), (z, tops)
    assert len(set(np.round(tops, 6))) > 1, "the worlds' tops differ under the ball"


def test_bad_input_is_named() -> None:
    import pytest

    tiles = rse.EnvTerrains(SCHEME, 2, layout="tiles")
    with pytest.raises(ValueError, match="^envs"):
        rse.mujoco_warp.add_terrain(mujoco.MjSpec(), tiles)
    envs = rse.EnvTerrains(SCHEME, NWORLD)
    mjm, m = model(envs)
    with pytest.raises(ValueError, match="^env_ids"):
        rse.mujoco_warp.sync(m, mjm, envs, [NWORLD])
    with pytest.raises(ValueError, match="^mjm"):
        rse.mujoco_warp.put_model(mujoco.MjModel.from_xml_string("<mujoco/>"), envs)


def test_the_gpus_one_upload_writes_what_the_cpus_view_writes() -> None:
    """``copy_rows`` on a GPU gathers the rows, uploads them once and
    scatters them with one kernel; on the CPU it writes a numpy view. The
    kernel, forced on the CPU device, writes the same floats at the same
    starts, and nothing else."""
    from rse._adapters.warp_fields import copy_rows

    rows = np.arange(5 * 7, dtype=np.float32).reshape(5, 7) + 0.25
    pairs = [(3, 40), (0, 2), (4, 19)]
    written = []
    for scatter in (False, True):
        dst = wp.array(np.full(60, -1.0, dtype=np.float32), dtype=wp.float32, device="cpu")
        copy_rows(dst, rows, pairs, scatter=scatter)
        written.append(dst.numpy().copy())
    expected = np.full(60, -1.0, dtype=np.float32)
    for r, start in pairs:
        expected[start : start + 7] = rows[r]
    assert np.array_equal(written[0], expected) and np.array_equal(written[1], expected)


def test_a_resets_blocks_go_into_two_arrays_the_same_either_way() -> None:
    """``Uploads`` (mjlab's reset: samples into ``hfield_data``, boxes
    into ``geom_aabb``) writes each block's rows (picked, in order, or
    filling themselves) at their starts in its own target, and nothing
    else: the GPU's way (one upload of the rows and their places, one
    kernel a send), forced on the CPU device, writes what the CPU's numpy
    views write, over calls that grow its buffers and reuse them, and
    with buffers too small for a call (several sends; a row longer than
    them alone), which never grow past their limit."""
    from rse._adapters.uploads import Filled, Uploads

    rng = np.random.default_rng(4)
    pool = rng.random((5, 7), dtype=np.float32)

    def fill(ids: list[int]) -> Filled:
        def rows(data: np.ndarray, at: np.ndarray, part: slice) -> None:
            for e, start in zip(ids[part], at):
                data[start : start + 7] = pool[e]

        return Filled(7, rows)

    calls = [
        [(0, [40, 2], pool, [3, 0]), (1, [3], rng.random((1, 6), dtype=np.float32), None), (0, [60], rng.random((1, 25), dtype=np.float32), None)],
        [(1, [20], rng.random((1, 6), dtype=np.float32), None), (0, [], pool, [])],
        [(0, [100], rng.random((1, 90), dtype=np.float32), None), (1, [0, 30], rng.random((2, 3), dtype=np.float32), None), (0, [10, 20, 30], pool, [4, 4, 1])],
        [(0, [150, 160, 170, 180], fill([2, 0, 4, 4]), None), (1, [8, 14], rng.random((2, 6), dtype=np.float32), None)],
    ]
    written = []
    for kernel, limit in ((False, Uploads.LIMIT), (True, Uploads.LIMIT), (True, 30), (True, 7), (True, 1)):
        targets = [wp.array(np.full(200, -1.0, dtype=np.float32), device="cpu"), wp.array(np.full(40, -2.0, dtype=np.float32), device="cpu")]
        uploads = Uploads(kernel=kernel, limit=limit)
        for blocks in calls:
            uploads.write(targets, blocks)
            # Values (the longest row alone may pass the limit) and their
            # places (a value a run at least, four int32 a run).
            assert uploads.device_bytes() <= 4 * max(limit, 90) + 16 * limit, (limit, uploads.device_bytes())
        written.append([t.numpy().copy() for t in targets])
    expected = [np.full(200, -1.0, dtype=np.float32), np.full(40, -2.0, dtype=np.float32)]
    for blocks in calls:
        for t, starts, rows, picks in blocks:
            for i, start in enumerate(starts):
                row = pool[[2, 0, 4, 4][i]] if isinstance(rows, Filled) else rows[i if picks is None else picks[i]]
                expected[t][start : start + len(row)] = row
    for got in written:
        assert all(np.array_equal(a, b) for a, b in zip(got, expected))


def test_the_upload_buffers_hold_what_staging_says_a_first_write_leaves() -> None:
    """``staging`` (the estimate of a reset's upload buffers before a
    scene is built) gives the values and runs ``Uploads`` holds buffers
    for after its first write, under its limit or over it."""
    from rse._adapters.uploads import Uploads, staging

    rng = np.random.default_rng(5)
    for limit, n in ((Uploads.LIMIT, 4), (100, 9), (25, 3), (10, 2)):
        rows = [rng.random((n, 20), dtype=np.float32), rng.random((n, 5), dtype=np.float32), rng.random((2 * n, 6), dtype=np.float32)]
        blocks = [(0, 20 * np.arange(n), rows[0], None), (0, 500 + 5 * np.arange(n), rows[1], None), (1, 6 * np.arange(2 * n), rows[2], None)]
        targets = [wp.zeros(600, dtype=wp.float32, device="cpu"), wp.zeros(200, dtype=wp.float32, device="cpu")]
        uploads = Uploads(kernel=True, limit=limit)
        uploads.write(targets, blocks)
        values, runs = staging([(20, n), (5, n), (6, 2 * n)], limit)
        assert uploads.device_bytes() == 4 * values + 16 * runs, (limit, n)
        assert values <= max(limit, 20)
