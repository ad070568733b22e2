"""Type stubs of the native module ``rse._rse`` (checked by mypy.stubtest)."""

import inspect
import os
from collections.abc import Sequence
from typing import Any, ClassVar, Literal, Optional, Union, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "__version__",
    "TARGETS",
    "MESH_MODES",
    "MUJOCO_COLLIDERS",
    "DEFAULT_OVERSAMPLE",
    "DEFAULT_ENV_OVERSAMPLE",
    "DEFAULT_SPAWN_RADIUS",
    "DEFAULT_PATCH_RADIUS",
    "DIFFICULTY_RULE",
    "SchemeError",
    "ShardBusyError",
    "Obstacle",
    "Scheme",
    "Terrain",
    "Atlas",
    "EnvTerrains",
    "generate_batch",
    "scheme_mix",
    "write_world",
    "write_worlds",
    "_time_generate",
    "_check_json",
    "_global_keywords",
    "_world_keywords",
    "_env_keywords",
    "_check_curriculum",
]

__version__: str

# World options: the values rse-world takes (a test keeps these equal to
# TARGETS, MESH_MODES and MUJOCO_COLLIDERS). None, where a keyword takes
# one, is the library's default: gazebo, auto, boxes, DEFAULT_OVERSAMPLE.
_Target = Literal["obj", "gazebo", "gazebo-classic", "webots", "mujoco", "urdf", "usd"]
_Targets = Union[str, Sequence[_Target]]
_MeshMode = Literal["auto", "single", "blocks"]
_MujocoCollider = Literal["boxes", "hfield"]
TARGETS: tuple[str, ...]
MESH_MODES: tuple[str, ...]
MUJOCO_COLLIDERS: tuple[str, ...]
DEFAULT_OVERSAMPLE: int
# The library's other defaults (rse-core's constants; a keyword left None
# gets the same value).
DEFAULT_ENV_OVERSAMPLE: int
DEFAULT_SPAWN_RADIUS: float
DEFAULT_PATCH_RADIUS: float
# The difficulty rule of every terrain made today (rse.json's difficulty_rule).
DIFFICULTY_RULE: str

# A value, or an inclusive (lo, hi) range drawn per world; numpy scalars
# and length-2 arrays are taken too.
_Int = Union[int, np.integer]
_Float = Union[float, int, np.floating, np.integer]
_IntParam = Union[_Int, tuple[_Int, _Int], list[_Int], npt.NDArray[np.integer]]
_FloatParam = Union[_Float, tuple[_Float, _Float], list[_Float], npt.NDArray[np.number]]
_Pair = Union[tuple[_Int, _Int], list[_Int], npt.NDArray[np.integer]]
_Coords = Union[float, npt.ArrayLike]

class SchemeError(ValueError):
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    field: Optional[str]

class ShardBusyError(ValueError):
    """Another live run holds this shard of this output folder (its lock): retry once it has ended, and the rerun skips every world it wrote."""

@final
class Obstacle:
    def __new__(
        cls,
        type: str,
        *,
        height: Optional[_IntParam] = None,
        angle: Optional[_FloatParam] = None,
        x1: Optional[_IntParam] = None,
        y1: Optional[_IntParam] = None,
        x2: Optional[_IntParam] = None,
        y2: Optional[_IntParam] = None,
        sigma: Optional[_FloatParam] = None,
        tread: Optional[_IntParam] = None,
    ) -> Obstacle: ...
    @property
    def type(self) -> str: ...
    @property
    def height(self) -> Optional[_IntParam]: ...
    @property
    def angle(self) -> Optional[_FloatParam]: ...
    @property
    def x1(self) -> Optional[_IntParam]: ...
    @property
    def y1(self) -> Optional[_IntParam]: ...
    @property
    def x2(self) -> Optional[_IntParam]: ...
    @property
    def y2(self) -> Optional[_IntParam]: ...
    @property
    def sigma(self) -> Optional[_FloatParam]: ...
    @property
    def tread(self) -> Optional[_IntParam]: ...
    __signature__: ClassVar[inspect.Signature]
    def __getnewargs_ex__(self) -> tuple[tuple[str], dict[str, object]]: ...

@final
class Scheme:
    # Generated from rse-core's table of global keys by scripts/python_stubs.py.
    def __new__(
        cls,
        obstacles: list[Obstacle] = [],
        *,
        size: _Pair = (10, 10),
        pallets: Optional[_Pair] = None,
        pallet_size: Optional[_Int] = None,
        pallet_boundary: Optional[bool] = None,
        block_size: _Float = 0.1,
        step_height: _Float = 0.1,
        base: _Float = 0.0,
        color: Union[tuple[_Float, _Float, _Float], str] = (0.72, 0.58, 0.42),
        ground_color: Union[tuple[_Float, _Float, _Float], str] = (0.8, 0.8, 0.8),
        amount: _Int = 1,
        seed: _Int = 0,
    ) -> Scheme: ...
    __signature__: ClassVar[inspect.Signature]
    def replace(self, **fields: object) -> Scheme: ...
    def fields(self) -> dict[str, object]: ...
    def __reduce__(self) -> tuple[object, tuple[str, Optional[str]]]: ...
    @staticmethod
    def load(path: Union[str, os.PathLike[str]]) -> Scheme: ...
    @staticmethod
    def from_csv(text: str, file: Optional[str] = None) -> Scheme: ...
    def to_csv(self) -> str: ...
    @property
    def obstacles(self) -> list[Obstacle]: ...
    @property
    def max_top(self) -> float: ...
    @property
    def grid(self) -> tuple[int, int]: ...
    @property
    def block_size(self) -> float: ...
    @property
    def step_height(self) -> float: ...
    @property
    def base(self) -> float: ...
    @property
    def amount(self) -> int: ...
    @property
    def seed(self) -> int: ...
    def generate(self, seed: Optional[int] = None, index: int = 0, difficulty: Optional[float] = None) -> Terrain: ...

@final
class Terrain:
    def __new__(cls, state: str, cells: bytes, scheme: Optional[str] = None) -> Terrain: ...
    def __reduce__(self) -> tuple[object, tuple[str, bytes, Optional[str]]]: ...
    def height_at(self, x: _Coords, y: _Coords, *, outside: float = 0.0) -> Union[float, npt.NDArray[np.float64]]: ...
    def preview(self, cell_pixels: Optional[int] = None) -> bytes: ...
    def heightmap_csv(self) -> str: ...
    @property
    def heights(self) -> npt.NDArray[np.uint16]: ...
    @property
    def elevation(self) -> npt.NDArray[np.float64]: ...
    @property
    def block_size(self) -> float: ...
    @property
    def step_height(self) -> float: ...
    @property
    def base(self) -> float: ...
    @property
    def seed(self) -> int: ...
    @property
    def index(self) -> int: ...
    @property
    def difficulty(self) -> float: ...
    @property
    def drawn(self) -> list[dict[str, object]]: ...
    @property
    def ramps(self) -> list[dict[str, object]]: ...
    def wedges(self) -> list[npt.NDArray[np.float64]]: ...
    def spawn_origin(self, radius: Optional[float] = None) -> npt.NDArray[np.float64]: ...
    def hfield(
        self, oversample: Optional[int] = None, *, out: Optional[npt.NDArray[np.float32]] = None
    ) -> tuple[npt.NDArray[np.float32], tuple[float, float, float, float], tuple[float, float, float]]: ...
    def hfield_layout(
        self, oversample: Optional[int] = None
    ) -> tuple[tuple[int, int], tuple[float, float, float, float], tuple[float, float, float]]: ...
    def hfield_shape(self, oversample: Optional[int] = None) -> tuple[int, int]: ...
    def hfield_into(
        self, out: npt.NDArray[np.float32], oversample: Optional[int] = None, z0: float = 0.0, elevation: float = 1.0
    ) -> None: ...
    def flat_patches(self, n: int, radius: Optional[float] = None, max_step: int = 0) -> npt.NDArray[np.float64]: ...
    def mesh(self) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]: ...
    def boxes(self) -> npt.NDArray[np.float64]: ...
    def mjcf(
        self,
        *,
        fragment: bool = False,
        prefix: str = "",
        offset: Optional[Union[tuple[_Float, _Float, _Float], list[_Float], npt.NDArray[np.floating]]] = None,
        friction: Optional[Union[float, tuple[float, ...], list[float]]] = None,
    ) -> str: ...
    def save(self, path: Union[str, os.PathLike[str]]) -> None: ...

@final
class Atlas:
    def __new__(
        cls,
        schemes: list[Union[Scheme, str, os.PathLike[str]]],
        rows: int,
        cols: int,
        *,
        seed: Optional[int] = None,
        border: Optional[int] = None,
        difficulty: Optional[Union[tuple[_Float, _Float], list[_Float], npt.NDArray[np.floating]]] = None,
        spawn_radius: Optional[float] = None,
        flat_patches: Optional[int] = None,
        patch_radius: Optional[float] = None,
        max_step: Optional[int] = None,
    ) -> Atlas: ...
    __signature__: ClassVar[inspect.Signature]
    @property
    def terrain(self) -> Terrain: ...
    @property
    def rows(self) -> int: ...
    @property
    def cols(self) -> int: ...
    @property
    def origins(self) -> npt.NDArray[np.float64]: ...
    @property
    def tiles(self) -> list[dict[str, object]]: ...
    def to_json(self) -> str: ...
    def flat_patches(self, n: int, radius: Optional[float] = None, max_step: int = 0) -> npt.NDArray[np.float64]: ...
    def write(
        self,
        out: Union[str, os.PathLike[str]],
        *,
        # The world options: scripts/python_stubs.py writes them from rse-world's table.
        targets: Optional[_Targets] = None,
        mesh: Optional[_MeshMode] = None,
        mujoco_collider: Optional[_MujocoCollider] = None,
        oversample: Optional[int] = None,
        template: Optional[Union[str, os.PathLike[str]]] = None,
        force: Optional[bool] = None,
    ) -> str: ...

@final
class EnvTerrains:
    def __new__(
        cls,
        scheme: Union[Scheme, Sequence[Scheme]],
        num_envs: int,
        *,
        # The per-env options: scripts/python_stubs.py writes them from rse-core's table.
        oversample: Optional[int] = None,
        seed: Optional[int] = None,
        env_offset: Optional[int] = None,
        difficulty: Optional[float] = None,
        layout: Optional[Literal["slots", "tiles"]] = None,
        cols: Optional[int] = None,
        border: Optional[int] = None,
        spawn_radius: Optional[float] = None,
        proportions: Optional[Sequence[float]] = None,
    ) -> EnvTerrains: ...
    __signature__: ClassVar[inspect.Signature]
    @property
    def scheme_ids(self) -> npt.NDArray[np.int64]: ...
    @property
    def schemes(self) -> list[Scheme]: ...
    @property
    def num_envs(self) -> int: ...
    @property
    def samples(self) -> npt.NDArray[np.float32]: ...
    @property
    def episode(self) -> npt.NDArray[np.int64]: ...
    @property
    def difficulty(self) -> npt.NDArray[np.float64]: ...
    @difficulty.setter
    def difficulty(self, values: Union[Sequence[float], npt.NDArray[np.floating]]) -> None: ...
    @property
    def origins(self) -> npt.NDArray[np.float64]: ...
    @property
    def layout(self) -> Literal["slots", "tiles"]: ...
    @property
    def field_shape(self) -> tuple[int, int]: ...
    @property
    def field_corners(self) -> npt.NDArray[np.int64]: ...
    @property
    def oversample(self) -> int: ...
    @property
    def hfield_size(self) -> tuple[float, float, float, float]: ...
    @property
    def hfield_pos(self) -> tuple[float, float, float]: ...
    def reset(
        self,
        env_ids: Union[Sequence[int], npt.NDArray[np.integer]],
        difficulty: Union[None, float, Sequence[float], npt.NDArray[np.floating]] = None,
    ) -> None: ...
    def terrain(self, env: int) -> Terrain: ...
    def contact_sheet(
        self,
        path: Optional[Union[str, os.PathLike[str]]] = None,
        *,
        env_ids: Union[None, Sequence[int], npt.NDArray[np.integer]] = None,
        cols: Optional[int] = None,
        cell_pixels: Optional[int] = None,
        names: Optional[Sequence[str]] = None,
        one_scale: Optional[bool] = None,
    ) -> bytes: ...
    def heights_at(
        self, env_ids: Union[Sequence[int], npt.NDArray[np.integer]], points: npt.ArrayLike
    ) -> npt.NDArray[np.float64]: ...
    def write(self, out: Any, env_ids: Union[None, Sequence[int], npt.NDArray[np.integer]] = None) -> None: ...
    def _copy_fields(
        self,
        env_ids: Union[Sequence[int], npt.NDArray[np.integer]],
        data: npt.NDArray[np.float32],
        starts: Union[Sequence[int], npt.NDArray[np.integer]],
        *,
        coarse: bool = False,
    ) -> None: ...

def scheme_mix(proportions: Sequence[float], num_envs: int, seed: int, env_offset: int = 0) -> npt.NDArray[np.int64]: ...
def generate_batch(
    scheme: Scheme, amount: int, seed: Optional[int] = None, jobs: Optional[int] = None, difficulty: Optional[float] = None
) -> list[Terrain]: ...
def _global_keywords() -> list[tuple[str, str, str, Optional[str]]]: ...
def _world_keywords() -> list[tuple[str, str, str, str]]: ...
def _env_keywords() -> list[tuple[str, str, str, str, Optional[str], str]]: ...
def write_worlds(
    scheme: Scheme,
    out: Union[str, os.PathLike[str]],
    *,
    amount: Optional[int] = None,
    seed: Optional[int] = None,
    jobs: Optional[int] = None,
    shard: Optional[str] = None,
    difficulty: Optional[float] = None,
    # The world options: scripts/python_stubs.py writes them from rse-world's table.
    targets: Optional[_Targets] = None,
    mesh: Optional[_MeshMode] = None,
    mujoco_collider: Optional[_MujocoCollider] = None,
    oversample: Optional[int] = None,
    template: Optional[Union[str, os.PathLike[str]]] = None,
    force: Optional[bool] = None,
) -> dict[str, int]: ...
def write_world(
    terrain: Terrain,
    out: Union[str, os.PathLike[str]],
    *,
    # The world options: scripts/python_stubs.py writes them from rse-world's table.
    targets: Optional[_Targets] = None,
    mesh: Optional[_MeshMode] = None,
    mujoco_collider: Optional[_MujocoCollider] = None,
    oversample: Optional[int] = None,
    template: Optional[Union[str, os.PathLike[str]]] = None,
    force: Optional[bool] = None,
) -> str: ...
def _time_generate(scheme: Scheme, count: int, seed: int = 0) -> float: ...
def _check_json(
    paths: list[Union[str, os.PathLike[str]]],
    physics: bool = False,
    jobs: Optional[int] = None,
    strict: bool = False,
    template: Optional[Union[str, os.PathLike[str]]] = None,
    budget: Optional[float] = None,
) -> str: ...
def _check_curriculum(
    scheme: Scheme, levels: int, draws: int, seed: Optional[int] = None, budget: Optional[float] = None
) -> tuple[list[tuple[int, float, float, float, float, float, float, int]], list[str], int]: ...
