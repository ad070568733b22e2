"""World options as Python takes them: the same typed options
and the same defaults as `rse-gen` (both are rse-world's `FromStr` and
`Default`), the stub's `Literal`s equal to what the library takes."""

import ast
import subprocess
from pathlib import Path

import pytest
import rse
from conftest import REPO, SCHEMES, rse_gen_path

SCHEME = REPO / "schemes" / "nist_hill.csv"


def tree(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_no_options_write_what_rse_gen_writes_without_flags(tmp_path: Path) -> None:
    scheme = rse.Scheme.load(SCHEME)
    rse.write_worlds(scheme, tmp_path / "py", amount=1)
    subprocess.run(
        [str(rse_gen_path()), "batch", str(SCHEME), "-o", str(tmp_path / "cli"), "--amount", "1"],
        check=True,
        capture_output=True,
    )
    assert tree(tmp_path / "py") == tree(tmp_path / "cli")
    assert '"targets": [\n    "gazebo"\n  ]' in (tmp_path / "py" / "world_0000" / "rse.json").read_text()


def test_targets_as_a_list_or_a_string_are_one_option(tmp_path: Path) -> None:
    scheme = rse.Scheme.load(SCHEME)
    rse.write_worlds(scheme, tmp_path / "a", amount=1, targets=["mujoco", "obj"])
    rse.write_worlds(scheme, tmp_path / "b", amount=1, targets="obj,mujoco")
    assert tree(tmp_path / "a") == tree(tmp_path / "b")


@pytest.mark.parametrize(
    ("keyword", "value", "error", "says"),
    [
        ("targets", "gazebo,isaac", ValueError, 'unknown target "isaac"'),
        ("targets", 3, TypeError, "targets: expected a comma-separated string or a list of target names, got int"),
        ("mesh", "triangles", ValueError, 'unknown mesh mode "triangles"'),
        ("mesh", 1, TypeError, "mesh: expected a string, got int"),
        ("mujoco_collider", "planes", ValueError, 'unknown MuJoCo collider "planes"'),
    ],
)
def test_bad_options_name_the_keyword(tmp_path: Path, keyword: str, value: object, error: type, says: str) -> None:
    scheme = rse.Scheme.load(SCHEME)
    with pytest.raises(error) as caught:
        rse.write_worlds(scheme, tmp_path, amount=1, **{keyword: value})
    assert says in str(caught.value)
    assert not any(tmp_path.iterdir()), "nothing written"


def test_an_oversample_needs_the_hfield_collider(tmp_path: Path) -> None:
    scheme = rse.Scheme.load(SCHEME)
    with pytest.raises(ValueError, match="oversample applies to the hfield collider only"):
        rse.write_worlds(scheme, tmp_path, amount=1, oversample=2)
    rse.write_worlds(scheme, tmp_path, amount=1, targets="mujoco", mujoco_collider="hfield")
    text = (tmp_path / "world_0000" / "rse.json").read_text()
    assert f'"oversample": {rse.DEFAULT_OVERSAMPLE}' in text


def test_the_stubs_literals_are_the_librarys_values() -> None:
    stub = ast.parse((Path(rse.__file__).parent / "_rse.pyi").read_text())
    literals = {}
    for node in stub.body:
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Subscript):
            name = node.targets[0].id  # type: ignore[attr-defined]
            if getattr(node.value.value, "id", None) == "Literal":
                literals[name] = tuple(e.value for e in node.value.slice.elts)  # type: ignore[attr-defined]
    assert literals == {
        "_Target": rse.TARGETS,
        "_MeshMode": rse.MESH_MODES,
        "_MujocoCollider": rse.MUJOCO_COLLIDERS,
    }
    assert rse.TARGETS == ("obj", "gazebo", "gazebo-classic", "webots", "mujoco", "urdf", "usd")


def test_the_library_defaults_reach_python_from_one_place() -> None:
    """Python's ``rse.DEFAULT_*`` are rse-core's constants, and a keyword
    left ``None`` gets exactly that value (ARCHITECTURE.md, "Settings")."""
    import subprocess

    import numpy as np

    scheme = rse.Scheme.load(SCHEMES / "six_obstacles.csv")
    terrain = scheme.generate(index=3)
    assert np.array_equal(terrain.spawn_origin(), terrain.spawn_origin(rse.DEFAULT_SPAWN_RADIUS))
    assert not np.array_equal(terrain.spawn_origin(), terrain.spawn_origin(rse.DEFAULT_SPAWN_RADIUS + 2.0))
    assert np.array_equal(
        terrain.flat_patches(4), terrain.flat_patches(4, rse.DEFAULT_PATCH_RADIUS), equal_nan=True
    )
    envs = rse.EnvTerrains(scheme, 2)
    nx, ny = scheme.grid
    k = rse.DEFAULT_ENV_OVERSAMPLE
    assert envs.field_shape == (ny * k, nx * k)
    assert envs.layout == "slots" and list(envs.difficulty) == [1.0, 1.0]
    assert envs.terrain(1).seed == scheme.seed, "the scheme's seed rules"
    assert terrain.hfield_shape(rse.DEFAULT_OVERSAMPLE) == terrain.hfield()[0].shape
    # The command line's help shows the same constants as its defaults.
    shown = subprocess.run([str(rse_gen_path()), "atlas", "--help"], capture_output=True, text=True).stdout
    assert f"[default: {rse.DEFAULT_SPAWN_RADIUS}]" in " ".join(shown.split())
