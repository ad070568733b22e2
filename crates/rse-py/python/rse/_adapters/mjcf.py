"""Every MJCF text rse makes or edits in Python, in one place:

- ``adapt``: ``Terrain.mjcf``'s options on our MuJoCo template's model,
  made to fit into a robot's model (a fragment, a name prefix, an offset, a
  friction). A terrain's MJCF has one source, the template the world
  folders use; this only edits its tree, so the default model keeps its
  bytes.
- ``field_model``: a model of empty height fields and the geom showing one
  (``rse.mujoco.hfield_mjcf``, ``env_hfields_mjcf``): fields to write
  terrains into after compiling, their shape and radii from rse-core's
  ``hfield_layout``.
- ``replace_field``: another's model (Playground's rough scene) with its
  height field resized to rse's and its geom moved, edited as a tree.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from typing import Any, Optional

# The globals a fragment leaves to the robot's model.
_GLOBALS = ("compiler", "option", "visual")
# Assets only the full model's floor uses.
_FLOOR_ASSETS = ("grid",)


def _fmt(v: float) -> str:
    return repr(float(v)) if not float(v).is_integer() else str(int(v))


def _friction(friction: Any) -> Optional[str]:
    if friction is None:
        return None
    try:
        if isinstance(friction, (str, bytes)):
            raise TypeError
        try:
            numbers = [float(friction)]
        except TypeError:
            numbers = [float(v) for v in friction]
    except (TypeError, ValueError):
        raise TypeError(f"friction: expected a number or up to three of them, got {friction!r}") from None
    if not 1 <= len(numbers) <= 3 or not all(math.isfinite(v) and v >= 0 for v in numbers):
        raise ValueError(
            f"friction: expected 1 to 3 numbers of 0 or more (sliding, torsional, rolling), got {friction!r}"
        )
    return " ".join(_fmt(v) for v in numbers)


def adapt(xml: str, fragment: bool, prefix: str, offset: tuple, friction: Any) -> str:
    """``xml`` (our template's model) with ``Terrain.mjcf``'s options applied."""
    friction_text = _friction(friction)
    ox, oy, oz = (float(v) for v in offset)
    if not all(math.isfinite(v) for v in (ox, oy, oz)):
        raise ValueError(f"offset: expected three finite numbers (metres), got {offset!r}")
    if not fragment and not prefix and (ox, oy, oz) == (0.0, 0.0, 0.0) and friction_text is None:
        return xml
    root = ET.fromstring(xml)
    asset = root.find("asset")
    world = root.find("worldbody")
    assert asset is not None and world is not None, "our MuJoCo template has <asset> and <worldbody>"
    if fragment:
        for tag in _GLOBALS:
            for element in root.findall(tag):
                root.remove(element)
        for element in list(world):
            if element.tag == "light" or element.get("name") == "floor":
                world.remove(element)
        for element in list(asset):
            if element.get("name") in _FLOOR_ASSETS:
                asset.remove(element)
    geoms = [g for g in world if g.tag == "geom" and g.get("name") != "floor"]
    # The terrain's geoms in one static body: moved together by `offset`,
    # and one element a robot's model can find and attach.
    body = ET.Element("body", name="terrain", pos=f"{_fmt(ox)} {_fmt(oy)} {_fmt(oz)}")
    for g in geoms:
        world.remove(g)
        if friction_text is not None:
            g.set("friction", friction_text)
        body.append(g)
    world.append(body)
    if prefix:
        root.set("model", prefix + root.get("model", "rse"))
        for element in root.iter():
            for key in ("name", "material", "texture", "mesh", "hfield"):
                if key in element.attrib:
                    element.set(key, prefix + element.attrib[key])
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n"


def _tag(tag: str, attrs: Sequence[tuple[str, str]]) -> str:
    return f"<{tag} " + " ".join(f'{k}="{v}"' for k, v in attrs) + "/>"


def floats(values: Sequence[float]) -> str:
    """Numbers as Python writes them back exactly (``repr``)."""
    return " ".join(repr(float(v)) for v in values)


def field_model(
    model: str,
    fields: Sequence[str],
    shape: tuple[int, int],
    size: Sequence[float],
    pos: str,
    rgba: str,
    *,
    light: Optional[Sequence[float]] = None,
    group: Optional[int] = None,
) -> str:
    """An MJCF model named ``model`` holding the height fields ``fields``,
    each of ``shape`` (rows, columns) and MuJoCo ``size`` (x and y radii,
    elevation, base), no samples (MJCF rescales given samples to span
    [0, 1]: write them after compiling), and a geom showing the first at
    ``pos`` (its text); a light straight above ``light`` (x, y) when given."""
    nrow, ncol = shape
    assets = [
        "    " + _tag("hfield", [("name", f), ("nrow", str(nrow)), ("ncol", str(ncol)), ("size", floats(size))]) for f in fields
    ]
    body = []
    if light is not None:
        body.append("    " + _tag("light", [("pos", f"{floats(light)} 5"), ("dir", "0 0 -1")]))
    geom = [("name", fields[0]), ("type", "hfield"), ("hfield", fields[0]), ("pos", pos), ("rgba", rgba)]
    if group is not None:
        geom.append(("group", str(group)))
    body.append("    " + _tag("geom", geom))
    lines = [f'<mujoco model="{model}">', "  <asset>", *assets, "  </asset>", "  <worldbody>", *body, "  </worldbody>", "</mujoco>"]
    return "\n".join(lines) + "\n"


def replace_field(xml: str, field: str, geom: str, shape: tuple[int, int], size: Sequence[float], pos: Sequence[float]) -> str:
    """``xml`` with its height field ``field`` resized to ``shape`` and
    ``size`` (its file or samples dropped: rse writes them after
    compiling) and the geom ``geom`` showing it moved to ``pos``. A
    ``ValueError`` naming the model when it has not exactly one of each."""
    root = ET.fromstring(xml)
    fields = [e for e in root.iter("hfield") if e.get("name") == field]
    geoms = [e for e in root.iter("geom") if e.get("name") == geom and e.get("type") == "hfield"]
    if len(fields) != 1 or len(geoms) != 1:
        raise ValueError(f'the scene: expected one <hfield name="{field}"> and one <geom name="{geom}" type="hfield">')
    element = fields[0]
    element.attrib.clear()
    element.attrib.update(name=field, nrow=str(shape[0]), ncol=str(shape[1]), size=" ".join(f"{v:.9g}" for v in size))
    geoms[0].set("pos", " ".join(f"{v:.9g}" for v in pos))
    return ET.tostring(root, encoding="unicode") + "\n"
