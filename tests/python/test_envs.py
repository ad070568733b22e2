"""Every environment its own terrain, new every episode:
`rse.EnvTerrains` — each env's terrain a pure function of (scheme, seed,
global id, episode, difficulty), resets that touch the named envs only, and
its samples, sizes and origins read back in MuJoCo by ray casts, as a pool
of height fields (slots) and as one tiled field (tiles)."""

from __future__ import annotations

import io

import mujoco
import numpy as np
import pytest
import rse
import rse.mujoco
from conftest import SCHEMES

SIX = rse.Scheme.load(SCHEMES / "six_obstacles.csv")
SMALL = rse.Scheme.from_csv(
    "# size: 12x10\n# base: 0.05\ntype,height,angle,x1,y1\nrandom,0..3,,,\npeak,2..5,45,2..9,2..7\n"
)


def test_a_terrain_is_its_env_episode_and_difficulty_alone() -> None:
    a = rse.EnvTerrains(SMALL, 6, seed=3)
    b = rse.EnvTerrains(SMALL, 6, seed=3)
    a.reset([0, 4])
    a.reset([1, 4], difficulty=[0.5, 0.25])
    a.reset([5], difficulty=0.0)
    b.reset([5, 4, 1, 0, 4], difficulty=[0.0, 1.0, 0.5, 1.0, 0.25])
    assert a.episode.tolist() == b.episode.tolist() == [1, 1, 0, 0, 2, 1]
    assert np.array_equal(a.samples, b.samples)
    assert np.array_equal(a.origins, b.origins)
    for e in range(6):
        k = int(a.episode[e])
        alone = SMALL.generate(seed=3, index=k * 2**32 + e, difficulty=float(a.difficulty[e]))
        assert np.array_equal(a.terrain(e).heights, alone.heights), e
    # Global ids: 2 processes of 3 envs are one of 6.
    second = rse.EnvTerrains(SMALL, 3, seed=3, env_offset=3)
    second.reset([2])
    fresh = rse.EnvTerrains(SMALL, 6, seed=3)
    fresh.reset([5])
    assert np.array_equal(second.terrain(2).heights, fresh.terrain(5).heights)
    assert np.array_equal(second.samples[2], fresh.samples[5])


def test_a_reset_touches_the_named_envs_only() -> None:
    envs = rse.EnvTerrains(SIX, 8, oversample=2, seed=1)
    before = envs.samples.copy()
    origins = envs.origins.copy()
    envs.reset(np.array([2, 6]))
    changed = [e for e in range(8) if not np.array_equal(envs.samples[e], before[e])]
    assert changed == [2, 6]
    assert np.array_equal(envs.origins[[0, 1, 3, 4, 5, 7]], origins[[0, 1, 3, 4, 5, 7]])
    assert envs.episode.tolist() == [0, 0, 1, 0, 0, 0, 1, 0]
    assert envs.samples.dtype == np.float32 and envs.samples.min() >= 0 and envs.samples.max() <= 1
    # The difficulty is the curriculum's knob: set, then used at the next reset.
    envs.difficulty = np.linspace(0, 1, 8)
    envs.reset([0])
    assert envs.terrain(0).difficulty == 0.0 and envs.terrain(0).heights.max() <= 1  # frames only
    envs.difficulty[1] = 0.5  # in place, too
    envs.reset([1])
    assert envs.terrain(1).difficulty == 0.5


@pytest.mark.parametrize(
    "mask",
    [[True, False, True, False], np.array([True, False, True, False]), (True, False, True, False)],
    ids=["list", "numpy", "tuple"],
)
def test_a_boolean_mask_means_the_envs_where_it_is_true(mask) -> None:
    """True and False are 1 and 0 to Python: read as numbers the mask reset
    envs 1, 0, 1, 0 and left env 2 alone. One rule in the extension and in
    every adapter (`rse._adapters.ids.env_ids`)."""
    from rse._adapters.ids import env_ids

    envs = rse.EnvTerrains(SMALL, 4, seed=2)
    envs.reset(mask)
    assert envs.episode.tolist() == [1, 0, 1, 0]
    assert env_ids(4, mask) == [0, 2]
    assert envs.heights_at(mask, np.zeros((2, 1, 2))).shape == (2, 1)
    for wrong in ([True, False], np.ones((2, 2), bool)):
        with pytest.raises(ValueError, match="^env_ids: a boolean mask"):
            envs.reset(wrong)
        with pytest.raises(ValueError, match="^env_ids: a mask"):
            env_ids(4, wrong)
    assert envs.episode.tolist() == [1, 0, 1, 0], "a refused mask changes nothing"


def test_bad_arguments_name_themselves() -> None:
    envs = rse.EnvTerrains(SMALL, 4)
    cases = [
        (lambda: envs.reset([4]), "env_ids"),
        (lambda: envs.reset([-1]), "env_ids"),
        (lambda: envs.reset(b"\x01\x02"), "env_ids"),
        (lambda: envs.reset(bytearray(b"\x01")), "env_ids"),
        (lambda: envs.reset("12"), "env_ids"),
        (lambda: envs.reset([0, 1], difficulty=[0.5]), "difficulty"),
        (lambda: envs.reset([0], difficulty=1.5), "difficulty"),
        (lambda: setattr(envs, "difficulty", [0.5] * 3), "difficulty"),
        (lambda: setattr(envs, "difficulty", [0.5, 0.5, 0.5, 2.0]), "difficulty"),
        (lambda: envs.write(np.zeros((4, 5, 5), np.float32)), "out"),
        (lambda: envs.write(np.zeros(envs.samples.shape, np.float64)), "out"),
        (lambda: envs.write(np.zeros(envs.samples.shape[::-1], np.float32).T), "out"),
        (lambda: envs.heights_at([0], np.zeros((2, 3, 2))), "points"),
        (lambda: envs.terrain(9), "env"),
        (lambda: rse.EnvTerrains(SMALL, 0), "num_envs"),
        (lambda: rse.EnvTerrains(SMALL, 2, layout="grid"), "layout"),
        (lambda: rse.EnvTerrains(SMALL, 2, cols=2), "cols"),
        (lambda: rse.EnvTerrains(SMALL, 2, env_offset=2**32 - 1), "env_offset"),
    ]
    for call, argument in cases:
        with pytest.raises(ValueError, match=f"^{argument}"):
            call()
    assert envs.episode.tolist() == [0, 0, 0, 0], "nothing changed"


def test_every_buffer_of_bytes_is_refused_as_ids_and_bools_as_difficulties() -> None:
    """Fifth hardening round: a memoryview of b"\\x00\\x03" was read as envs
    0 and 3 (bytes were refused), and difficulty=[True, False] as 1.0 and
    0.0. One rule for every buffer; a bool is never a difficulty."""
    from rse._adapters.ids import env_ids

    envs = rse.EnvTerrains(SMALL, 4)
    for raw in (b"\x00\x03", bytearray(b"\x00\x03"), memoryview(b"\x00\x03"), memoryview(bytearray(b"\x03"))):
        with pytest.raises(ValueError, match="^env_ids: expected a sequence of environment numbers"):
            envs.reset(raw)
        with pytest.raises(ValueError, match="^env_ids: expected a sequence of environment numbers"):
            env_ids(4, raw)
    for flags in ([True, False], np.array([True, False]), True, np.bool_(False)):
        with pytest.raises(TypeError, match="^difficulty: expected a number from 0 to 1"):
            envs.reset([0, 1], difficulty=flags)
    with pytest.raises(TypeError, match="^difficulty"):
        envs.difficulty = [True] * 4
    with pytest.raises(TypeError, match="^difficulty"):
        rse.EnvTerrains(SMALL, 2, difficulty=True)
    with pytest.raises(TypeError, match="^difficulty"):
        SMALL.generate(difficulty=False)
    assert envs.episode.tolist() == [0, 0, 0, 0], "nothing changed"
    # Numbers, one or one per id, numpy's too, are still difficulties.
    envs.reset([0, 1], difficulty=np.array([0.25, 1]))
    envs.reset([2], difficulty=np.float32(0.5))
    envs.reset([3], difficulty=0)
    assert envs.difficulty.tolist() == [0.25, 1.0, 0.5, 0.0]


class DLPackOnly:
    """An array that offers DLPack alone (as a torch CPU tensor would)."""

    def __init__(self, array: np.ndarray) -> None:
        self.array = array

    def __dlpack__(self, **kwargs):
        return self.array.__dlpack__(**kwargs)

    def __dlpack_device__(self):
        return self.array.__dlpack_device__()


def test_write_into_a_callers_array_by_numpy_dlpack_or_buffer() -> None:
    envs = rse.EnvTerrains(SMALL, 3)
    target = np.full(envs.samples.shape, -1.0, np.float32)
    envs.write(target, [1])
    assert np.array_equal(target[1], envs.samples[1]) and (target[[0, 2]] == -1).all()
    backing = np.zeros(envs.samples.shape, np.float32)
    envs.write(DLPackOnly(backing))
    assert np.array_equal(backing, envs.samples)
    raw = bytearray(envs.samples.nbytes)
    envs.write(memoryview(raw).cast("B").cast("f", envs.samples.shape))
    assert np.array_equal(np.frombuffer(raw, np.float32).reshape(envs.samples.shape), envs.samples)


def test_the_fields_copied_out_for_a_reset_are_the_pools_exact_and_coarse() -> None:
    """``_copy_fields`` (mjlab's reset: the host model, the upload's
    buffer) puts each named env's field at its start and nothing else;
    with ``coarse``, a cell's sample is the mean of its first and last
    (over a ramp, its plane at the centre); bad places are named, and a
    refused copy writes nothing."""
    ramps = rse.Scheme.load(SCHEMES / "mix_ramps.csv")
    envs = rse.EnvTerrains(ramps, 3, oversample=2, difficulty=1.0)
    n = envs.samples[0].size
    data = np.full(3 * n, -1.0, np.float32)
    envs._copy_fields([2, 0], data, [5, n + 5])
    assert np.array_equal(data[5 : n + 5], envs.samples[2].ravel())
    assert np.array_equal(data[n + 5 : 2 * n + 5], envs.samples[0].ravel())
    assert (data[:5] == -1).all() and (data[2 * n + 5 :] == -1).all()
    k = envs.oversample
    first, last = envs.samples[1, ::k, ::k], envs.samples[1, k - 1 :: k, k - 1 :: k]
    coarse = np.zeros(first.size, np.float32)
    envs._copy_fields(np.array([1]), coarse, np.array([0]), coarse=True)
    assert np.array_equal(coarse, ((first + last) * np.float32(0.5)).ravel())
    assert not np.array_equal(coarse, first.ravel()), "the ramps' cells read their planes"
    data[:] = 7.0
    for starts, said in (([0, n - 1], "starts: the field at"), ([2 * n + 1, 0], "data: "), ([-1, 0], "starts: -1 is not a place")):
        with pytest.raises(ValueError, match=said):
            envs._copy_fields([0, 1], data, starts)
    with pytest.raises(ValueError, match="env_ids: 3"):
        envs._copy_fields([3], data, [0])
    assert (data == 7.0).all()


def ray_down(model, data, x: float, y: float, geom: int) -> float:
    hit = np.zeros(1, dtype=np.int32)
    dist = mujoco.mj_ray(model, data, np.array([x, y, 20.0]), np.array([0.0, 0.0, -1.0]), None, 1, -1, hit)
    assert dist >= 0 and hit[0] == geom, (x, y, hit)
    return 20.0 - dist


def cell_centres(envs: rse.EnvTerrains, e: int) -> np.ndarray:
    """The centre of every cell of env e's terrain, in its slot's frame."""
    t = envs.terrain(e)
    ny, nx = t.heights.shape
    ys, xs = np.mgrid[0:ny, 0:nx]
    return np.stack([(xs.ravel() + 0.5) * t.block_size, (ys.ravel() + 0.5) * t.block_size], axis=1)


def test_slots_are_a_pool_of_mujoco_height_fields_each_env_its_own() -> None:
    """One height field per env, each geom in its own place: MuJoCo's
    surface over every cell centre is the env's top, and after resetting
    some envs and copying their slots only, theirs change, the others not."""
    n = 4
    envs = rse.EnvTerrains(SMALL, n, oversample=2, seed=5)
    spec = mujoco.MjSpec()
    gap = 3.0
    names = rse.mujoco.add_env_hfields(spec, envs)
    assert names == [f"rse_env{e}" for e in range(n)]
    for e, hfield in enumerate(names):
        rse.mujoco.add_env_geom(spec, envs, hfield, offset=(e * gap, 0.0, 0.0))
    model = spec.compile()
    data = mujoco.MjData(model)

    def sync(ids) -> None:
        rse.mujoco.sync_env_hfields(model, envs, ids)
        mujoco.mj_forward(model, data)

    def seen(e: int) -> np.ndarray:
        return np.array([ray_down(model, data, px + e * gap, py, e) for px, py in cell_centres(envs, e)])

    sync(range(n))
    for e in range(n):
        expected = envs.heights_at([e], cell_centres(envs, e)[None])[0]
        assert np.allclose(seen(e), expected, atol=1e-5), e
    before = [seen(e) for e in range(n)]
    envs.reset([1, 3])
    sync([1, 3])
    after = [seen(e) for e in range(n)]
    for e in (0, 2):
        assert np.array_equal(after[e], before[e]), e
    for e in (1, 3):
        assert not np.array_equal(after[e], before[e]), e
        assert np.allclose(after[e], envs.heights_at([e], cell_centres(envs, e)[None])[0], atol=1e-5)
    # Each env stands on its own terrain: no two alike.
    assert len({a.tobytes() for a in after}) == n


def test_tiles_are_one_mujoco_height_field_each_env_in_its_tile() -> None:
    n, cols, border = 5, 2, 2
    envs = rse.EnvTerrains(SMALL, n, oversample=2, seed=9, layout="tiles", cols=cols, border=border)
    _, rows, columns = envs.samples.shape
    spec = mujoco.MjSpec()
    (hfield,) = rse.mujoco.add_env_hfields(spec, envs, name="map")
    rse.mujoco.add_env_geom(spec, envs, hfield)
    model = spec.compile()
    data = mujoco.MjData(model)

    def sync() -> None:
        rse.mujoco.sync_env_hfields(model, envs, name="map")
        mujoco.mj_forward(model, data)

    sync()
    s = SMALL.block_size
    for e in range(n):
        row, col = divmod(e, cols)
        x0, y0 = (border + col * (12 + border)) * s, (border + row * (10 + border)) * s
        points = cell_centres(envs, e) + [x0, y0]
        expected = envs.heights_at([e], points[None])[0]
        seen = np.array([ray_down(model, data, x, y, 0) for x, y in points])
        assert np.allclose(seen, expected, atol=1e-5), e
        # The origin is over the env's tile, on its top.
        ox, oy, oz = envs.origins[e]
        assert x0 <= ox <= x0 + 12 * s and y0 <= oy <= y0 + 10 * s
        assert oz >= envs.heights_at([e], [[[ox, oy]]])[0, 0] - 1e-9
    # Borders are ground (height 0, the slab's top).
    assert ray_down(model, data, 0.05, 0.05, 0) == pytest.approx(SMALL.base, abs=1e-5)


def test_each_tile_sits_at_its_field_corner_and_holds_its_slots_samples() -> None:
    """``field_corners``: env e's tile of the map, ``field_shape`` from its
    corner, holds the samples env e's slot holds (the same terrain in
    either layout); a slot's corner is its own first sample."""
    n, cols, border = 5, 2, 2
    tiles = rse.EnvTerrains(SMALL, n, oversample=2, seed=9, layout="tiles", cols=cols, border=border)
    slots = rse.EnvTerrains(SMALL, n, oversample=2, seed=9)
    rows, columns = tiles.field_shape
    corners = tiles.field_corners
    assert corners.shape == (n, 2) and corners.dtype == np.int64
    assert list(corners[3]) == [2 * (border + 10 + border), 2 * (border + 12 + border)], "row, column of tile (1, 1)"
    for e, (r, c) in enumerate(corners):
        assert np.array_equal(tiles.samples[0, r : r + rows, c : c + columns], slots.samples[e]), e
    assert not slots.field_corners.any()


@pytest.mark.parametrize("layout", ["slots", "tiles"])
def test_the_pool_as_mjcf_loads_in_mujoco_and_takes_the_samples(layout: str) -> None:
    """env_hfields_mjcf: MuJoCo loads the text; after sync_env_hfields the
    first field's geom shows env 0's terrain under every cell centre."""
    envs = rse.EnvTerrains(SMALL, 3, oversample=2, seed=2, layout=layout, **({"cols": 2} if layout == "tiles" else {}))
    model = mujoco.MjModel.from_xml_string(rse.mujoco.env_hfields_mjcf(envs))
    assert model.nhfield == (3 if layout == "slots" else 1)
    rse.mujoco.sync_env_hfields(model, envs)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    points = cell_centres(envs, 0)  # env 0's slot, or its tile at the map's corner (no border)
    seen = np.array([ray_down(model, data, x, y, 0) for x, y in points])
    assert np.allclose(seen, envs.heights_at([0], points[None])[0], atol=1e-5)


def test_a_model_without_the_pool_is_named() -> None:
    envs = rse.EnvTerrains(SMALL, 2)
    empty = mujoco.MjModel.from_xml_string("<mujoco/>")
    with pytest.raises(ValueError, match="^model: no height field named 'rse_env0'"):
        rse.mujoco.sync_env_hfields(empty, envs)
    spec = mujoco.MjSpec()
    rse.mujoco.add_env_hfields(spec, envs)
    rse.mujoco.add_env_geom(spec, envs, "rse_env0")
    model = spec.compile()
    with pytest.raises(ValueError, match="^env_ids"):
        rse.mujoco.sync_env_hfields(model, envs, [-1])
    other = rse.EnvTerrains(SMALL, 2, oversample=3)
    with pytest.raises(ValueError, match="^model: height field rse_env0 holds"):
        rse.mujoco.sync_env_hfields(model, other)


def test_a_contact_sheet_shows_every_env_on_one_scale_with_its_label(tmp_path) -> None:
    """The PNG a person looks at to see a pool's terrains: read back with
    Pillow, one tile per env in the order asked, each the env's heights in
    the preview palette on the pool's common scale, labels above."""
    from PIL import Image

    scheme = rse.Scheme.from_csv("# size: 20x12\ntype,height\nrandom,4\n")
    envs = rse.EnvTerrains(scheme, 5, seed=3, difficulty=0.5)
    envs.reset([1, 3], difficulty=[1.0, 0.25])
    path = tmp_path / "sheet.png"
    png = envs.contact_sheet(path, env_ids=[3, 1, 0], cols=2, cell_pixels=7)
    assert path.read_bytes() == png
    image = np.asarray(Image.open(path).convert("RGB")).astype(int)
    gap, line, tile_w, tile_h = 6, 11, 20 * 7, 12 * 7
    cell_w = max(tile_w, 120)
    assert image.shape[1] == gap + 2 * (cell_w + gap)
    hi = max(int(envs.terrain(e).heights.max()) for e in (3, 1, 0))

    def colour(h: int) -> list[int]:
        # rse's preview palette (rse_core::preview::palette) from 0 to hi.
        t = h * 510 // hi
        return [0, t, 255 - t] if t <= 255 else [t - 255, 510 - t, 0]

    for i, e in enumerate([3, 1, 0]):
        x0 = gap + (i % 2) * (cell_w + gap)
        y0 = gap + (i // 2) * (tile_h + 2 * line + gap) + 2 * line
        heights = envs.terrain(e).heights
        for y in range(12):
            for x in range(20):
                # The cell's centre pixel; north (y = 11) at the top.
                px = image[y0 + (11 - y) * 7 + 3, x0 + x * 7 + 3]
                assert list(px) == colour(int(heights[y, x])), (e, x, y)
        label = image[y0 - 2 * line : y0, x0 : x0 + 100]
        assert (label == 235).all(axis=2).sum() > 50, "no label text above the tile"
    assert envs.contact_sheet() == envs.contact_sheet(env_ids=range(5))
    with pytest.raises(ValueError, match="env_ids: 9 is not an environment"):
        envs.contact_sheet(env_ids=[9])
    with pytest.raises(ValueError, match="cols and cell_pixels"):
        envs.contact_sheet(cols=0)
    with pytest.raises(ValueError, match=r"pixel contact sheet \(3 columns, 100000 pixels a cell\) is more than"):
        envs.contact_sheet(cell_pixels=100_000)


def test_rse_gen_contact_sheet_draws_the_picture_envterrains_draws(tmp_path) -> None:
    """From the shell, the same PNG byte for byte as
    ``EnvTerrains.contact_sheet`` of the same envs, seed and difficulty,
    for one scheme and for a mix (its tiles named by file)."""
    import subprocess

    from conftest import rse_gen_path

    out = tmp_path / "sheet.png"
    scheme = SCHEMES / "six_obstacles.csv"
    done = subprocess.run([str(rse_gen_path()), "contact-sheet", str(scheme), "--envs", "7", "--difficulty", "0.5",
                           "--seed", "4", "-o", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    envs = rse.EnvTerrains(rse.Scheme.load(scheme), 7, seed=4, difficulty=0.5)
    assert out.read_bytes() == envs.contact_sheet()

    mix = [SCHEMES / "mix_stairs.csv", SCHEMES / "mix_rough.csv"]
    done = subprocess.run([str(rse_gen_path()), "contact-sheet", *map(str, mix), "--proportions", "3,1", "--envs", "12",
                           "--seed", "9", "--cols", "4", "-o", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    pool = rse.EnvTerrains([rse.Scheme.load(p) for p in mix], 12, seed=9, proportions=[3, 1])
    assert set(pool.scheme_ids) == {0, 1}
    assert out.read_bytes() == pool.contact_sheet(cols=4, names=["mix_stairs", "mix_rough"])
    # Each scheme on its own colour scale unless one is asked for: the
    # rough ground (a few cm) is not one colour on the stairs' scale.
    done = subprocess.run([str(rse_gen_path()), "contact-sheet", *map(str, mix), "--proportions", "3,1", "--envs", "12",
                           "--seed", "9", "--cols", "4", "--one-scale", "-o", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    one = pool.contact_sheet(cols=4, names=["mix_stairs", "mix_rough"], one_scale=True)
    assert out.read_bytes() == one != pool.contact_sheet(cols=4, names=["mix_stairs", "mix_rough"])


def test_a_mix_sheet_draws_each_scheme_on_its_own_scale_with_a_legend_bar_each() -> None:
    """In a mix each scheme has its colour scale (rse-core's tests check
    the pixels) and a legend line of its own, 11 pixels; ``one_scale``
    draws them on one. One scheme has one scale either way."""
    from PIL import Image

    mix = [rse.Scheme.load(SCHEMES / f"mix_{n}.csv") for n in ("stairs", "rough")]
    pool = rse.EnvTerrains(mix, 8, seed=2, proportions=[1, 1], difficulty=1.0)
    assert len(set(pool.scheme_ids)) == 2

    def height(png: bytes) -> int:
        return Image.open(io.BytesIO(png)).height

    own, one = pool.contact_sheet(), pool.contact_sheet(one_scale=True)
    assert own != one
    assert height(own) == height(one) + 11
    single = rse.EnvTerrains(mix[1], 4, seed=2, difficulty=1.0)
    assert single.contact_sheet() == single.contact_sheet(one_scale=True)


def test_a_mix_draws_each_envs_scheme_by_proportion_from_its_global_id() -> None:
    """Several schemes in one pool, as mjlab mixes sub-terrains: env ``e``
    draws scheme ``rse.scheme_mix(...)[e]`` (its global id and the seed
    alone, so two processes draw what one draws), and its terrain is world
    ``episode·2³² + g`` of that scheme; one field scale for all."""
    stairs, rough = (rse.Scheme.load(SCHEMES / f"mix_{n}.csv") for n in ("stairs", "rough"))
    envs = rse.EnvTerrains([stairs, rough], 12, seed=5, difficulty=0.5, proportions=[3, 1])
    drawn = rse.scheme_mix([3, 1], 12, seed=5)
    np.testing.assert_array_equal(envs.scheme_ids, drawn)
    assert set(drawn) == {0, 1} and [s.to_csv() for s in envs.schemes] == [stairs.to_csv(), rough.to_csv()]
    for e in range(12):
        mine = (stairs, rough)[drawn[e]]
        np.testing.assert_array_equal(envs.terrain(e).heights, mine.generate(seed=5, index=e, difficulty=0.5).heights)
    # The same draw for the second half of a split over two processes.
    half = rse.EnvTerrains([stairs, rough], 6, seed=5, difficulty=0.5, proportions=[3, 1], env_offset=6)
    np.testing.assert_array_equal(half.scheme_ids, drawn[6:])
    np.testing.assert_array_equal(half.terrain(0).heights, envs.terrain(6).heights)
    # One scale: the highest top either scheme can have.
    assert envs.hfield_size[2] == pytest.approx(max(stairs.max_top, rough.max_top))
    envs.reset([0, 1])
    assert list(envs.scheme_ids) == list(drawn), "an env keeps its scheme across episodes"
    # A mix's tiles name their scheme.
    assert envs.contact_sheet(names=["stairs", "rough"]) != envs.contact_sheet()


GAP = 3.0
"""Metres between two envs' geoms in a model of the pool."""


def pool_in_mujoco(envs: rse.EnvTerrains, gap: float) -> tuple[mujoco.MjModel, mujoco.MjData]:
    """A MuJoCo model of ``envs``' pool, env ``e``'s geom ``e · gap`` along
    x, every field synced and forward run."""
    spec = mujoco.MjSpec()
    for e, hfield in enumerate(rse.mujoco.add_env_hfields(spec, envs)):
        rse.mujoco.add_env_geom(spec, envs, hfield, offset=(e * gap, 0.0, 0.0))
    model = spec.compile()
    data = mujoco.MjData(model)
    rse.mujoco.sync_env_hfields(model, envs, range(envs.num_envs))
    mujoco.mj_forward(model, data)
    return model, data


def tops_of(t: rse.Terrain) -> np.ndarray:
    """Each cell's top, metres: the slab (``base``) plus its steps."""
    return np.where(t.heights > 0, t.base + t.heights * t.step_height, t.base)


def test_a_mix_of_other_step_heights_and_bases_holds_each_envs_tops_in_metres() -> None:
    """Schemes of one grid mix whatever their step height and base: 1 cm
    steps of a gentle hill beside 5 cm pyramid stairs on a 20 cm slab.
    The field's scale is the highest top any can have, each env's samples
    its own terrain's tops in metres on it, and MuJoCo's rays land on
    them."""
    fine = rse.Scheme.from_csv("# size: 20x16\n# step_height: 0.01\ntype,height,angle,x1,y1\npeak,30,20,10,8\n")
    coarse = rse.Scheme.from_csv("# size: 20x16\n# step_height: 0.05\n# base: 0.2\ntype,height,angle,x1,y1,x2,y2,tread\npyramid,4,,2,2,17,13,2\n")
    envs = rse.EnvTerrains([fine, coarse], 8, seed=1, oversample=2)
    assert set(envs.scheme_ids) == {0, 1}
    _, _, elevation, base = envs.hfield_size
    assert elevation == pytest.approx(0.4) and base == pytest.approx(0.05)  # 0.2 + 4 steps of 5 cm; the deeper step
    for e in range(8):
        t = envs.terrain(e)
        assert np.allclose(envs.samples[e, ::2, ::2] * elevation, tops_of(t), atol=1e-6), e
        assert t.step_height == (0.01 if envs.scheme_ids[e] == 0 else 0.05)
    # In MuJoCo: each env's field, cast on from above at every cell centre.
    model, data = pool_in_mujoco(envs, GAP)
    for e in range(8):
        seen = np.array([ray_down(model, data, px + e * GAP, py, e) for px, py in cell_centres(envs, e)])
        assert np.allclose(seen, envs.heights_at([e], cell_centres(envs, e)[None])[0], atol=1e-5), e
        assert np.allclose(seen, tops_of(envs.terrain(e)).ravel(), atol=1e-5), e


def test_a_mix_of_grids_gives_every_slot_the_largest_a_smaller_terrain_in_its_corner() -> None:
    """A 12x8 stepfield beside a 20x16 hill: every slot is 20x16 cells, the
    smaller terrain in its first cells (its origin, ``heights_at`` and
    MuJoCo's rays agree), the ground plane at 0 around it."""
    big = rse.Scheme.from_csv("# size: 20x16\ntype,height,angle,x1,y1\npeak,6,30,10,8\n")
    small = rse.Scheme.from_csv("# size: 12x8\n# step_height: 0.05\ntype,height\nrandom,1..3\n")
    envs = rse.EnvTerrains([big, small], 6, seed=2, oversample=2)
    assert set(envs.scheme_ids) == {0, 1} and envs.field_shape == (32, 40) and envs.oversample == 2
    model, data = pool_in_mujoco(envs, GAP)
    s = 0.1
    ys, xs = np.mgrid[0:16, 0:20]
    centres = np.stack([(xs.ravel() + 0.5) * s, (ys.ravel() + 0.5) * s], axis=1)
    for e in range(6):
        seen = np.array([ray_down(model, data, px + e * GAP, py, e) for px, py in centres])
        tops = envs.heights_at([e], centres[None])[0]
        on = np.isfinite(tops)
        assert on.sum() == envs.terrain(e).heights.size, e
        assert np.allclose(seen[on], tops[on], atol=1e-5) and np.allclose(seen[~on], 0.0, atol=1e-5), e
        x, y, _ = envs.origins[e]
        assert 0 < x < envs.terrain(e).heights.shape[1] * s and 0 < y < envs.terrain(e).heights.shape[0] * s, "its origin on its terrain"


def test_a_mix_refuses_schemes_of_other_block_sizes_and_bad_proportions() -> None:
    a = rse.Scheme.from_csv("# size: 20x20\ntype,height\nrandom,2\n")
    with pytest.raises(ValueError, match="schemes: scheme 2 has block_size 0.2 m, scheme 1 0.1 m"):
        rse.EnvTerrains([a, rse.Scheme.from_csv("# size: 20x20\n# block_size: 0.2\ntype,height\nrandom,2\n")], 2)
    with pytest.raises(ValueError, match="proportions: 1 given for 2 schemes"):
        rse.EnvTerrains([a, a], 2, proportions=[1])
    with pytest.raises(ValueError, match="proportions: every proportion is 0"):
        rse.EnvTerrains([a, a], 2, proportions=[0, 0])
    with pytest.raises(ValueError, match="proportions: scheme 2's proportion is -1"):
        rse.scheme_mix([1, -1], 4, seed=0)
    # Shares whose sum overflows are still shares (hostile worlds VI).
    assert sorted(set(rse.scheme_mix([1e308, 1e308], 64, seed=0))) == [0, 1]
    with pytest.raises(TypeError, match="scheme: expected an rse.Scheme"):
        rse.EnvTerrains(["not a scheme"], 2)  # type: ignore[list-item]
