"""What to write in a link that has no <inertial>, and where: a macro's call or the element."""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..analysis import Analysis, of
from ..expansion import probe_macros
from ..location import Location, MacroLocation, calls_of
from ..model import Box, Collision, Cylinder, Inertial, Link, Robot, Sphere
from ..write import inertial_xml, rounded
from ._macros import InertiaMacro, recognise_macros
from ._table import inertial_dict

if TYPE_CHECKING:
    from ..expansion import Argument, MacroDefinition, MacroTable

__all__ = [
    "InertialSuggestion",
    "call_text",
    "number_text",
    "place_dict",
    "suggest_inertials",
    "xacro_suggestions",
]


@dataclass(frozen=True, slots=True)
class InertialSuggestion:
    """What to write in a link that has no <inertial>, and where.

    Attributes:
        link: The link's name.
        inertial: The inertial ``fill_inertials`` computed for it (what ``--fill -o``
            writes; ``text`` and ``to_dict`` give it to 12 significant digits).
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
        given: For a link a macro made: what the call that made it gave that macro's
            parameters (by :func:`xacro_suggestions`; else empty).
        maker: The definition of the macro that made the link, when it is one of the
            robot's top-level macros (by :func:`xacro_suggestions`; else None).
    """

    link: str
    inertial: Inertial
    source: Location | None
    line: int | None
    macro: InertiaMacro | None = None
    arguments: tuple[tuple[str, str], ...] = ()
    plain_because: str | None = None
    written: tuple[tuple[str, str], ...] = ()
    given: tuple[tuple[str, Argument], ...] = ()
    maker: MacroDefinition | None = None

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
        return call_text(self.macro, self.arguments)

    @property
    def written_text(self) -> str | None:
        """The call with the arguments as written in the macro's body, if there are any."""
        return call_text(self.macro, self.written) if self.macro and self.written else None

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""

        place = place_dict
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
            "inertial": inertial_dict(rounded(self.inertial)),
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

    def probe(table: MacroTable) -> tuple[Any, ...]:
        found = {where: table.written(where) for where in places}
        given = {name: table.arguments(calls_of(links[name].source)) for name in inertials}
        makers = {d.name: d for d in table.definitions}
        return (
            recognise_macros(table),
            {k: v for k, v in found.items() if v is not None},
            given,
            makers,
        )

    macros, written, given, makers = probe_macros(
        path,
        probe,
        args,
        packages,
        trust_expressions=trust_expressions,
        allow_read=allow_read,
    )
    made = []
    for suggestion in suggest_inertials(robot, inertials, macros, written):
        calls = suggestion.made_by
        if calls:
            arguments = given.get(suggestion.link) or {}
            suggestion = dataclasses.replace(
                suggestion, given=tuple(arguments.items()), maker=makers.get(calls[0][0])
            )
        made.append(suggestion)
    return tuple(made)


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


def call_text(macro: InertiaMacro, arguments: Iterable[tuple[str, str]]) -> str:
    """``<xacro:NAME param="value" .../>`` with a final line break."""
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


def number_text(value: float) -> str:
    """A number to 6 significant digits, as short as it reads ('0.1', not '0.100000')."""
    text = f"{value:.6g}"
    return "0" if text == "-0" else text


_text = number_text


def _texts(values: Iterable[float]) -> str:
    return " ".join(_text(v) for v in values)


def place_dict(where: Location | None) -> dict[str, Any] | None:
    """A location, JSON-ready: its path, line and column."""
    if where is None:
        return None
    return {"path": where.path, "line": where.line, "column": where.column}
