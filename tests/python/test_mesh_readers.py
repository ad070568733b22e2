"""Our meshes loaded in real third-party readers: trimesh, manifold3d,
pygltflib and PyBullet."""

from pathlib import Path

import manifold3d
import numpy as np
import pybullet as p
import pygltflib
import pytest
import trimesh
import rse
from conftest import SCHEMES, heights, ramps_top, run, units, wedges_volume

SAMPLES = sorted(SCHEMES.glob("*.csv"))


def expected_volume(scheme: Path, base: float | None = None) -> float:
    """The cells' solid and the ramps' wedges of world 0 (the wedges only
    when the scheme's own base is asked for)."""
    u = units(scheme)
    wedges = wedges_volume(rse.Scheme.load(scheme).generate(index=0)) if base is None else 0.0
    base = u["base"] if base is None else base
    return float(np.sum(base + heights(scheme) * u["step_height"]) * u["block_size"] ** 2) + wedges


def top(scheme: Path) -> float:
    cells = float(heights(scheme).max() * units(scheme)["step_height"])
    return max(cells, ramps_top(rse.Scheme.load(scheme).generate(index=0)))


def load_obj(path: Path) -> trimesh.Trimesh:
    """Our OBJ in trimesh, vertex for vertex: by default trimesh 5 splits each
    vertex per normal (the `merge_norm=True` of older versions is gone);
    `maintain_order=True` keeps the file's vertices."""
    return trimesh.load(path, process=False, maintain_order=True, force="mesh")


def write_mesh(scheme: Path, path: Path, *flags: str) -> Path:
    run("mesh", str(scheme), "-o", str(path), *flags)
    return path


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_obj_is_a_closed_volume_of_exact_size_in_trimesh(scheme: Path, out: Path) -> None:
    obj = write_mesh(scheme, out / "terrain.obj")
    assert (out / "terrain.mtl").exists()
    mesh = load_obj(obj)
    assert mesh.is_watertight
    assert mesh.is_winding_consistent
    assert mesh.is_volume
    assert mesh.volume == pytest.approx(expected_volume(scheme), rel=1e-6)
    assert mesh.bounds[1][2] == pytest.approx(top(scheme), abs=1e-6)
    assert len(mesh.vertex_normals) == len(mesh.vertices)


@pytest.mark.parametrize("scheme", SAMPLES, ids=lambda s: s.stem)
def test_stl_edges_pair_up_after_merging_vertices(scheme: Path, out: Path) -> None:
    stl = write_mesh(scheme, out / "terrain.stl")
    soup = trimesh.load(stl, process=False, force="mesh")
    obj = load_obj(write_mesh(scheme, out / "t.obj"))
    assert len(soup.faces) == len(obj.faces)
    # STL is a triangle soup: merge by position, then every edge must be used
    # equally often in each direction.
    soup.merge_vertices()
    edges = soup.edges_sorted
    directed = {}
    for a, b in soup.edges:
        directed[(a, b)] = directed.get((a, b), 0) + 1
    for (a, b), n in directed.items():
        assert directed.get((b, a), 0) == n, f"edge {a}-{b}"
    assert len(edges) == 3 * len(soup.faces)
    assert soup.volume == pytest.approx(expected_volume(scheme), rel=1e-6)


@pytest.mark.parametrize("scheme", ["wall", "random", "paper_pallets", "curriculum"])
def test_manifold3d_accepts_the_mesh(scheme: str, out: Path) -> None:
    path = SCHEMES / f"{scheme}.csv"
    mesh = load_obj(write_mesh(path, out / "t.obj"))
    solid = manifold3d.Manifold(
        manifold3d.Mesh(
            vert_properties=np.asarray(mesh.vertices, dtype=np.float32),
            tri_verts=np.asarray(mesh.faces, dtype=np.uint32),
        )
    )
    assert solid.status() == manifold3d.Error.NoError
    assert solid.volume() == pytest.approx(expected_volume(path), rel=1e-5)


def test_a_slab_under_the_grid_is_part_of_the_solid(out: Path) -> None:
    scheme = SCHEMES / "random.csv"
    mesh = load_obj(write_mesh(scheme, out / "t.obj", "--base", "0.05"))
    assert mesh.is_volume
    assert mesh.volume == pytest.approx(expected_volume(scheme, base=0.05), rel=1e-6)
    assert mesh.bounds[0] == pytest.approx([0, 0, 0])
    assert mesh.bounds[1][:2] == pytest.approx([2.0, 2.0])


@pytest.mark.parametrize("scheme", ["wall", "six_obstacles"])
def test_glb_loads_with_the_right_counts(scheme: str, out: Path) -> None:
    path = SCHEMES / f"{scheme}.csv"
    glb = write_mesh(path, out / "t.glb")
    obj = load_obj(write_mesh(path, out / "t.obj"))
    gltf = pygltflib.GLTF2().load(str(glb))
    primitive = gltf.meshes[0].primitives[0]
    assert gltf.accessors[primitive.attributes.POSITION].count == len(obj.vertices)
    assert gltf.accessors[primitive.attributes.COLOR_0].count == len(obj.vertices)
    assert gltf.accessors[primitive.indices].count == 3 * len(obj.faces)
    scene = trimesh.load(glb, process=False)
    loaded = scene.to_geometry() if isinstance(scene, trimesh.Scene) else scene
    assert len(loaded.faces) == len(obj.faces)
    # glTF is Y up: our heights are its Y.
    assert loaded.bounds[1][1] == pytest.approx(top(path), abs=1e-6)


def test_pybullet_bodies_rest_at_their_cells_height(out: Path) -> None:
    scheme = SCHEMES / "six_obstacles.csv"
    h = heights(scheme)
    step, block = units(scheme)["step_height"], units(scheme)["block_size"]
    obj = write_mesh(scheme, out / "t.obj")
    client = p.connect(p.DIRECT)
    try:
        p.setGravity(0, 0, -9.81, physicsClientId=client)
        p.setTimeStep(1 / 240, physicsClientId=client)
        terrain = p.createCollisionShape(
            p.GEOM_MESH, fileName=str(obj), flags=p.GEOM_FORCE_CONCAVE_TRIMESH, physicsClientId=client
        )
        p.createMultiBody(0, terrain, physicsClientId=client)
        # Cells in the middle of flat 3x3 patches, so a body cannot slide off.
        cells = [
            (x, y)
            for y in range(1, h.shape[0] - 1)
            for x in range(1, h.shape[1] - 1)
            if (h[y - 1 : y + 2, x - 1 : x + 2] == h[y, x]).all()
        ][:6]
        assert len(cells) >= 3, "the sample has flat patches to drop on"
        radius = 0.02
        bodies = []
        for x, y in cells:
            sphere = p.createCollisionShape(p.GEOM_SPHERE, radius=radius, physicsClientId=client)
            rest = h[y, x] * step
            body = p.createMultiBody(
                0.1, sphere, basePosition=[(x + 0.5) * block, (y + 0.5) * block, rest + 0.1], physicsClientId=client
            )
            bodies.append((body, rest))
        for _ in range(1000):
            p.stepSimulation(physicsClientId=client)
        for body, rest in bodies:
            z = p.getBasePositionAndOrientation(body, physicsClientId=client)[0][2]
            assert z - radius == pytest.approx(rest, abs=0.002)
    finally:
        p.disconnect(client)
