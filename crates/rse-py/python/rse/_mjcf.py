"""``Terrain.mjcf``'s options: our MuJoCo template's model, made to fit
into a robot's model (a fragment, a name prefix, an offset, a friction).

A terrain's MJCF has one source, the template the world folders use; this
only edits its tree, so the default model keeps its bytes. (The empty
height-field slot of ``rse.mujoco.hfield_mjcf`` is not a terrain: a field
to write terrains into later, with its shape and radii from rse-core's
``hfield_layout``.)
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
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
