"""Height fields in MuJoCo, printed, not asserted:

1. generate + write a new 50x50 terrain into a live model at k = 4
   (200x200 samples), median over many calls (target < 100 us);
2. resets per second of rse.gym's Ant with a new terrain every reset, beside
   the same env keeping one terrain (target >= 0.9x);
3. Gymnasium's Ant stepping with fixed seeded controls on a 50x50 stepfield
   as a height field (k = 1, 2, 4), as merged boxes, and on Gymnasium's
   plane, with each collider's surface error against the true tops.

Run: .venv/bin/python bench/hfield.py (make bench runs it).
"""

from __future__ import annotations

import statistics
import time
from pathlib import Path

import gymnasium as gym
import mujoco
import numpy as np
import rse
import rse.gym
import rse.mujoco

SIX = Path(__file__).resolve().parents[1] / "schemes" / "six_obstacles.csv"


def median_us(fn, repeats: int) -> tuple[float, float, float]:
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t) * 1e6)
    return statistics.median(times), min(times), max(times)


def live_write() -> None:
    scheme = rse.Scheme.load(SIX)
    model = mujoco.MjModel.from_xml_string(rse.mujoco.hfield_mjcf(scheme, 4))
    slot = rse.mujoco.HFieldSlot(model, "terrain", 4)
    counter = iter(range(10**9))

    def once() -> None:
        slot.write(scheme.generate(index=next(counter)))

    def checked_each_time() -> None:
        rse.mujoco.set_hfield(model, "terrain", scheme.generate(index=next(counter)), 4)

    for _ in range(50):
        once()
    med, lo, hi = median_us(once, 3000)
    gen, _, _ = median_us(lambda: scheme.generate(index=next(counter)), 3000)
    each, _, _ = median_us(checked_each_time, 3000)
    print(f"new 50x50 terrain into a live model, k = 4 (200x200 samples), HFieldSlot.write(generate()):"
          f" median {med:.1f} us [{lo:.1f}-{hi:.1f}] (of which generate {gen:.1f} us; target < 100 us);"
          f" with set_hfield's checks every call: {each:.1f} us")


def resets() -> None:
    rates = {}
    for label, new in [("new terrain every reset", True), ("one terrain kept", False)]:
        env = gym.make(rse.gym.ENV_ID, scheme=str(SIX), new_terrain_each_reset=new)
        env.reset(seed=0)
        runs = []
        for _ in range(5):
            t = time.perf_counter()
            for _ in range(500):
                env.reset()
            runs.append(500 / (time.perf_counter() - t))
        env.close()
        rates[label] = statistics.median(runs)
        print(f"rse.gym Ant resets/s, {label}: median {rates[label]:,.0f} [{min(runs):,.0f}-{max(runs):,.0f}]")
    ratio = rates["new terrain every reset"] / rates["one terrain kept"]
    print(f"  ratio new / kept: {ratio:.3f} (target >= 0.9)")


def ant_spec() -> mujoco.MjSpec:
    from gymnasium.envs.mujoco import ant_v5

    return mujoco.MjSpec.from_file(str(Path(ant_v5.__file__).parent / "assets" / "ant.xml"))


def model_for(collider: str, terrain: rse.Terrain) -> mujoco.MjModel:
    """Gymnasium's Ant with the terrain centred on its start as `collider`."""
    if collider.startswith("hfield"):
        k = int(collider.rsplit("=", 1)[1])
        scheme = rse.Scheme.load(SIX)
        spec = mujoco.MjSpec.from_string(rse.gym.ant_on_hfield_xml(scheme, k, rse.mujoco.max_top(scheme)))
        model = spec.compile()
        rse.mujoco.set_hfield(model, "terrain", terrain, k)
        return model
    spec = ant_spec()
    if collider == "boxes":
        w = terrain.heights.shape[1] * terrain.block_size / 2
        for cx, cy, cz, hx, hy, hz in terrain.boxes():
            spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, pos=[cx - w, cy - w, cz], size=[hx, hy, hz],
                                    group=2, conaffinity=1, condim=3)  # fmt: skip
    return spec.compile()


def surface_error(model: mujoco.MjModel, terrain: rse.Terrain) -> tuple[float, float]:
    """Mean |surface - top| and the share of the area off by > 1 cm, over a
    200x200 grid of points on the terrain (rays at the terrain's geoms)."""
    s, n = terrain.block_size, terrain.heights.shape[1]
    if model.nhfield == 0 and all(model.geom_group[g] != 2 for g in range(model.ngeom)):
        # The plane: its surface is z = 0 everywhere.
        errors = np.repeat(np.repeat(terrain.elevation, 4, axis=0), 4, axis=1)
        return float(errors.mean()), float((errors > 0.01).mean())
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    w = n * s / 2
    group = np.array([0, 0, 1, 0, 0, 0], dtype=np.uint8)  # the terrain's geoms
    geomid = np.zeros(1, dtype=np.int32)
    errors = []
    for y in (np.arange(200) + 0.5) * (n * s / 200):
        for x in (np.arange(200) + 0.5) * (n * s / 200):
            d = mujoco.mj_ray(model, data, np.array([x - w, y - w, 5.0]), np.array([0, 0, -1.0]), group, 1, 1, geomid)
            z = 5.0 - d if d >= 0 else 0.0
            errors.append(abs(z - terrain.elevation[int(y / s), int(x / s)]))
    errors = np.array(errors)
    return float(errors.mean()), float((errors > 0.01).mean())


def stepping() -> None:
    terrain = rse.Scheme.load(SIX).generate(index=1)
    controls = np.random.default_rng(0).uniform(-1, 1, (2000, 8))
    print("Gymnasium Ant, 2000 steps of fixed seeded controls, 50x50 six_obstacles (world 1), median of 5:")
    plane_rate = None
    for collider in ["plane", "boxes", "hfield k=1", "hfield k=2", "hfield k=4"]:
        model = model_for(collider.replace(" ", "="), terrain) if collider != "plane" else model_for("plane", terrain)
        top = float(terrain.spawn_origin(0.6)[2]) if collider != "plane" else 0.0
        rates, contacts = [], []
        for _ in range(5):
            data = mujoco.MjData(model)
            data.qpos[2] = top + 0.75
            mujoco.mj_forward(model, data)
            t = time.perf_counter()
            ncon = 0
            for u in controls:
                data.ctrl[:] = u
                mujoco.mj_step(model, data)
                ncon += data.ncon
            rates.append(len(controls) / (time.perf_counter() - t))
            contacts.append(ncon / len(controls))
        rate = statistics.median(rates)
        plane_rate = plane_rate or rate
        mean_err, off = surface_error(model, terrain)
        print(f"  {collider:<11} {rate:>9,.0f} steps/s [{min(rates):,.0f}-{max(rates):,.0f}]  {rate / plane_rate:4.2f}x plane"
              f"  {statistics.median(contacts):5.1f} contacts/step  surface error mean {mean_err * 100:5.2f} cm,"
              f" {off * 100:5.1f} % of the area off by > 1 cm")


if __name__ == "__main__":
    live_write()
    resets()
    stepping()
