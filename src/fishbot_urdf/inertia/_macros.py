"""A xacro robot's own inertia macros (common_inertia.xacro's kind), found by calling them."""

from __future__ import annotations

import itertools
import math
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import FishbotUrdfError
from ..expansion import MacroDefinition, probe_macros
from ..location import Location
from ..model import Inertial, Origin
from ..parsing import parse
from ._solids import box_inertia, cylinder_inertia, sphere_inertia

if TYPE_CHECKING:
    from ..expansion import MacroTable

__all__ = ["InertiaMacro", "inertia_macros", "recognise_macros"]

# The solids a macro may write, by how many values a call gives (the mass, then the sizes),
# and the closed form each is held to.
_SOLIDS: dict[int, tuple[str, Callable[..., Inertial]]] = {
    2: ("sphere", sphere_inertia),
    3: ("cylinder", cylinder_inertia),
    4: ("box", box_inertia),
}
# Distinct values: the closed forms differ for every order of them, so a call with them tells
# apart which parameter is the mass and which size goes where.
_PROBE = (2.0, 3.0, 5.0, 7.0)
_PLACE = (0.25, 0.5, 0.75)  # a position or rotation given to an optional parameter


@dataclass(frozen=True, slots=True)
class InertiaMacro:
    """A macro of the robot that writes the <inertial> of a uniform solid.

    Attributes:
        shape: ``box``, ``cylinder`` or ``sphere``.
        name: The macro's name (``cylinder_inertia``).
        mass: Its parameter for the mass (kg).
        sizes: Its parameters for the sizes (m), in the order of the shape's element: a
            box's sides along x, y, z; a cylinder's radius and length; a sphere's radius.
        xyz: Its parameter for the inertial's position, if it has one.
        rpy: Its parameter for the inertial's rotation, if it has one.
        source: Where the macro is defined.
    """

    shape: str
    name: str
    mass: str
    sizes: tuple[str, ...]
    xyz: str | None = None
    rpy: str | None = None
    source: Location | None = None


def inertia_macros(
    path: str | Path,
    args: Mapping[str, str] | None = None,
    packages: Mapping[str, str | Path] | None = None,
    *,
    trust_expressions: bool | None = None,
    allow_read: str | os.PathLike[str] | Iterable[str | os.PathLike[str]] = (),
) -> tuple[InertiaMacro, ...]:
    """The macros of a xacro robot that write a box's, cylinder's or sphere's <inertial>.

    They are found whatever their names and their parameters' names: each top-level macro
    with two, three or four parameters without a default is called with distinct values
    (2, 3, 5, 7); it is one of them when what it makes is one <inertial> equal to a solid's
    closed form (:func:`box_inertia`, :func:`cylinder_inertia`, :func:`sphere_inertia`, in
    metres and kilograms) for some order of those values: that order names its mass and
    size parameters. An optional parameter is its position (rotation) parameter when a
    value given to it comes out as the inertial's origin xyz (rpy). A macro that takes a
    diameter, or other units, is not one.

    Args:
        path: The xacro file; the other arguments are :func:`fishbot_urdf.expand`'s.

    Raises:
        The errors of :func:`fishbot_urdf.expand`.
    """
    return probe_macros(
        path,
        recognise_macros,
        args,
        packages,
        trust_expressions=trust_expressions,
        allow_read=allow_read,
    )


def recognise_macros(table: MacroTable) -> tuple[InertiaMacro, ...]:
    """The inertia macros among the top-level macros of ``table`` (see `inertia_macros`)."""
    found = []
    for definition in table.definitions:
        macro = _recognise(table, definition)
        if macro is not None:
            found.append(macro)
    return tuple(found)


def _recognise(table: MacroTable, definition: MacroDefinition) -> InertiaMacro | None:
    required = definition.required
    solid = _SOLIDS.get(len(required))
    if solid is None:
        return None
    shape, formula = solid
    values = dict(zip(required, map(repr, _PROBE), strict=False))
    made = _inertial(table.call(definition.name, values))
    if made is None or made.origin != Origin():
        return None
    order = _order(made, required, formula)
    if order is None:
        return None
    mass, *sizes = order
    places: dict[str, str] = {}
    for param in definition.params:
        if param not in definition.optional or param.startswith("*"):
            continue
        place = " ".join(map(repr, _PLACE))
        moved = _inertial(table.call(definition.name, {**values, param: place}))
        if moved is None or moved.inertia != made.inertia:
            continue
        if moved.origin == Origin(xyz=_PLACE):
            places.setdefault("xyz", param)
        elif moved.origin == Origin(rpy=_PLACE):
            places.setdefault("rpy", param)
    return InertiaMacro(
        shape,
        definition.name,
        mass,
        tuple(sizes),
        places.get("xyz"),
        places.get("rpy"),
        definition.source,
    )


def _order(
    made: Inertial, params: Sequence[str], formula: Callable[..., Inertial]
) -> tuple[str, ...] | None:
    """The parameters as the formula takes them (mass, then sizes), if some order of the
    probe's values gives what the macro made."""
    given = dict(zip(params, _PROBE, strict=False))
    for order in itertools.permutations(params):
        numbers = [given[p] for p in order]
        if not math.isclose(numbers[0], made.mass, rel_tol=1e-12):
            continue
        expected = formula(*numbers).inertia
        if all(
            math.isclose(getattr(expected, f), getattr(made.inertia, f), rel_tol=1e-9, abs_tol=0)
            for f in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
        ):
            return order
    return None


def _inertial(text: str | None) -> Inertial | None:
    """The one <inertial> ``text`` holds, and nothing else, read as a URDF reads it."""
    if text is None:
        return None
    try:
        robot = parse(f'<robot name="probe"><link name="probe">{text}</link></robot>')
    except FishbotUrdfError:
        return None
    if len(robot.links) != 1 or robot.joints:
        return None
    link = robot.links[0]
    if link.visuals or link.collisions or link.extras:
        return None
    return link.inertial
