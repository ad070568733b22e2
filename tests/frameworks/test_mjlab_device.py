"""What rse's mjlab task holds on the device and does there in a step,
checked on the CPU device (the proxies docs/train.md names for a GPU):
every term rse adds to a step runs on the device alone (no host copy,
caught by name: ``host_copies.HostCopies``), the terrains take at most
128 KiB an env on the device at the task's stepfield, counted from the
arrays and estimated before the scene is built within 20 %, and the ray
sensors read each env's own field with no mesh per env."""

from __future__ import annotations

import functools

import mjlab.tasks  # noqa: F401  (registers the tasks)
import numpy as np
import pytest
import rse
import torch
from host_copies import HostCopies, as_a_gpu_runs_them
from launches import Launches
from mjlab.envs import ManagerBasedRlEnv
from mjlab.managers.observation_manager import ObservationTermCfg
from mjlab.tasks.registry import load_env_cfg
from rse._adapters.mjlab.ray_sensors import DirectRays, FieldRays, seen_geoms
from rse._adapters.mjlab.reset_event import event_of
from rse._adapters.mjlab.scene_pool import pool_memory, staging_bytes
from rse._adapters.mjlab.step_terms import bound_near_robots
from rse._adapters.mjlab.terrains import probe_envs
from rse._adapters.uploads import Uploads
from rse.mjlab import env_terrains, exact_height_scan, out_of_slot, use_env_terrains
from rse.mjlab_tasks import STEPFIELD

TASK = "Mjlab-Velocity-Rough-Unitree-Go1"
NUM_ENVS = 4


def make_env() -> ManagerBasedRlEnv:
    """The Go1 rough task on rse's stepfield, laid out apart (the offsets'
    path of every term) and with the exact scan as the critic's height
    scan, so that each step term rse has is in the config; reset and
    stepped once."""
    cfg = load_env_cfg(TASK)
    cfg.scene.num_envs = NUM_ENVS
    use_env_terrains(cfg, rse.Scheme.from_csv(STEPFIELD), seed=3, apart=True)
    cfg.observations["critic"].terms["height_scan"] = ObservationTermCfg(func=exact_height_scan, params={"sensor_name": "terrain_scan"})
    env = ManagerBasedRlEnv(cfg, device="cpu")
    env.reset()
    env.step(torch.zeros(env.action_space.shape))
    return env


@pytest.fixture(scope="module")
def env():
    """``make_env``'s env, shared by the tests that only read it."""
    env = make_env()
    yield env
    env.close()


def step_terms(env: ManagerBasedRlEnv) -> list[tuple[str, object]]:
    """Every observation, reward and termination term of ``env``'s config
    whose function is rse's: what rse adds to each step (the curriculum
    term and the reset event run at resets, which copy a new terrain up by
    design; the step events run every step)."""
    found = []
    for group, cfg in env.cfg.observations.items():
        found += [(f"observations[{group}].{name}", term) for name, term in cfg.terms.items()]
    found += [(f"rewards.{name}", term) for name, term in env.cfg.rewards.items()]
    found += [(f"terminations.{name}", term) for name, term in env.cfg.terminations.items()]
    found += [(f"events.{name}", term) for name, term in env.cfg.events.items() if term.mode == "step"]
    return [(name, term) for name, term in found if getattr(term.func, "__module__", "").startswith("rse.")]


def test_the_step_terms_rse_adds_copy_nothing_between_host_and_device(env) -> None:
    """Each term as a GPU runs it: the exact tops by a kernel on the
    device (``DeviceTops.device_tops``; the CPU device reads them with
    ``heights_at`` over the points' own memory, and both give the same)."""
    terms = step_terms(env)
    assert {term.func.__name__ for _, term in terms} == {"exact_height_scan", "out_of_slot", "bound_near_robots"}, terms

    def run(term) -> torch.Tensor:
        # An event term returns nothing: what it wrote is its result.
        args = (None,) if getattr(term, "mode", None) == "step" else ()
        got = term.func(env, *args, **term.params)
        return env.sim.model.geom_aabb.clone() if got is None else got

    on_host = [run(term) for _, term in terms]
    with as_a_gpu_runs_them(event_of(env, "rse_terrain").exact_tops()):
        for (name, term), expected in zip(terms, on_host):
            with HostCopies() as copies:
                got = run(term)
            assert not copies.found, f"{name} ({term.func.__name__}) copies to or from the host: {copies.found}"
            assert torch.allclose(got.float(), expected.float(), atol=1e-5), name


def test_the_step_terms_rse_adds_launch_a_kernel_or_a_few_each(env) -> None:
    """Each term as a GPU runs it launches few kernels from Python (each a
    gap on a GPU, outside mjlab's captured graphs): the bounds around the
    robots one Warp kernel and no tensor op (it was 44 tensor ops), the
    exact scan its kernel and the few tensor ops around it, no more than
    twice mjlab's own ray height scan (it was 150), ``out_of_slot`` as
    many as mjlab's ``out_of_terrain_bounds``."""
    from mjlab.envs import mdp

    def launched(f) -> list[str]:
        f()
        with Launches() as launches:
            f()
        return launches.found

    with as_a_gpu_runs_them(event_of(env, "rse_terrain").exact_tops()):
        near = launched(lambda: bound_near_robots(env))
        scan = launched(lambda: exact_height_scan(env, "terrain_scan"))
        out = launched(lambda: out_of_slot(env))
    rays = launched(lambda: mdp.height_scan(env, "terrain_scan"))
    assert near == ["warp: near_boxes"], near
    assert "warp: tops_under" in scan and len(scan) <= 2 * len(rays), (scan, rays)
    assert len(out) <= 8, out


def test_the_launch_recorder_sees_tensor_ops_and_warp_kernels() -> None:
    """``Launches`` counts a tensor op that computes, not a view nor an
    allocation, and a Warp kernel: the test above can fail."""
    import warp as wp
    from rse._adapters.warp_fields import scatter_rows_kernel

    x = torch.ones(4)
    with Launches() as launches:
        x.view(2, 2)
        torch.empty(3)
        x + 1
        wp.launch(scatter_rows_kernel(), dim=(1, 1), inputs=[wp.zeros((1, 1)), wp.zeros(1, dtype=wp.int32)], outputs=[wp.zeros(1)], device="cpu")
    assert launches.found == ["torch: aten.add.Tensor", "warp: scatter_rows"], launches.found


def test_the_recorder_catches_the_host_round_trip_the_scan_made_before() -> None:
    """The scan as it was (rays' origins to numpy, ``heights_at`` on the
    host, back as a tensor) is caught: the test above can fail."""
    envs = rse.EnvTerrains(rse.Scheme.from_csv(STEPFIELD), 2)
    origins = torch.zeros((2, 3, 3))
    with HostCopies() as copies:
        xy = origins[..., :2].to("cpu", torch.float64).numpy()
        torch.as_tensor(np.nan_to_num(envs.heights_at(np.arange(2), xy)), device=origins.device)
    said = " | ".join(copies.found)
    for kind in ("Tensor.to", "Tensor.numpy", "torch.as_tensor"):
        assert kind in said, said
    with HostCopies() as copies:
        float(torch.ones(1).sum())
    assert any("_local_scalar_dense" in f for f in copies.found), copies.found


def test_a_reset_reads_its_ids_once_and_sends_nothing_the_host_waits_for() -> None:
    """On a GPU each copy from pageable memory, and each read into
    Python, waits for the device: a step's reset (the curriculum term,
    then the reset event, with mjlab's env ids on the device, the same
    tensor to both) reads the ids once (the host draws the terrains), the
    curriculum its moves, and makes no tensor from host data but the
    origins, which go up through pinned memory without the host waiting
    (``to_device``). Another tensor, or another step's, is read anew."""
    from rse._adapters.mjlab.curriculum import terrain_difficulty

    env = make_env()  # its terrains change: not the shared one
    try:
        event = event_of(env, "rse_terrain")
        terrain_difficulty(env, torch.tensor([0, 2], device=env.device))  # its per-env halves, made once
        ids = torch.tensor([0, 2], device=env.device)
        with HostCopies() as curriculum:
            terrain_difficulty(env, ids)
        with HostCopies() as reset:
            event(env, ids)
        # The ids kept for the same tensor in the same step, read anew for
        # another tensor or in another step.
        with HostCopies() as again:
            assert event.ids(ids) == [0, 2]
        assert event.ids(torch.tensor([1], device=env.device)) == [1]
        with torch.inference_mode():  # as in training
            ids = torch.tensor([0, 2], device=env.device)
            assert event.ids(ids) == [0, 2]
            env.common_step_counter += 1
            ids[1] = 3
            assert event.ids(ids) == [0, 3], "the same tensor, a step later"
    finally:
        env.close()
    made = [f for f in curriculum.found + reset.found if "host data" in f and "from_numpy" not in f and "lift_fresh" not in f]
    assert not made, made
    assert sum("Tensor.cpu" in f for f in curriculum.found) == 2, curriculum.found
    assert sum("Tensor.cpu" in f for f in reset.found) == 0, reset.found
    assert sum("from_numpy" in f for f in reset.found) == 1, reset.found
    assert not again.found, again.found


def test_the_terrains_take_at_most_128_kib_an_env_on_the_device_as_estimated(env) -> None:
    """The terrains' arrays on the device take at most 128 KiB an env, as
    estimated before the scene is built (within 20 %); the buffers a
    reset's rows go up through on a GPU (made here the GPU's way, on the
    CPU device) are what the estimate adds for them, a few MiB whatever
    the envs: 4096 envs of the task's stepfield take at most 0.5 GiB."""
    event = event_of(env, "rse_terrain")
    parts = event.device_bytes()
    assert parts["camera meshes"] == 0 and parts["upload staging"] == 0, parts  # the CPU device: rows go straight in
    per_env = sum(parts.values()) / NUM_ENVS
    assert per_env <= 128 * 1024, parts
    probe = probe_envs(rse.Scheme.from_csv(STEPFIELD), None)
    geoms = env.sim.mj_model.ngeom
    staging = staging_bytes(probe, NUM_ENVS)
    _, estimate = pool_memory(probe, NUM_ENVS, "cuda", geoms=geoms)
    assert abs((estimate - staging) / NUM_ENVS - per_env) <= 0.2 * per_env, (estimate / NUM_ENVS, parts)
    kept = event._uploads
    event._uploads = Uploads(kernel=True)
    try:
        event._copy_out(list(range(NUM_ENVS)))  # every env, as when the scene is built
        assert event.device_bytes()["upload staging"] == staging
    finally:
        event._uploads = kept
    _, at_4096 = pool_memory(probe, 4096, "cuda", geoms=geoms)
    assert staging_bytes(probe, 4096) <= 5 * 2**20
    assert at_4096 <= 0.5 * 2**30, at_4096 / 2**30


def test_the_ray_sensors_read_each_envs_own_field_with_no_mesh_per_env(env) -> None:
    """Both ray sensors of the task (``terrain_scan``, the feet's
    ``foot_height_scan``) cast one thread a ray on rse's terrain's geoms
    and the ground (``FieldRays``), and the rays of each env land on its
    own tops."""
    ctx = env.scene.sensor_context
    assert ctx is not None and not ctx.has_cameras
    assert all(isinstance(s.raycast_kernel, FieldRays) for s in ctx.raycast_sensors), ctx.raycast_sensors
    # The terrain's geoms in group 0 alone: mjlab's ground plane, rse's
    # field and (laid out apart) its view; none of the robot's.
    names = [[env.sim.mj_model.geom(g).name for g in s.raycast_kernel.candidates] for s in ctx.raycast_sensors]
    assert all(n == ["terrain", "rse_terrain", "rse_terrain_view"] for n in names), names
    assert event_of(env, "rse_terrain").direct_rays == 2
    envs = env_terrains(env)
    sensor = env.scene["terrain_scan"]
    hits = sensor.data.hit_pos_w.numpy().astype(np.float64)
    slot = event_of(env, "rse_terrain").apart.slot_xy(torch.as_tensor(hits[..., :2])).numpy()
    t = envs.terrain(0)
    spacing = t.block_size * t.heights.shape[1] / envs.field_shape[1]  # one sample
    near = [(dx, dy) for dx in (-spacing, 0.0, spacing) for dy in (-spacing, 0.0, spacing)]
    for e in range(NUM_ENVS):
        tops = envs.heights_at([e], slot[e][None])[0]
        inside = np.isfinite(tops)
        assert inside.sum() > 100, e
        # On a top, or within a sample of a step edge on MuJoCo's slope
        # between the tops on either side; never another env's terrain.
        around = np.stack([envs.heights_at([e], (slot[e] + d)[None])[0] for d in near])[:, inside]
        z = hits[e, inside, 2]
        assert np.all((z >= around.min(axis=0) - 1e-4) & (z <= around.max(axis=0) + 1e-4)), e
        assert (np.abs(z - tops[inside]) < 1e-4).mean() > 0.3, e
        others = [np.abs(z - envs.heights_at([o], slot[e][None])[0][inside]).mean() for o in range(NUM_ENVS) if o != e]
        # Two terrains may agree under a scan (both at ground level there):
        # some other env must differ.
        assert np.abs(z - tops[inside]).mean() < max(others), e


def cast(env: ManagerBasedRlEnv, kernel) -> list[np.ndarray]:
    """The distances, geom ids and normals ``kernel`` casts for the
    ``terrain_scan`` sensor's current rays."""
    sensor = env.scene["terrain_scan"]
    for out in (sensor._ray_dist, sensor._ray_geomid, sensor._ray_normal):
        out.fill_(7)
    kernel(rc=None)
    return [sensor._ray_dist.numpy().copy(), sensor._ray_geomid.numpy().copy(), sensor._ray_normal.numpy().copy()]


def test_field_rays_hit_what_mujoco_warps_direct_kernel_hits_bit_for_bit(env) -> None:
    """``FieldRays`` (one thread a ray over the geoms a sensor sees) and
    MuJoCo Warp's own direct kernel give the same distances, geom ids and
    normals, to the bit: on the terrain the task's sensor sees, and with
    every geom of the scene visible (the robot's geoms of all types, ties
    and misses among them), through random poses."""
    import mujoco_warp
    import warp as wp

    sensor = env.scene["terrain_scan"]
    direct = DirectRays(functools.partial(type(sensor).raycast_kernel, sensor))
    groups = sensor._geomgroup
    everything = type(groups)(*([-1.0] * 6))
    gen = torch.Generator().manual_seed(5)
    hits: set[int] = set()
    try:
        for step in range(6):
            env.step(2 * torch.rand(env.action_space.shape, generator=gen) - 1)
            mujoco_warp.kinematics(env.sim.wp_model, env.sim.wp_data)
            for geomgroup in (groups, everything):
                sensor._geomgroup = geomgroup
                seen = seen_geoms(env.sim.mj_model, geomgroup)
                ours, theirs = cast(env, FieldRays(sensor, seen)), cast(env, direct)
                for a, b in zip(ours, theirs):
                    assert np.array_equal(a.view(np.uint8), b.view(np.uint8)), (step, len(seen))
                assert (theirs[1] >= 0).any(), step
                hits.update(np.unique(theirs[1]).tolist())
    finally:
        sensor._geomgroup = groups
        wp.synchronize()
    # The robot's own geoms were hit too, not the terrain alone.
    robot = {g for g in hits if g >= 0 and not env.sim.mj_model.geom(g).name.startswith(("terrain", "rse_"))}
    assert robot, hits


def test_each_worlds_terrain_is_bounded_by_its_own_tops_so_only_the_feet_pair_with_flat_ground() -> None:
    """MuJoCo Warp's broadphase pairs a geom with the terrain where their
    boxes overlap: each world's terrain geoms reach up to that env's
    highest top (``geom_aabb`` per world, renewed at its resets), so on
    flat ground (difficulty 0) the standing Go1's feet alone pair with it,
    where the box of the scheme's highest top paired all 26 colliders."""
    import mujoco

    cfg = load_env_cfg(TASK)
    cfg.scene.num_envs = NUM_ENVS
    use_env_terrains(cfg, rse.Scheme.from_csv(STEPFIELD), seed=3, difficulty=0.0)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        env.reset()
        envs = env_terrains(env)
        mjm, m = env.sim.mj_model, env.sim.wp_model
        gids = [mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, g) for g in ("rse_terrain", "rse_terrain_coarse")]
        _, _, elevation, base = envs.hfield_size

        def bounded() -> np.ndarray:
            aabb = m.geom_aabb.numpy()
            top = envs.samples.reshape(NUM_ENVS, -1).max(axis=1) * elevation
            for g in gids:
                assert np.allclose(aabb[:, g, 0, 2], (top - base) / 2, atol=1e-6), aabb[:, g]
                assert np.allclose(aabb[:, g, 1, 2], (top + base) / 2, atol=1e-6), aabb[:, g]
            return top

        assert bounded().max() == 0.0
        pairs = []
        for _ in range(10):
            env.step(torch.zeros(env.action_space.shape))
            pairs.append(env.sim.wp_data.ncollision.numpy()[0] / NUM_ENVS)
        assert max(pairs[5:]) <= 4, pairs  # the four feet
        # A reset renews the bounds of the envs it renews, and theirs only.
        envs.difficulty = [1.0] + [0.0] * (NUM_ENVS - 1)
        env.reset(env_ids=torch.tensor([0]))
        top = bounded()
        assert top[0] > 0.1 and not top[1:].any(), top
    finally:
        env.close()


def trajectory(near: bool, reach: float | None = None, steps: int = 40) -> tuple[torch.Tensor, float]:
    """Every step's ``qpos`` of 8 Go1s under random actions on rse's
    hardest stepfield, episodes of 0.5 s (two rounds of resets), and the
    broadphase pairs per world: with the step event that bounds each
    world's terrain around its robot (``near``, its reach replaced by
    ``reach`` when given) or without it."""
    torch.manual_seed(0)
    cfg = load_env_cfg(TASK)
    cfg.scene.num_envs = 8
    cfg.seed = 5
    cfg.episode_length_s = 0.5
    use_env_terrains(cfg, rse.Scheme.from_csv(STEPFIELD), seed=3, difficulty=1.0)
    if not near:
        del cfg.events["rse_terrain_near"]
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        env.reset()
        square = event_of(env, "rse_terrain").near_robot
        assert square is not None
        if reach is not None:
            square.reach = reach
        actions = torch.Generator().manual_seed(1)
        qpos, pairs = [], 0
        for _ in range(steps):
            env.step(torch.randn(env.action_space.shape, generator=actions))
            qpos.append(env.sim.data.qpos.clone())
            pairs += int(env.sim.wp_data.ncollision.numpy()[0])
        return torch.stack(qpos), pairs / steps / 8
    finally:
        env.close()


def test_the_terrain_bounded_around_each_robot_halves_the_pairs_and_changes_no_contact() -> None:
    """The step event ``bound_near_robots`` narrows each world's terrain
    box to the square its robot can reach before the next step: the
    broadphase tests half the pairs, and the simulation is the same to the
    bit (a dropped pair could not touch), through falls on 20 cm steps and
    resets that put every robot somewhere new. A square that misses the
    legs (a reach of 0.2 m) changes it: the comparison can fail."""
    near, near_pairs = trajectory(True)
    whole, whole_pairs = trajectory(False)
    assert torch.equal(near, whole), (near - whole).abs().amax(dim=(1, 2))
    assert near_pairs <= 0.6 * whole_pairs, (near_pairs, whole_pairs)
    short, _ = trajectory(True, reach=0.2)
    assert not torch.equal(short, whole)


def test_the_reach_holds_every_collider_in_any_pose_of_the_legs() -> None:
    """``near.reach`` bounds how far from the root any point of a geom that
    may touch the terrain gets, over random poses within the joints'
    ranges (MuJoCo's own kinematics), and is no more than 1.5x the
    farthest seen."""
    import mujoco
    from rse._adapters.mjlab.near_bounds import free_root, reach, terrain_colliders

    cfg = load_env_cfg(TASK)
    cfg.scene.num_envs = 1
    use_env_terrains(cfg, rse.Scheme.from_csv(STEPFIELD), seed=3)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        mjm = env.sim.mj_model
        terrain = [mujoco.mj_name2id(mjm, mujoco.mjtObj.mjOBJ_GEOM, g) for g in ("rse_terrain", "rse_terrain_coarse")]
        geoms = terrain_colliders(mjm, terrain)
        root = free_root(mjm, geoms)
        assert root is not None and len(geoms) > 4
        bound = reach(mjm, root, geoms)
        data = mujoco.MjData(mjm)
        rng = np.random.default_rng(0)
        farthest = 0.0
        for _ in range(200):
            for j in range(mjm.njnt):
                if mjm.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE:
                    data.qpos[mjm.jnt_qposadr[j]] = rng.uniform(*mjm.jnt_range[j]) if mjm.jnt_limited[j] else rng.uniform(-np.pi, np.pi)
            mujoco.mj_kinematics(mjm, data)
            out = np.linalg.norm(data.geom_xpos[geoms] - data.xpos[root], axis=1) + mjm.geom_rbound[geoms] + mjm.geom_margin[geoms]
            farthest = max(farthest, float(out.max()))
        assert farthest <= bound <= 1.5 * farthest, (farthest, bound)
    finally:
        env.close()


def test_the_devices_tops_read_a_ramps_plane_as_the_host_does() -> None:
    """Over a ramp a cell's samples lie on its plane: the device's tops
    (each cell's own samples, extended to the point) read the plane where
    the host's ``heights_at`` does, not the staircase under it."""
    from pathlib import Path

    cfg = load_env_cfg(TASK)
    cfg.scene.num_envs = 2
    ramps = rse.Scheme.load(Path(__file__).resolve().parents[2] / "schemes" / "mix_ramps.csv")
    use_env_terrains(cfg, ramps, seed=1)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        tops = event_of(env, "rse_terrain").exact_tops()
        rng = np.random.default_rng(0)
        points = []
        for e in range(2):
            terrain = tops.envs.terrain(e)
            s = terrain.block_size
            here = []
            for ramp in terrain.ramps * 20:
                x0, y0, x1, y1 = ramp["cells"]
                here.append(rng.uniform([x0 * s, y0 * s], [(x1 + 1) * s, (y1 + 1) * s]))
            points.append(here[:100])
        xy = np.array(points)
        host = tops.envs.heights_at(np.arange(2), xy)
        staircase = np.array([[tops.envs.terrain(e).elevation[int(y // s), int(x // s)] for x, y in xy[e]] for e in range(2)])
        assert (host - staircase).max() > 0.02, "the plane stands above the staircase somewhere"
        device = tops.device_tops(torch.from_numpy(xy)).numpy()
        np.testing.assert_allclose(device, host, atol=1e-5)
    finally:
        env.close()


def test_the_box_around_each_robot_reaches_every_sample_near_it_also_at_a_ramps_top_edge() -> None:
    """The step event's box around a robot reaches the highest sample of
    every cell its square touches (one more each side), wherever the robot
    stands: also where a ramp's top cell rises within it above the next
    cell, whose first samples alone stand lower (a box that low would let
    a foot on the ramp's top edge sink into it before it pairs)."""
    from pathlib import Path

    cfg = load_env_cfg(TASK)
    cfg.scene.num_envs = 2
    ramps = rse.Scheme.load(Path(__file__).resolve().parents[2] / "schemes" / "mix_ramps.csv")
    use_env_terrains(cfg, ramps, seed=1, difficulty=1.0)
    env = ManagerBasedRlEnv(cfg, device="cpu")
    try:
        env.reset()
        near = event_of(env, "rse_terrain").near_robot
        assert near is not None
        envs = env_terrains(env)
        k, block, root = near.tops.grid.k, near.tops.block, near.square.root
        ny, nx = envs.terrain(0).elevation.shape
        samples = envs.samples.reshape(2, ny * k, nx * k)
        _, _, elevation, _ = envs.hfield_size
        gid = int(near.gids.numpy()[0])
        d = env.sim.wp_data
        d.qvel.zero_()
        half = near.reach + near.square.slack  # standing still
        offsets = near.offsets.numpy()
        rng = np.random.default_rng(0)
        short = 0
        for x, y in rng.uniform(0.0, [nx * block, ny * block], size=(1500, 2)):
            xpos = d.xpos.numpy()
            xpos[:, root, :2] = offsets + [x, y]
            d.xpos.assign(xpos)
            near.update(env.sim)
            # The cells the square touches, one more each side, on the terrain.
            cx0, cy0 = (int(np.clip(np.floor((v - half) / block) - 1, 0, n - 1)) for v, n in ((x, nx), (y, ny)))
            cx1, cy1 = (int(np.clip(np.floor((v + half) / block) + 1, 0, n - 1)) for v, n in ((x, nx), (y, ny)))
            aabb = env.sim.wp_model.geom_aabb.numpy()[:, gid]
            for e in range(2):
                under = samples[e, cy0 * k : (cy1 + 1) * k, cx0 * k : (cx1 + 1) * k]
                top = max(float(under.max()), 0.0) * elevation
                assert aabb[e, 0, 2] + aabb[e, 1, 2] == pytest.approx(top, abs=1e-5), (e, x, y)
                # Where the first samples of the cells, even one more each
                # side, stand below a sample the square itself covers (a
                # ramp's top cell, the drop after it): a box that low misses
                # a contact.
                inner = samples[e, (cy0 + 1) * k : cy1 * k, (cx0 + 1) * k : cx1 * k]
                short += under[::k, ::k].max() < inner.max()
        assert short > 0, "no square ended on a ramp's top cell: the test would not catch first samples alone"
    finally:
        env.close()
