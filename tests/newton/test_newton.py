"""`rse.newton` inside Newton 1.8 on the CPU: every world its own rse
height field (Newton's native per-world shapes); spheres dropped in each
world rest on that world's own tops, with Newton's collision pipeline
(XPBD) and with its MuJoCo solver; after a partial reset (`envs.reset`,
`rse.newton.sync`) the reset worlds' spheres rest on their new tops and the
others' on their old ones."""

from __future__ import annotations

import numpy as np
import pytest
import rse
import rse.newton
import warp as wp

wp.config.quiet = True
import newton  # noqa: E402

# Wide flat tops (stepped hills), so a sphere rests on one top.
SCHEME = rse.Scheme.from_csv(
    "# size: 20x20\n# step_height: 0.05\ntype,height,angle,x1,y1\npeak,2..5,15,5..15,5..15\npeak,1..4,15,5..15,5..15\n"
)
WORLDS = 4
R = 0.05
# Drop points in each world's slot frame (the terrain's corner at 0).
DROPS = [(0.55, 0.55), (1.05, 1.45), (1.45, 0.75), (0.75, 1.25)]


def build(solver_kind: str):
    envs = rse.EnvTerrains(SCHEME, WORLDS, seed=7)
    builder = newton.ModelBuilder()
    for w in range(WORLDS):
        builder.begin_world()
        rse.newton.add_heightfield(builder, envs, w)
        for x, y in DROPS:
            b = builder.add_body(xform=wp.transform(p=wp.vec3(x, y, 0.6), q=wp.quat_identity()))
            builder.add_shape_sphere(body=b, radius=R)
        builder.end_world()
    model = builder.finalize(device="cpu")
    if solver_kind == "xpbd":
        solver = newton.solvers.SolverXPBD(model, iterations=10)
        pipe = newton.CollisionPipeline(model, soft_contact_max=0)
        return envs, model, solver, pipe, pipe.contacts(), 10
    solver = newton.solvers.SolverMuJoCo(model)
    return envs, model, solver, None, None, 2


def settle(model, solver, pipe, contacts, sub: int, frames: int = 120) -> np.ndarray:
    """Steps 1.2 s; each body's position, (worlds, bodies, 3)."""
    s0, s1 = model.state(), model.state()
    control = model.control()
    dt = 0.01 / sub
    for _ in range(frames):
        if pipe is not None:
            pipe.collide(s0, contacts)
        for _ in range(sub):
            s0.clear_forces()
            solver.step(s0, s1, control, contacts, dt)
            s0, s1 = s1, s0
    wp.synchronize()
    return s0.body_q.numpy().reshape(WORLDS, len(DROPS), 7)[:, :, :3].astype(np.float64)


def on_tops(envs: rse.EnvTerrains, q: np.ndarray, worlds: list[int]) -> None:
    """Each sphere's bottom is on its world's tops under it: between the
    lowest and the highest top within its radius and a sample (on one top,
    or on the field's slope at a step edge), and each world's spheres rest
    at heights its own tops explain."""
    t = envs.terrain(0)
    reach = R + t.block_size * t.heights.shape[0] / envs.field_shape[0]
    probes = [(dx, dy) for dx in np.linspace(-reach, reach, 9) for dy in np.linspace(-reach, reach, 9)]
    for w in worlds:
        around = np.stack([envs.heights_at([w], (q[w, :, :2] + d)[None])[0] for d in probes])
        bottom = q[w, :, 2] - R
        assert np.all(bottom > around.min(axis=0) - 0.012), (w, bottom, around.min(axis=0))
        assert np.all(bottom < around.max(axis=0) + 0.012), (w, bottom, around.max(axis=0))


@pytest.mark.parametrize("solver_kind", ["xpbd", "mujoco"])
def test_each_world_rests_on_its_own_terrain_and_a_partial_reset_renews_only_it(solver_kind: str) -> None:
    envs, model, solver, pipe, contacts, sub = build(solver_kind)
    if solver_kind == "mujoco":
        rse.newton.sync(model, envs, solver=solver)
    q = settle(model, solver, pipe, contacts, sub)
    on_tops(envs, q, list(range(WORLDS)))
    # The worlds' terrains differ: a sphere in the wrong world's field would
    # not rest on these tops.
    assert len({envs.terrain(w).heights.tobytes() for w in range(WORLDS)}) == WORLDS

    old = [envs.terrain(w).heights.copy() for w in range(WORLDS)]
    envs.reset([1, 3])
    rse.newton.sync(model, envs, [1, 3], solver=solver if solver_kind == "mujoco" else None)
    assert np.array_equal(envs.terrain(0).heights, old[0]) and not np.array_equal(envs.terrain(1).heights, old[1])
    q = settle(model, solver, pipe, contacts, sub)
    on_tops(envs, q, list(range(WORLDS)))


def test_bad_uses_are_named() -> None:
    tiles = rse.EnvTerrains(SCHEME, 2, layout="tiles", cols=2)
    with pytest.raises(ValueError, match="^envs: .*slots"):
        rse.newton.add_heightfield(newton.ModelBuilder(), tiles, 0)
    envs = rse.EnvTerrains(SCHEME, 2)
    with pytest.raises(ValueError, match="^env: 2 is not"):
        rse.newton.add_heightfield(newton.ModelBuilder(), envs, 2)
    builder = newton.ModelBuilder()
    builder.begin_world()
    rse.newton.add_heightfield(builder, envs, 0)
    builder.end_world()
    builder.begin_world()
    builder.end_world()
    model = builder.finalize(device="cpu")
    with pytest.raises(ValueError, match=r"^model: height fields in worlds \[0\]"):
        rse.newton.sync(model, envs)
