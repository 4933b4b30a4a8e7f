"""The values of a robot built in Python: each field of its declared type, each number finite,
each name one the reader would give.

The reader gives every field the type the model declares, refuses numbers that are not
finite (``bad-number``) and names that are missing (``missing-attribute``, ``robot-name``),
and never keeps a character XML cannot hold. A Robot built in Python may hold anything:
`values` walks one once and holds it to what the reader would have read.

- A field of the wrong type (a str where a number is, a list where a tuple is, an int where a
  `JointType` is) raises `FieldTypeError` naming the field: no rule can look at such a model.
  A name that is None is no type error but a missing name, as in a file.
- A value the reader would refuse is a finding of the reader's own rule, an error:
  ``bad-number`` (nan, inf), ``missing-attribute`` and ``robot-name`` (no name),
  ``bad-color``, ``robot-version``, and ``xml-control-char`` (a character XML cannot hold,
  which no file can give the model: its reader keeps U+FFFD in its place).

`fishbot_urdf.check` and `fishbot_urdf.to_urdf` call `values` first; the model's classes
check nothing when they are made. A check in ``__post_init__`` doubles the cost of making an
Origin (0.60 -> 1.21 us), and would run for every object the reader makes, on values it has
checked already. Here the cost is paid
once per call: a quick test of all links and joints at once (`._plain`) passes
a read robot, and only a robot that fails it is walked field by field. Read 10,000-link tree
(best of 12): check 461 -> 527 ms, to_urdf 848 -> 908 ms; `check_file` and the command line
do not walk (the reader has checked). 1,000-link tree, callgrind: the quick test 51 M
instructions, the walk 256 M, the other rules 190 M.
"""

from __future__ import annotations

import math
from numbers import Real
from typing import TypeVar

from ..catalog import Rule
from ..catalog.reading import (
    BAD_COLOR,
    BAD_NUMBER,
    MISSING_ATTRIBUTE,
    ROBOT_NAME,
    ROBOT_VERSION,
    FieldFacts,
)
from ..catalog.xml import XML_CONTROL_CHAR
from ..diagnostics import Diagnostic, Kind, Severity, Subject
from ..errors import FieldTypeError
from ..model import (
    Box,
    Calibration,
    Collision,
    Cylinder,
    Dynamics,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Location,
    Material,
    Mesh,
    Mimic,
    Origin,
    Robot,
    SafetyController,
    Sphere,
    Visual,
)
from ..parsing._reader import _VERSION  # the one test of a version, the reader's
from ._plain import bounds_named, plain

__all__ = ["values"]

_T = TypeVar("_T")

_NUMBER = "a number (int or float)"
_SHAPES = (Box, Cylinder, Sphere, Mesh)
# The code points XML 1.0 cannot hold (lxml refuses to write them): control characters but
# tab, line feed and carriage return, lone surrogates, and the non-characters U+FFFE, U+FFFF.
_NOT_XML = frozenset(
    [*range(0x09), 0x0B, 0x0C, *range(0x0E, 0x20), *range(0xD800, 0xE000), 0xFFFE, 0xFFFF]
)


def values(robot: Robot, path: str | None = None) -> list[Diagnostic]:
    """Every finding about a value of ``robot`` that the reader would refuse (see the module).

    Args:
        robot: The robot, built in Python or read.
        path: The file findings without a place are reported against (default: where the
            robot was read, else ``<robot>``, as `fishbot_urdf.analyse` reports them).

    Raises:
        FieldTypeError: A field holds a value of the wrong type (the first one found).
    """
    if not isinstance(robot, Robot):
        raise FieldTypeError("robot", "a Robot", robot)
    source = _source(robot.source, "robot.source")
    walk = _Walk(path or (source.path if source is not None else "<robot>"))
    walk.robot(robot)
    return walk.found


def _source(value: object, field: str) -> Location | None:
    if value is None or isinstance(value, Location):
        return value
    raise FieldTypeError(field, "a Location or None", value)


def _items(value: object, cls: type[_T], field: str) -> tuple[_T, ...]:
    """``value``, a tuple whose every item is a ``cls``."""
    if not isinstance(value, tuple):
        raise FieldTypeError(field, f"a tuple of {cls.__name__}", value)
    for index, item in enumerate(value):
        if not isinstance(item, cls):
            raise FieldTypeError(f"{field}[{index}]", f"a {cls.__name__}", item)
    return value


def _shown(value: float) -> str:
    """A number as a message shows it (``nan``, ``inf``, ``0.5``)."""
    return f"{float(value):g}"


def _finite(value: object, field: str) -> bool:
    """Whether the number ``value`` is finite; FieldTypeError if it is no number, or an int
    no float can hold (which no rule could compute with)."""
    if type(value) is float:  # nearly always
        return value - value == 0.0
    if not isinstance(value, Real):  # a bool is an int, as for mypy
        raise FieldTypeError(field, _NUMBER, value)
    try:
        return math.isfinite(float(value))
    except OverflowError:
        raise FieldTypeError(field, "a number a float can hold", value) from None


def _forbidden(text: str) -> str | None:
    """How a message names the first character of ``text`` that XML cannot hold, if any."""
    if text.isascii() and text.isprintable():  # nearly always
        return None
    for char in text:
        if ord(char) in _NOT_XML:
            code = ord(char)
            if code < 0x20:
                return f"control character 0x{code:02X}"
            if code < 0xE000:
                return f"a lone surrogate U+{code:04X}"
            return f"U+{code:04X}, not a character"
    return None


def _label(kind: str, index: int, count: int) -> str:
    """``visual``, or ``visual 2`` when the link has several."""
    return kind if count == 1 else f"{kind} {index + 1}"


def _owner(kind: Kind, name: object, field: str) -> tuple[Subject, str]:
    """What findings are about, and how messages name it: ``link 'base'``, or for a link
    with no name, ``link at robot.links[2]``."""
    if isinstance(name, str) and name:
        owner = Subject(kind, name)
        return owner, str(owner)
    return Subject(kind, ""), f"{kind.value} at {field}"


class _Walk:
    """One walk over a robot: raises at the first wrong type, collects findings about the
    link, joint or material being walked (``owner``, named ``who`` in messages)."""

    def __init__(self, path: str) -> None:
        self.path = path
        self.found: list[Diagnostic] = []
        self.owner = Subject(Kind.ROBOT, "")
        self.who = "the robot"

    def report(
        self, rule: Rule, message: str, where: Location | None, hint: str, field: str
    ) -> None:
        self.found.append(
            rule.report(
                message,
                where,
                path=self.path,
                subject=self.owner,
                hint=hint,
                severity=Severity.ERROR,
                data=FieldFacts(field=field),
            )
        )

    # -- values ---------------------------------------------------------------------------
    def number(self, value: object, field: str, label: str, where: Location | None) -> None:
        if not _finite(value, field):
            shown = _shown(value)  # type: ignore[arg-type]
            self.report(BAD_NUMBER, f"{self.who}: {label} is {shown}", where, _FINITE, field)

    def numbers(
        self, value: object, size: int, field: str, label: str, where: Location | None
    ) -> tuple[float, ...]:
        """A tuple of ``size`` numbers; one finding if any is not finite."""
        if not isinstance(value, tuple) or len(value) != size:
            raise FieldTypeError(field, f"a tuple of {size} numbers", value)
        finite = True
        for index, number in enumerate(value):
            finite = _finite(number, f"{field}[{index}]") and finite
        if not finite:
            shown = " ".join(map(_shown, value))
            self.report(BAD_NUMBER, f"{self.who}: {label} is {shown}", where, _FINITE, field)
        return value

    def text(
        self,
        value: object,
        field: str,
        label: str,
        where: Location | None,
        *,
        optional: bool = True,
    ) -> None:
        """A str (or None, when ``optional``); a finding for a character XML cannot hold."""
        if value is None and optional:
            return
        if not isinstance(value, str):
            raise FieldTypeError(field, "a str or None" if optional else "a str", value)
        what = _forbidden(value)
        if what is not None:
            shown = "its name" if label == "name" else f"{label} {value!r}"  # named already
            self.report(
                XML_CONTROL_CHAR,
                f"{self.who}: {shown} holds {what}, which XML cannot hold",
                where,
                "XML 1.0 forbids it, so the robot cannot be written; delete it",
                field,
            )

    def name(
        self,
        value: object,
        field: str,
        tag: str,
        where: Location | None,
        *,
        attr: str = "name",
        within: str = "",
        empty: bool = False,
    ) -> None:
        """A name the reader requires, of ``<tag attr="...">`` (in the owner's ``within``):
        the reader's finding when it is None (or "", unless ``empty``)."""
        element = f"{within} <{tag}>".lstrip()
        if value is None or (value == "" and not empty):
            self.report(
                MISSING_ATTRIBUTE,
                f"{self.who}: {element} has no {attr!r} attribute",
                where,
                f'write <{tag} {attr}="...">',
                field,
            )
            return
        own = not within and tag == self.owner.kind.value and attr == "name"
        self.text(value, field, "name" if own else f"{element} {attr}", where, optional=False)

    # -- the model ------------------------------------------------------------------------
    def robot(self, robot: Robot) -> None:
        name, where = robot.name, robot.source
        self.owner = Subject(Kind.ROBOT, name if isinstance(name, str) else "")
        self.who = f"robot {name!r}" if isinstance(name, str) and name else "the robot"
        if name is None or name == "":
            self.report(
                ROBOT_NAME,
                "<robot> has no name",
                where,
                'write <robot name="my_robot">',
                "robot.name",
            )
        else:
            self.text(name, "robot.name", "name", where, optional=False)
        version = robot.version
        self.text(version, "robot.version", "version", where)
        if isinstance(version, str) and not _known(version):
            self.report(
                ROBOT_VERSION,
                f'<robot version="{version}"> is not a URDF version this tool knows',
                where,
                'use version="1.0" or leave the attribute out',
                "robot.version",
            )
        _items(robot.extras, str, "robot.extras")
        materials = _items(robot.materials, Material, "robot.materials")
        for index, material in enumerate(materials):
            field = f"robot.materials[{index}]"
            self.owner, self.who = _owner(Kind.MATERIAL, material.name, field)
            self.material(material, field, "")
        if plain(robot):  # a read robot's links and joints are
            return
        for index, link in enumerate(_items(robot.links, Link, "robot.links")):
            self.link(link, f"robot.links[{index}]")
        for index, joint in enumerate(_items(robot.joints, Joint, "robot.joints")):
            self.joint(joint, f"robot.joints[{index}]")

    def material(self, material: Material, field: str, within: str) -> None:
        """A material of the robot's own (``within`` empty), or of a link's visual."""
        where = _source(material.source, f"{field}.source")
        name = material.name
        # urdfdom reads name="" (an anonymous colour), and so does the reader.
        self.name(name, f"{field}.name", "material", where, within=within, empty=True)
        label = ""  # a material of the robot's own is the owner
        if within:
            named = f" {name!r}" if isinstance(name, str) and name else ""
            label = f"{within} material{named}"
        if material.color is not None:
            shown = f"{label} color".lstrip()
            color = self.numbers(material.color, 4, f"{field}.color", shown, where)
            if all(map(math.isfinite, color)) and not all(0.0 <= v <= 1.0 for v in color):
                numbers = " ".join(map(_shown, color))
                self.report(
                    BAD_COLOR,
                    f"{self.who}: {shown} {numbers} has a value outside 0..1",
                    where,
                    "each of red, green, blue and alpha is between 0 and 1",
                    f"{field}.color",
                )
        self.text(material.texture, f"{field}.texture", f"{label} texture".lstrip(), where)

    def origin(self, origin: object, field: str, label: str) -> None:
        if not isinstance(origin, Origin):
            raise FieldTypeError(field, "an Origin", origin)
        where = _source(origin.source, f"{field}.source")
        self.numbers(origin.xyz, 3, f"{field}.xyz", f"{label} xyz".lstrip(), where)
        self.numbers(origin.rpy, 3, f"{field}.rpy", f"{label} rpy".lstrip(), where)

    def link(self, link: Link, field: str) -> None:
        where = _source(link.source, f"{field}.source")
        self.owner, self.who = _owner(Kind.LINK, link.name, field)
        self.name(link.name, f"{field}.name", "link", where)
        _items(link.extras, str, f"{field}.extras")
        if link.inertial is not None:
            self.inertial(link.inertial, f"{field}.inertial")
        visuals = _items(link.visuals, Visual, f"{field}.visuals")
        for index, visual in enumerate(visuals):
            label = _label("visual", index, len(visuals))
            self.shape(visual, f"{field}.visuals[{index}]", label)
        collisions = _items(link.collisions, Collision, f"{field}.collisions")
        for index, collision in enumerate(collisions):
            label = _label("collision", index, len(collisions))
            self.shape(collision, f"{field}.collisions[{index}]", label)

    def inertial(self, inertial: object, field: str) -> None:
        if not isinstance(inertial, Inertial):
            raise FieldTypeError(field, "an Inertial or None", inertial)
        where = _source(inertial.source, f"{field}.source")
        self.number(inertial.mass, f"{field}.mass", "inertial mass", where)
        self.origin(inertial.origin, f"{field}.origin", "inertial origin")
        inertia = inertial.inertia
        if not isinstance(inertia, Inertia):
            raise FieldTypeError(f"{field}.inertia", "an Inertia", inertia)
        at = _source(inertia.source, f"{field}.inertia.source") or where
        for part in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
            self.number(getattr(inertia, part), f"{field}.inertia.{part}", f"inertial {part}", at)

    def shape(self, shape: Visual | Collision, field: str, label: str) -> None:
        where = _source(shape.source, f"{field}.source")
        self.text(shape.name, f"{field}.name", f"{label} name", where)
        self.origin(shape.origin, f"{field}.origin", f"{label} origin")
        geometry = shape.geometry
        here = f"{field}.geometry"
        if not isinstance(geometry, _SHAPES):
            raise FieldTypeError(here, "a Box, Cylinder, Sphere or Mesh", geometry)
        at = _source(geometry.source, f"{here}.source") or where
        if isinstance(geometry, Box):
            self.numbers(geometry.size, 3, f"{here}.size", f"{label} box size", at)
        elif isinstance(geometry, Cylinder):
            self.number(geometry.radius, f"{here}.radius", f"{label} cylinder radius", at)
            self.number(geometry.length, f"{here}.length", f"{label} cylinder length", at)
        elif isinstance(geometry, Sphere):
            self.number(geometry.radius, f"{here}.radius", f"{label} sphere radius", at)
        else:
            self.name(
                geometry.filename, f"{here}.filename", "mesh", at, attr="filename", within=label
            )
            if geometry.scale is not None:
                self.numbers(geometry.scale, 3, f"{here}.scale", f"{label} mesh scale", at)
        if isinstance(shape, Visual) and shape.material is not None:
            if not isinstance(shape.material, Material):
                raise FieldTypeError(f"{field}.material", "a Material or None", shape.material)
            self.material(shape.material, f"{field}.material", label)

    def joint(self, joint: Joint, field: str) -> None:
        where = _source(joint.source, f"{field}.source")
        self.owner, self.who = _owner(Kind.JOINT, joint.name, field)
        self.name(joint.name, f"{field}.name", "joint", where)
        if not isinstance(joint.type, JointType):
            raise FieldTypeError(f"{field}.type", "a JointType", joint.type)
        for end in ("parent", "child"):
            at = _source(getattr(joint, f"{end}_source"), f"{field}.{end}_source") or where
            self.name(getattr(joint, end), f"{field}.{end}", end, at, attr="link")
        self.origin(joint.origin, f"{field}.origin", "origin")
        self.numbers(joint.axis, 3, f"{field}.axis", "axis", where)
        _items(joint.extras, str, f"{field}.extras")
        for part, cls, names in _PARTS:
            item = getattr(joint, part)
            if item is None:
                continue
            here = f"{field}.{part}"
            if not isinstance(item, cls):
                raise FieldTypeError(here, f"a {cls.__name__} or None", item)
            at = _source(item.source, f"{here}.source") or where
            if isinstance(item, Limit) and item.unset != () and not bounds_named(item.unset):
                raise FieldTypeError(f"{here}.unset", 'a tuple of "lower" and "upper"', item.unset)
            for number in names:
                value = getattr(item, number)
                if value is not None or part != "calibration":  # its two may be None
                    self.number(value, f"{here}.{number}", f"{part} {number}", at)
            if isinstance(item, Mimic):
                self.name(item.joint, f"{here}.joint", "mimic", at, attr="joint")


def _known(version: str) -> bool:
    """Whether urdfdom reads ``version`` as 1.0, the one version it supports."""
    parts = _VERSION.fullmatch(version)
    return parts is not None and (int(parts[1]), int(parts[2])) == (1, 0)


_FINITE = "write finite numbers"
_Part = Limit | Dynamics | Calibration | Mimic | SafetyController
_PARTS: tuple[tuple[str, type[_Part], tuple[str, ...]], ...] = (
    ("limit", Limit, ("effort", "velocity", "lower", "upper")),
    ("dynamics", Dynamics, ("damping", "friction")),
    ("calibration", Calibration, ("rising", "falling")),
    ("mimic", Mimic, ("multiplier", "offset")),
    (
        "safety_controller",
        SafetyController,
        ("k_velocity", "k_position", "soft_lower_limit", "soft_upper_limit"),
    ),
)
