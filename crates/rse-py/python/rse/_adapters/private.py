"""Every private API of a framework that an rse adapter uses, in one list:
what it is, which adapter needs it and why, and the framework versions it
was checked against (the pins of the framework tests, tests/*/requirements.txt).

A framework's private names can go in any release. So the adapters reach
them only through ``getattr_checked`` / ``setattr_checked`` (a name not on
this list is a programming error), and ``verify(framework)`` checks them
all against the installed framework without running it: each framework's
tests call it first (tests/*/test_private_api.py, in make test-frameworks
and CI), so a release that drops one fails with a message that names the
name, the adapter, the version checked and the version installed, instead
of an ``AttributeError`` deep in a training run.
"""

from __future__ import annotations

import functools
import importlib
import importlib.metadata
import inspect
from dataclasses import dataclass
from typing import Any


class PrivateApiError(RuntimeError):
    """A framework no longer has a private name an rse adapter uses."""


@dataclass(frozen=True)
class Framework:
    """A framework an adapter reaches into: its distribution on PyPI and
    the versions every use below was checked against."""

    distribution: str
    checked: tuple[str, ...]


@dataclass(frozen=True)
class Use:
    """One private name: ``attribute`` of ``owner`` (a module, or a class
    in it as ``module:Class``), used by ``adapter`` for ``why``.
    ``instance``: set on instances (in a method of the class or a base
    class), so ``verify`` looks for a declared field or ``self.<attribute> =``
    in their source."""

    framework: str
    owner: str
    attribute: str
    adapter: str
    why: str
    instance: bool = False

    @property
    def name(self) -> str:
        return f"{self.owner.replace(':', '.')}.{self.attribute}"


FRAMEWORKS = {
    "genesis": Framework("genesis-world", ("1.4.5",)),
    "mjlab": Framework("mjlab", ("1.6.0",)),
    "mujoco_warp": Framework("mujoco-warp", ("3.11.0",)),
    "newton": Framework("newton", ("1.8.0",)),
    "playground": Framework("playground", ("0.2.0",)),
    "gymnasium": Framework("gymnasium", ("1.4.0",)),
}
"""The frameworks below, by the name ``verify`` takes. Isaac Lab (2.3 and
3.0), MJX and MuJoCo are used through public names only."""

USES = (
    # Genesis: no public call rewrites a built terrain (rse.genesis.sync).
    Use("genesis", "genesis.engine.solvers.rigid.collider.collider:Collider", "collider_info", "rse.genesis.sync",
        "the collider's height field and bounds, rewritten in place", instance=True),
    Use("genesis", "genesis.engine.entities.rigid_entity.terrain_entity:TerrainEntity", "_terrain_height_field",
        "rse.genesis.sync", "the heights get_terrain_height answers from", instance=True),
    Use("genesis", "genesis.utils.misc", "qd_to_torch", "rse.genesis.sync",
        "a torch view of the collider's field, to write the reset envs' tiles in place"),
    # mjlab: the ray sensors' state.
    Use("mjlab", "mjlab.sensor.raycast_sensor:RayCastSensor", "_cached_world_origins", "rse.mjlab.exact_height_scan",
        "where the scan's rays start this step", instance=True),
    # mjlab's ray sensors' buffers and model, which rse.mjlab's FieldRays
    # casts into with one thread a ray (the kernel mjlab calls in its graph).
    *(
        Use("mjlab", "mjlab.sensor.raycast_sensor:RayCastSensor", name, "rse.mjlab FieldRays", why, instance=True)
        for name, why in (
            ("_model", "the device model the sensor casts in"),
            ("_data", "the device data (the geoms' poses)"),
            ("_mj_model", "the host model: which geoms the sensor's groups see"),
            ("_ray_pnt", "the rays' origins"),
            ("_ray_vec", "the rays' directions"),
            ("_geomgroup", "the sensor's geom groups"),
            ("_ray_bodyexclude", "each ray's excluded body"),
            ("_ray_dist", "the distances cast"),
            ("_ray_geomid", "the geoms hit"),
            ("_ray_normal", "the normals at the hits"),
        )
    ),
    # MuJoCo Warp's per-geom ray test, which FieldRays calls for the few
    # geoms a terrain sensor sees (its direct kernel tries them all).
    Use("mujoco_warp", "mujoco_warp._src.ray", "_ray_geom_mesh", "rse.mjlab FieldRays", "the ray test of one geom in one world"),
    Use("mujoco_warp", "mujoco_warp._src.types", "MJ_MAXVAL", "rse.mjlab FieldRays", "the distance of a miss"),
    Use("mujoco_warp", "mujoco_warp._src.types", "vec6", "rse.mjlab FieldRays", "the geom groups' type"),
    # MuJoCo Warp's render context (mjlab's camera sensors): per-field
    # BVHs, fields of a public class that MuJoCo Warp fills and reads itself.
    Use("mujoco_warp", "mujoco_warp:RenderContext", "hfield_registry", "rse.mjlab.EnvTerrainsEvent",
        "the meshes the cameras see, one per env's field", instance=True),
    Use("mujoco_warp", "mujoco_warp:RenderContext", "hfield_bvh_id", "rse.mjlab.EnvTerrainsEvent",
        "which mesh each height field's camera rays hit", instance=True),
    Use("mujoco_warp", "mujoco_warp:RenderContext", "hfield_bounds_size", "rse.mjlab.EnvTerrainsEvent",
        "the box each field's camera rays are tested against", instance=True),
    # Newton: a height field's samples as given (Newton rescales them).
    Use("newton", "newton:Heightfield", "_data", "rse.newton.add_heightfield",
        "the samples, kept in rse's [0, 1] of [0, top]", instance=True),
    Use("newton", "newton:Heightfield", "_cached_hash", "rse.newton.add_heightfield",
        "the hash of the samples, reset when they are replaced", instance=True),
    # Playground exports no Go1 class: rse.playground subclasses its own.
    Use("playground", "mujoco_playground._src.locomotion.go1.joystick", "Joystick", "rse.playground.go1_joystick",
        "the Go1 joystick task rse's stepfield task subclasses"),
    Use("playground", "mujoco_playground._src.locomotion.go1.joystick", "default_config", "rse.playground.go1_joystick",
        "the task's default config"),
    Use("playground", "mujoco_playground._src.locomotion.go1.base", "Go1Env", "rse.playground.go1_joystick",
        "the base class whose __init__ reads the scene from a path"),
    Use("playground", "mujoco_playground._src.locomotion.go1.go1_constants", "FEET_ONLY_ROUGH_TERRAIN_XML",
        "rse.playground.go1_joystick", "the rough scene whose height field rse replaces"),
    Use("playground", "mujoco_playground._src.locomotion.go1.joystick:Joystick", "_post_init",
        "rse.playground.go1_joystick", "the task's set-up after the model is read"),
    Use("playground", "mujoco_playground._src.locomotion.go1.base:Go1Env", "_mj_model", "rse.playground.go1_joystick",
        "the host model whose field rse fills", instance=True),
    Use("playground", "mujoco_playground._src.locomotion.go1.base:Go1Env", "_mjx_model", "rse.playground.go1_joystick",
        "the device model, put again after the field is filled", instance=True),
    # Gymnasium's Ant: rse.gym's env is a subclass that resets its own way.
    Use("gymnasium", "gymnasium.envs.mujoco.ant_v5:AntEnv", "_reset_noise_scale", "rse.gym.AntStepfieldEnv",
        "the Ant's reset noise, applied as Gymnasium's reset does", instance=True),
    Use("gymnasium", "gymnasium.envs.mujoco.ant_v5:AntEnv", "_get_obs", "rse.gym.AntStepfieldEnv",
        "the Ant's observation after a reset"),
)


def uses(framework: str) -> list[Use]:
    """The private names of ``framework`` (a key of ``FRAMEWORKS``)."""
    if framework not in FRAMEWORKS:
        raise ValueError(f"framework: {framework!r} is not one of {sorted(FRAMEWORKS)}")
    return [u for u in USES if u.framework == framework]


def installed_version(framework: str) -> str:
    """The installed version of ``framework``'s distribution, or "not
    installed"."""
    try:
        return importlib.metadata.version(FRAMEWORKS[framework].distribution)
    except importlib.metadata.PackageNotFoundError:
        return "not installed"


def _owner(owner: str) -> Any:
    module, _, cls = owner.partition(":")
    found: Any = importlib.import_module(module)
    for part in filter(None, cls.split(".")):
        found = getattr(found, part)
    return found


def _instance_attribute(cls: type, attribute: str) -> bool:
    """Whether instances of ``cls`` have ``attribute``: a field it or a
    base class declares (a dataclass's), or one a method sets
    (``self.attribute = ...``)."""
    needle = f"self.{attribute}"
    for klass in inspect.getmro(cls):
        if attribute in vars(klass).get("__annotations__", {}):
            return True
        try:
            source = inspect.getsource(klass)
        except (OSError, TypeError):
            continue
        if any(line.strip().startswith(needle) and "=" in line.split(needle, 1)[1][:4] for line in source.splitlines()):
            return True
    return False


def missing(use: Use) -> str:
    """Why ``use`` is not there in the installed framework, or ""."""
    try:
        owner = _owner(use.owner)
    except (ImportError, AttributeError) as e:
        return f"{use.owner.replace(':', '.')} does not import ({e})"
    if hasattr(owner, use.attribute):
        return ""
    if use.instance and inspect.isclass(owner) and _instance_attribute(owner, use.attribute):
        return ""
    return f"{use.name} is gone"


def _message(framework: str, problems: list[tuple[Use, str]]) -> str:
    fw = FRAMEWORKS[framework]
    lines = [
        f"{fw.distribution} (installed: {installed_version(framework)}; rse checked {', '.join(fw.checked)}) "
        "lacks private names rse's adapters use (rse._adapters.private):"
    ]
    lines += [f"  - {why}: {u.adapter} uses it for {u.why}" for u, why in problems]
    return "\n".join(lines)


def verify(framework: str) -> None:
    """Checks every private name ``framework``'s adapters use against the
    installed framework; a ``PrivateApiError`` lists those gone."""
    problems = [(u, why) for u in uses(framework) if (why := missing(u))]
    if problems:
        raise PrivateApiError(_message(framework, problems))


def _use(obj: Any, attribute: str, framework: str) -> Use:
    found = [u for u in uses(framework) if u.attribute == attribute and isinstance(obj, _owner_class(u))]
    if not found:
        raise AssertionError(f"{framework}: {type(obj).__name__}.{attribute} is not in rse._adapters.private.USES: list it there")
    return found[0]


@functools.lru_cache(maxsize=None)
def _owner_class(use: Use) -> type:
    owner = _owner(use.owner)
    return owner if inspect.isclass(owner) else type(None)


def getattr_checked(obj: Any, attribute: str, framework: str) -> Any:
    """``obj.attribute``, a listed private name of ``framework``; a
    ``PrivateApiError`` that says which when ``obj`` lacks it."""
    use = _use(obj, attribute, framework)
    try:
        return getattr(obj, attribute)
    except AttributeError:
        raise PrivateApiError(_message(framework, [(use, f"{use.name} is gone")])) from None


def setattr_checked(obj: Any, attribute: str, value: Any, framework: str) -> None:
    """Sets ``obj.attribute``, a listed private name of ``framework``,
    which ``obj`` must have already (setting a name the framework no
    longer reads would do nothing, silently)."""
    getattr_checked(obj, attribute, framework)
    setattr(obj, attribute, value)
