"""What sdformat 12 refuses in a robot's ``<gazebo>`` blocks: the values its URDF converter
reads with C++'s std::stod and std::stoi (it crashes on one that is no number), and the
values its reader refuses for their element's type and bounds, from SDFormat 1.9's
description in sdf_1.9.json."""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterator
from functools import cache
from importlib import resources
from typing import Any, NamedTuple, Protocol

__all__ = [
    "FLAGS",
    "IGNORED",
    "NUMBERS",
    "SETTINGS",
    "TEXTS",
    "WHOLE",
    "Description",
    "Node",
    "Refusal",
    "allowed",
    "bounds",
    "children",
    "describe",
    "refusal",
    "refusals",
    "stod",
    "stoi",
]

Description = dict[str, Any]

NUMBERS = {  # settings the converter reads with std::stod, and the SDF element each is put in
    "dampingFactor": ("link.sdf", "velocity_decay", "linear"),
    "maxVel": ("collision.sdf", "surface", "contact", "ode", "max_vel"),
    "minDepth": ("collision.sdf", "surface", "contact", "ode", "min_depth"),
    "mu1": ("collision.sdf", "surface", "friction", "ode", "mu"),
    "mu2": ("collision.sdf", "surface", "friction", "ode", "mu2"),
    "kp": ("collision.sdf", "surface", "contact", "ode", "kp"),
    "kd": ("collision.sdf", "surface", "contact", "ode", "kd"),
    "laserRetro": ("collision.sdf", "laser_retro"),
    "springReference": ("joint.sdf", "axis", "dynamics", "spring_reference"),
    "springStiffness": ("joint.sdf", "axis", "dynamics", "spring_stiffness"),
    "stopCfm": ("joint.sdf", "physics", "ode", "limit", "cfm"),
    "stopErp": ("joint.sdf", "physics", "ode", "limit", "erp"),
    "fudgeFactor": ("joint.sdf", "physics", "ode", "fudge_factor"),
}
WHOLE = {"maxContacts": ("collision.sdf", "max_contacts")}  # read with std::stoi
TEXTS = {"fdir1": ("collision.sdf", "surface", "friction", "ode", "fdir1")}  # put as written
FLAGS = {"static", "selfCollide", "provideFeedback", "implicitSpringDamper"}
IGNORED = {"canonicalBody", "disableFixedJointLumping", "preserveFixedJoint"}
SETTINGS = frozenset(  # every element the converter reads as a setting, not copies
    {*NUMBERS, *WHOLE, *TEXTS, *FLAGS, *IGNORED, "material", "cfmDamping", "turnGravityOff"}
)


@cache
def _files() -> dict[str, Description]:
    text = resources.files(__package__).joinpath("sdf_1.9.json").read_text(encoding="utf-8")
    files: dict[str, Description] = json.loads(text)
    return files


def children(description: Description) -> list[Description]:
    """The element descriptions below ``description``, includes resolved."""
    found = []
    for child in description.get("children", ()):
        if "include" in child:
            included = _files().get(child["include"])
            if included is not None:
                found.append({**included, "required": child["required"]})
        else:
            found.append(child)
    return found


def describe(file: str, *path: str) -> Description | None:
    """The description of the element at ``path`` below the top one of ``file``
    (``"collision.sdf", "surface"``), None where SDFormat 1.9 has none."""
    description: Description | None = _files().get(file)
    for name in path:
        if description is None:
            return None
        description = next((d for d in children(description) if d["name"] == name), None)
    return description


_STOD = re.compile(
    r"\s*[+-]?(?:0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)(?:[pP][+-]?\d+)?"
    r"|(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan(?:\([0-9A-Za-z_]*\))?)",
    re.IGNORECASE,
)


def stod(text: str) -> float | None:
    """``text`` as C++'s std::stod reads it: the longest number it starts with (None where
    it throws)."""
    found = _STOD.match(text)
    if found is None:
        return None
    token = found.group().strip()
    try:
        if token.lower().lstrip("+-").startswith("0x"):
            return float.fromhex(token)
        value = float(re.sub(r"\(.*\)", "", token))
    except (ValueError, OverflowError):
        return None
    return value if math.isfinite(value) or token[-1].isalpha() or token[-1] == ")" else None


def stoi(text: str) -> int | None:
    """``text`` as C++'s std::stoi reads it: the whole number it starts with (None where it
    throws)."""
    found = re.match(r"\s*[+-]?\d+", text)
    value = int(found.group()) if found is not None else None
    return value if value is not None and -(2**31) <= value < 2**31 else None


_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_SIZES = {"vector3": 3, "vector2d": 2, "color": 3}
_ALLOWED = {
    "bool": "true, false, 1 or 0",
    "double": "a number",
    "float": "a number",
    "int": "a whole number",
    "unsigned int": "a whole number",
    "vector3": "3 numbers",
    "vector2d": "2 numbers",
    "color": "3 or 4 numbers from 0 to 1",
    "pose": "6 numbers",
}


def refusal(description: Description, text: str) -> str | None:
    """Why sdformat's reader refuses ``text`` for an element of ``description``'s type, None
    where it takes it: a bool that is none of true, false, 1, 0; a number that does not
    start as one (as std::stod reads it; a whole number, with a digit), or is out of the
    element's bounds; a vector of fewer numbers than it has, a pose of other than 6, a colour
    with a number beyond 0 to 1."""
    kind = description["type"]
    if kind == "bool" and text.lower() not in ("true", "false", "1", "0"):
        return "is no bool"
    if kind in ("double", "float", "int", "unsigned int"):
        whole = kind.endswith("int")
        value = stod(text) if not whole or re.match(r"\s*[+-]?\d", text) else None
        if value is None:
            return "is no number"
        return bounds(description, value)
    if kind in _SIZES:
        tokens = text.split()[: _SIZES[kind]]
        if len(tokens) < _SIZES[kind] or not all(_NUMBER.fullmatch(t) for t in tokens):
            return f"is not {_SIZES[kind]} numbers"
        if kind == "color" and not all(0 <= float(t) <= 1 for t in text.split()[:4]):
            return "is not a colour (each of its numbers from 0 to 1)"
    if kind == "pose":
        tokens = text.split()
        if len(tokens) != 6 or not all(_NUMBER.fullmatch(t) for t in tokens):
            return "is not 6 numbers"
    return None


def bounds(description: Description, value: float) -> str | None:
    """Why ``value`` is out of the bounds of ``description``'s element, None where it is in."""
    if "min" in description and value < float(description["min"]):
        return f"is less than {description['min']}, its least"
    if "max" in description and value > float(description["max"]):
        return f"is more than {description['max']}, its most"
    return None


def allowed(description: Description) -> str:
    """What the reader takes for an element of ``description``: its type, and its bounds."""
    what = _ALLOWED.get(description["type"], "text")
    low, high = description.get("min"), description.get("max")
    if low is not None and high is not None:
        return f"{what} from {low} to {high}"
    if low is not None:
        return f"{what} >= {low}"
    if high is not None:
        return f"{what} <= {high}"
    return what


class Node(Protocol):
    """An element of the robot's text, as lxml reads it."""

    tag: object
    text: str | None

    def __iter__(self) -> Iterator[Node]: ...

    def __len__(self) -> int: ...

    def get(self, key: str) -> str | None: ...


class Refusal(NamedTuple):
    """An element the reader refuses, why, and what it would take."""

    element: Node
    why: str
    allowed: str


def refusals(element: Node, description: Description) -> Iterator[Refusal]:
    """Every element at or below ``element`` (one of a robot's text, that the converter
    copies to where ``description`` is) whose value the reader refuses: a typed one with a
    bad value, or a required one left empty. It does not look into an element it copies
    as it is (a plugin) or one it does not know."""
    if "default" in description:
        text = element.text if element.text is not None and element.text.strip() else None
        if text is None:
            if description["required"] == "1":
                yield Refusal(element, "is empty", allowed(description))
        else:
            why = refusal(description, text.strip())
            if why is not None:
                yield Refusal(element, why, allowed(description))
    if description.get("copy"):
        return
    known = {d["name"]: d for d in reversed(children(description))}
    for child in element:
        if isinstance(child.tag, str) and child.tag in known:
            yield from refusals(child, known[child.tag])
