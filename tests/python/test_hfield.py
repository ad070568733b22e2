"""Height fields: rse's terrains as MuJoCo height fields, checked
in MuJoCo itself — ray casts against the heightmap, a live model rewritten
in place, bodies resting on the new ground, the file `rse-gen hfield`
writes, and the documented exactness bound."""

import json
from pathlib import Path

import mujoco
import numpy as np
import pytest
import rse
import rse.mujoco
from conftest import SCHEMES, heights, run

SAMPLES = sorted(SCHEMES.glob("*.csv"))
SIX = SCHEMES / "six_obstacles.csv"


def ray_down(model, data, x: float, y: float) -> float:
    geomid = np.zeros(1, dtype=np.int32)
    dist = mujoco.mj_ray(model, data, np.array([x, y, 20.0]), np.array([0.0, 0.0, -1.0]), None, 1, -1, geomid)
    assert dist >= 0, (x, y)
    return 20.0 - dist


def model_of(hfield_xml_attrs: str, pos: tuple) -> tuple:
    xml = f"""<mujoco><asset><hfield name="t" {hfield_xml_attrs}/></asset>
      <worldbody><geom type="hfield" hfield="t" pos="{pos[0]!r} {pos[1]!r} {pos[2]!r}"/></worldbody></mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


def away_from_steps(h: np.ndarray, x: float, y: float, s: float, r: float) -> bool:
    """Whether the square of half-side `r` around (x, y) lies inside the grid
    on cells of one height: no step edge within `r` along x or y."""
    ny, nx = h.shape
    x0, x1, y0, y1 = (x - r) / s, (x + r) / s, (y - r) / s, (y + r) / s
    if x0 < 0 or y0 < 0 or x1 >= nx or y1 >= ny:
        return False
    block = h[int(y0) : int(y1) + 1, int(x0) : int(x1) + 1]
    return bool((block == block[0, 0]).all())


def away_from_ramp_edges(ramps: list[dict], x: float, y: float, s: float, r: float) -> bool:
    """Whether no edge of a ramp's rectangle lies within `r` of (x, y)
    along x or y: where a plane meets the cells around it, the field
    interpolates between the two."""
    for ramp in ramps:
        x0, y0, x1, y1 = ramp["cells"]
        lo, hi = (x0 * s, y0 * s), ((x1 + 1) * s, (y1 + 1) * s)
        near_x = lo[1] - r <= y <= hi[1] + r and min(abs(x - lo[0]), abs(x - hi[0])) <= r
        near_y = lo[0] - r <= x <= hi[0] + r and min(abs(y - lo[1]), abs(y - hi[1])) <= r
        if near_x or near_y:
            return False
    return True


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_the_file_mujoco_loads_obeys_the_bound_of_the_docs(scheme: Path, tmp_path: Path) -> None:
    """`rse-gen hfield` → MuJoCo: exact at every cell centre, and at random
    points farther than half a sample spacing (along x and y) from every
    step edge and the border."""
    k = 4
    info = json.loads(run("hfield", str(scheme), "-o", str(tmp_path / "t.bin"), "--oversample", str(k), "--index", "1"))
    model, data = model_of(f'file="{tmp_path / "t.bin"}" size="{" ".join(map(repr, info["size"]))}"', info["pos"])
    assert (model.hfield_nrow[0], model.hfield_ncol[0]) == (info["nrow"], info["ncol"])
    h = heights(scheme, index=1)
    terrain = rse.Scheme.load(scheme).generate(index=1)
    s = terrain.block_size
    # The surface: a cell's top, or a ramp's plane over it (a plane's
    # samples interpolate to the plane itself).
    for y in range(h.shape[0]):
        for x in range(h.shape[1]):
            centre = ((x + 0.5) * s, (y + 0.5) * s)
            assert ray_down(model, data, *centre) == pytest.approx(terrain.height_at(*centre), abs=1e-5)
    rng = np.random.default_rng(0)
    checked = 0
    margin = s / k / 2 + 1e-6
    for x, y in rng.uniform(0, 1, (3000, 2)) * [h.shape[1] * s, h.shape[0] * s]:
        if away_from_steps(h, x, y, s, margin) and away_from_ramp_edges(terrain.ramps, x, y, s, margin):
            assert ray_down(model, data, x, y) == pytest.approx(terrain.height_at(x, y), abs=1e-5)
            checked += 1
    assert checked > 300


def test_set_hfield_rewrites_a_live_model_in_place() -> None:
    """One compiled model: rays at every cell centre see terrain A, then B
    after set_hfield, and a sphere dropped on B rests on B's top."""
    scheme = rse.Scheme.load(SIX)
    a, b = scheme.generate(index=3), scheme.generate(index=4)
    s, h = a.block_size, b.heights
    flat = [(x, y) for y in range(1, 49) for x in range(1, 49) if (h[y - 1 : y + 2, x - 1 : x + 2] == h[y, x]).all()]
    bx, by = max(flat, key=lambda c: h[c[1], c[0]])
    spec = mujoco.MjSpec.from_string(rse.mujoco.hfield_mjcf(scheme, 4))
    ball = spec.worldbody.add_body(name="ball", pos=[(bx + 0.5) * s, (by + 0.5) * s, b.elevation[by, bx] + 0.1])
    ball.add_freejoint()
    ball.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.02, 0, 0], mass=0.1, group=3)
    model = spec.compile()
    data = mujoco.MjData(model)
    terrain_only = np.array([1, 0, 0, 0, 0, 0], dtype=np.uint8)
    geomid = np.zeros(1, dtype=np.int32)
    for terrain in [a, b]:
        rse.mujoco.set_hfield(model, "terrain", terrain, 4)
        mujoco.mj_forward(model, data)
        for y in range(50):
            for x in range(50):
                origin = np.array([(x + 0.5) * s, (y + 0.5) * s, 20.0])
                d = mujoco.mj_ray(model, data, origin, np.array([0, 0, -1.0]), terrain_only, 1, -1, geomid)
                assert 20.0 - d == pytest.approx(terrain.elevation[y, x], abs=1e-3), (x, y)
    for _ in range(1500):
        mujoco.mj_step(model, data)
    assert data.body("ball").xpos[2] == pytest.approx(b.elevation[by, bx] + 0.02, abs=0.002)


def test_hfield_arrays_and_reused_buffers() -> None:
    terrain = rse.Scheme.load(SIX).generate(index=2)
    samples, size, pos = terrain.hfield(2)
    assert samples.dtype == np.float32 and samples.shape == terrain.hfield_shape(2) == (100, 100)
    assert samples.min() == 0.0 and samples.max() == 1.0
    # Every sample is its cell's top (k x k blocks).
    tops = np.kron(terrain.elevation, np.ones((2, 2)))
    np.testing.assert_allclose(samples * size[2] + pos[2], tops, atol=1e-6)
    reused = np.empty((100, 100), dtype=np.float32)
    again, size_again, pos_again = terrain.hfield(2, out=reused)
    assert again is reused and (size_again, pos_again) == (size, pos)
    np.testing.assert_array_equal(reused, samples)
    buffer = np.empty((100, 100), dtype=np.float32)
    for index in range(3):
        t = rse.Scheme.load(SIX).generate(index=index)
        t.hfield_into(buffer, 2, 0.0, 1.0)
        np.testing.assert_allclose(buffer, np.kron(t.elevation, np.ones((2, 2))), atol=1e-6)


def test_bad_height_field_input_is_a_clear_error() -> None:
    scheme = rse.Scheme.load(SIX)
    terrain = scheme.generate()
    with pytest.raises(ValueError, match="oversample 0"):
        terrain.hfield(0)
    with pytest.raises(ValueError, match="at most"):
        terrain.hfield(100_000)
    model = mujoco.MjModel.from_xml_string(rse.mujoco.hfield_mjcf(scheme, 2))
    with pytest.raises(KeyError, match="no height field named 'ground'"):
        rse.mujoco.set_hfield(model, "ground", terrain, 2)
    with pytest.raises(ValueError, match=r"shape \(100, 100\).*\(200, 200\)"):
        rse.mujoco.set_hfield(model, "terrain", terrain, 4)
    low = mujoco.MjModel.from_xml_string(rse.mujoco.hfield_mjcf(scheme, 2, elevation=0.1))
    before = low.hfield_data.copy()
    with pytest.raises(ValueError, match="tops run from"):
        rse.mujoco.set_hfield(low, "terrain", terrain, 2)
    np.testing.assert_array_equal(low.hfield_data, before)
    with pytest.raises(ValueError, match="shape"):
        terrain.hfield_into(np.empty((3, 3), dtype=np.float32), 2)
    # A Fortran-ordered buffer of the right shape would be filled transposed.
    nrow, ncol = terrain.hfield_shape(2)
    with pytest.raises(ValueError, match="C-contiguous"):
        terrain.hfield_into(np.empty((ncol, nrow), dtype=np.float32).T, 2)


def test_rse_gen_hfield_refuses_a_bad_oversample(tmp_path: Path) -> None:
    import subprocess

    from conftest import rse_gen_path

    done = subprocess.run(
        [str(rse_gen_path()), "hfield", str(SIX), "-o", str(tmp_path / "t.bin"), "--oversample", "0"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 2 and "--oversample" in done.stderr
    assert not (tmp_path / "t.bin").exists()


@pytest.mark.parametrize("mode", ["single", "blocks"])
def test_a_batch_with_the_hfield_collider_loads_in_mujoco_and_checks_good(tmp_path: Path, mode: str) -> None:
    out = tmp_path / "hf"
    run("batch", str(SIX), "-o", str(out), "--amount", "2", "--target", "obj,mujoco", "--mesh", mode,
        "--mujoco-collider", "hfield", "--oversample", "2")  # fmt: skip
    run("check", str(out))
    # The same bytes from Python.
    rse.write_worlds(rse.Scheme.load(SIX), tmp_path / "py", amount=2, targets="obj,mujoco", mesh=mode,
                     mujoco_collider="hfield", oversample=2)  # fmt: skip
    for world in sorted(out.glob("world_*")):
        for f in ["rse.json", "mujoco/rse.xml", "mujoco/terrain.bin"]:
            assert (world / f).read_bytes() == (tmp_path / "py" / world.name / f).read_bytes(), f
        manifest = json.loads((world / "rse.json").read_text())
        assert manifest["mujoco_collider"] == {"type": "hfield", "oversample": 2}
        model = mujoco.MjModel.from_xml_path(str(world / "mujoco" / "rse.xml"))
        assert model.nhfield == 1 and (model.hfield_nrow[0], model.hfield_ncol[0]) == (100, 100)
        boxes = sum(model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX for g in range(model.ngeom))
        assert boxes == 0
        data = mujoco.MjData(model)
        mujoco.mj_forward(model, data)
        h = heights(SIX, index=manifest["index"])
        for y in range(0, 50, 2):
            for x in range(50):
                # The floor plane is at 0, under the field.
                assert ray_down(model, data, (x + 0.5) * 0.1, (y + 0.5) * 0.1) == pytest.approx(h[y, x] * 0.1, abs=1e-5)


def test_an_oversample_without_the_hfield_collider_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="hfield collider only"):
        rse.write_worlds(rse.Scheme.load(SIX), tmp_path, amount=1, targets="mujoco", oversample=4)
    with pytest.raises(ValueError, match="unknown MuJoCo collider"):
        rse.write_worlds(rse.Scheme.load(SIX), tmp_path, amount=1, targets="mujoco", mujoco_collider="mesh")
    assert not any(tmp_path.iterdir())
