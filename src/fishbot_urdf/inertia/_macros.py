"""A xacro robot's own inertia macros, found by calling them, and what to write in a link."""

from __future__ import annotations

import itertools
import math
import os
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..analysis import Analysis, of
from ..errors import FishbotUrdfError
from ..expansion import MacroDefinition, probe_macros
from ..location import Location, MacroLocation, calls_of
from ..model import Box, Collision, Cylinder, Inertial, Link, Origin, Robot, Sphere
from ..parsing import parse
from ..write import inertial_xml
from ._solids import box_inertia, cylinder_inertia, sphere_inertia
from ._table import inertial_dict

if TYPE_CHECKING:
    from ..expansion import MacroTable

__all__ = [
    "InertiaMacro",
    "InertialSuggestion",
    "inertia_macros",
    "suggest_inertials",
    "xacro_suggestions",
]

# The solids a macro may write, by how many values a call gives (the mass, then the sizes),
# and the closed form each is held to.
_SOLIDS: dict[int, tuple[str, Callable[..., Inertial]]] = {
    2: ("sphere", sphere_inertia),
    3: ("cylinder", cylinder_inertia),
    4: ("box", box_inertia),
}
# Values no two of which are equal, and no sum of squares of which is another's: a call
# with them tells apart which parameter is the mass and which size goes where.
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
        _recognised,
        args,
        packages,
        trust_expressions=trust_expressions,
        allow_read=allow_read,
    )


def _recognised(table: MacroTable) -> tuple[InertiaMacro, ...]:
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
    values = dict(zip(required, map(_text, _PROBE), strict=False))
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
        moved = _inertial(table.call(definition.name, {**values, param: _texts(_PLACE)}))
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


@dataclass(frozen=True, slots=True)
class InertialSuggestion:
    """What to write in a link that has no <inertial>, and where.

    Attributes:
        link: The link's name.
        inertial: The inertial ``fill_inertials`` computed for it (what ``--fill -o``
            writes).
        source: Where its ``<link>`` is written (for a link a macro made, in the macro's
            body; ``made_by`` gives the calls).
        line: The line of ``source``'s file to write it at, inside the link (the line of
            its first child element), or None when no line is sure to be inside it (its
            children start on its own line, or are written in another file).
        macro: The robot's inertia macro to call, or None for a plain <inertial>.
        arguments: The call's parameters and their values, in the macro's order (rounded
            to 6 significant digits; a position or rotation only when not zero).
        plain_because: Why the <inertial> is written out rather than a macro's call (None
            for a call).
        written: For a link a macro made whose sizes (or position, rotation) are written
            there with expressions: the call's arguments as written in the macro's body
            (``r="${radius}"``), which fit every call of it; else empty.
    """

    link: str
    inertial: Inertial
    source: Location | None
    line: int | None
    macro: InertiaMacro | None = None
    arguments: tuple[tuple[str, str], ...] = ()
    plain_because: str | None = None
    written: tuple[tuple[str, str], ...] = ()

    @property
    def made_by(self) -> tuple[tuple[str, Location], ...]:
        """The macro calls that made the link, innermost first (none when it is written
        out in its file)."""
        return calls_of(self.source)

    @property
    def text(self) -> str:
        """What to write: ``<xacro:NAME .../>``, or the <inertial> element (with a final
        line break either way)."""
        if self.macro is None:
            return inertial_xml(self.inertial)
        return _call(self.macro, self.arguments)

    @property
    def written_text(self) -> str | None:
        """The call with the arguments as written in the macro's body, if there are any."""
        return _call(self.macro, self.written) if self.macro and self.written else None

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""

        def place(where: Location | None) -> dict[str, Any] | None:
            if where is None:
                return None
            return {"path": where.path, "line": where.line, "column": where.column}

        macro = self.macro
        return {
            "link": self.link,
            "source": place(self.source),
            "line": self.line,
            "made_by": [{"macro": name, "call": place(site)} for name, site in self.made_by],
            "macro": None
            if macro is None
            else {"name": macro.name, "shape": macro.shape, "source": place(macro.source)},
            "arguments": dict(self.arguments) if macro is not None else None,
            "text": self.text,
            "written": dict(self.written) if self.written else None,
            "written_text": self.written_text,
            "plain_because": self.plain_because,
            "inertial": inertial_dict(self.inertial),
        }


def suggest_inertials(
    robot: Robot | Analysis,
    inertials: Mapping[str, Inertial],
    macros: Sequence[InertiaMacro] = (),
    written: Mapping[Location, Mapping[str, str]] | None = None,
) -> tuple[InertialSuggestion, ...]:
    """What to write in each link of ``inertials``, and at which line.

    For each link of ``inertials`` (as :func:`fill_inertials` computed them): a call of one
    of ``macros`` (:func:`inertia_macros`) when the link's one collision is a box, cylinder
    or sphere that the macro can place, else the <inertial> itself.

    Args:
        robot: The robot, or its analysis.
        inertials: Link name -> the inertial computed for it.
        macros: The robot's inertia macros (none for a URDF).
        written: The attributes of elements as written in macro bodies, by where they
            are (what :func:`xacro_suggestions` reads), for the calls in the macro's terms.
    """
    links = of(robot).links
    return tuple(
        _suggestion(links[name], inertial, macros, written or {})
        for name, inertial in inertials.items()
    )


def xacro_suggestions(
    path: str | Path,
    robot: Robot | Analysis,
    inertials: Mapping[str, Inertial],
    args: Mapping[str, str] | None = None,
    packages: Mapping[str, str | Path] | None = None,
    *,
    trust_expressions: bool | None = None,
    allow_read: str | os.PathLike[str] | Iterable[str | os.PathLike[str]] = (),
) -> tuple[InertialSuggestion, ...]:
    """What to write in each link of a xacro robot's ``inertials``: its own macros' calls.

    :func:`suggest_inertials` with the robot's own inertia macros (as
    :func:`inertia_macros` finds them) and, for a link a macro made, its collision's sizes
    as written in the macro's body: one more expansion of the file.

    Args:
        path: The xacro file ``robot`` was read from; the other arguments are
            :func:`fishbot_urdf.expand`'s.

    Raises:
        The errors of :func:`fishbot_urdf.expand`.
    """
    links = of(robot).links
    places: list[Location] = []
    for name in inertials:
        for collision in links[name].collisions:
            for where in (collision.geometry.source, collision.origin.source):
                if isinstance(where, MacroLocation):
                    places.append(where)

    def probe(table: MacroTable) -> tuple[tuple[InertiaMacro, ...], dict[Location, Any]]:
        found = {where: table.written(where) for where in places}
        return _recognised(table), {k: v for k, v in found.items() if v is not None}

    macros, written = probe_macros(
        path,
        probe,
        args,
        packages,
        trust_expressions=trust_expressions,
        allow_read=allow_read,
    )
    return suggest_inertials(robot, inertials, macros, written)


def _suggestion(
    link: Link,
    inertial: Inertial,
    macros: Sequence[InertiaMacro],
    written: Mapping[Location, Mapping[str, str]],
) -> InertialSuggestion:
    line = _line(link)
    if len(link.collisions) != 1:
        return InertialSuggestion(
            link.name, inertial, link.source, line, plain_because="several collision shapes"
        )
    collision = link.collisions[0]
    shape, sizes = _solid(collision.geometry)
    if shape is None:
        return InertialSuggestion(
            link.name, inertial, link.source, line, plain_because="its collision is a mesh"
        )
    fitting = [m for m in macros if m.shape == shape]
    if not fitting:
        why = f"the robot has no {shape} inertia macro" if macros else "no inertia macros"
        return InertialSuggestion(link.name, inertial, link.source, line, plain_because=why)
    origin = collision.origin
    for macro in fitting:
        if (any(origin.xyz) and macro.xyz is None) or (any(origin.rpy) and macro.rpy is None):
            continue
        arguments = [(macro.mass, _text(inertial.mass))]
        arguments += [(p, _text(v)) for p, v in zip(macro.sizes, sizes, strict=True)]
        if macro.xyz is not None and any(origin.xyz):
            arguments.append((macro.xyz, _texts(origin.xyz)))
        if macro.rpy is not None and any(origin.rpy):
            arguments.append((macro.rpy, _texts(origin.rpy)))
        return InertialSuggestion(
            link.name,
            inertial,
            link.source,
            line,
            macro,
            tuple(arguments),
            written=_as_written(arguments, macro, collision, link.source, written),
        )
    why = f"{fitting[0].name} takes no position or rotation, and the {shape} is moved"
    return InertialSuggestion(link.name, inertial, link.source, line, plain_because=why)


def _as_written(
    arguments: list[tuple[str, str]],
    macro: InertiaMacro,
    collision: Collision,
    where: Location | None,
    written: Mapping[Location, Mapping[str, str]],
) -> tuple[tuple[str, str], ...]:
    """``arguments`` with the sizes, position and rotation as the macro's body that has
    the <link> at ``where`` writes them, when one of them is an expression there (else
    none: the numbers are what is written)."""
    geometry = _written_beside(collision.geometry.source, where, written)
    origin = _written_beside(collision.origin.source, where, written)
    texts: dict[str, str] = {}
    if geometry is not None:
        if isinstance(collision.geometry, Box):
            sides = _TOKEN.findall(geometry.get("size", ""))
            if len(sides) == 3:
                texts.update(zip(macro.sizes, sides, strict=True))
        else:
            cylinder = isinstance(collision.geometry, Cylinder)
            keys = ("radius", "length") if cylinder else ("radius",)
            for param, key in zip(macro.sizes, keys, strict=True):
                if key in geometry:
                    texts[param] = geometry[key]
    if origin is not None:
        for place, key in ((macro.xyz, "xyz"), (macro.rpy, "rpy")):
            if place is not None and key in origin:
                texts[place] = origin[key]
    if not any("${" in text for text in texts.values()):
        return ()
    return tuple((name, texts.get(name, value)) for name, value in arguments)


def _written_beside(
    part: Location | None, link: Location | None, written: Mapping[Location, Mapping[str, str]]
) -> Mapping[str, str] | None:
    """The attributes as written of the element at ``part``, if it is written beside the
    <link> (its expressions then mean there what they mean in the element)."""
    if part is None or link is None or not _beside(part, link):
        return None
    return written.get(part)


# One number or expression of a list of them: a `${...}` may hold spaces.
_TOKEN = re.compile(r"(?:\$\{[^}]*\}|[^\s$]|\$(?!\{))+")


def _call(macro: InertiaMacro, arguments: Iterable[tuple[str, str]]) -> str:
    given = " ".join(f'{name}="{value}"' for name, value in arguments)
    return f"<xacro:{macro.name} {given}/>\n"


def _solid(geometry: object) -> tuple[str | None, tuple[float, ...]]:
    if isinstance(geometry, Box):
        return "box", tuple(geometry.size)
    if isinstance(geometry, Cylinder):
        return "cylinder", (geometry.radius, geometry.length)
    if isinstance(geometry, Sphere):
        return "sphere", (geometry.radius,)
    return None, ()


def _line(link: Link) -> int | None:
    """The line to write a child of ``link`` at: that of its first child element, when it
    starts below the <link> in the same text (else None: no line is sure to be inside)."""
    where = link.source
    if where is None:
        return None
    children = [v.source for v in link.visuals] + [c.source for c in link.collisions]
    below = [
        child.line
        for child in children
        if child is not None and _beside(child, where) and child.line > where.line
    ]
    return min(below) if below else None


def _beside(where: Location, link: Location) -> bool:
    """Whether ``where`` is in the same text as the <link> at ``link``: the same file, and
    made by the same macro calls (an element a macro called inside the link made is written
    in that macro's body, elsewhere, even in the same file)."""
    return where.path == link.path and calls_of(where) == calls_of(link)


def _text(value: float) -> str:
    """A number to 6 significant digits, as short as it reads ('0.1', not '0.100000')."""
    text = f"{value:.6g}"
    return "0" if text == "-0" else text


def _texts(values: Iterable[float]) -> str:
    return " ".join(_text(v) for v in values)
