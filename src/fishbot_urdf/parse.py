"""URDF text or file -> Robot. One ``_parse_<tag>`` per element; every element keeps file:line:col."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from .diagnostics import Diagnostic, Severity
from .errors import RobotError, UnsupportedInputError
from .model import (
    DEFAULT_AXIS,
    ZERO3,
    Box,
    Calibration,
    Collision,
    Cylinder,
    Dynamics,
    Geometry,
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
from .xmlsource import STRING_PATH, Locator, diagnostic, parse_xml, read_bytes

__all__ = ["Parsed", "is_xacro_path", "load", "parse", "read"]

# What urdfdom's strToDouble accepts: an iostream ">> double" in the classic locale that must
# consume the whole text. Leading white space is skipped, trailing text (even a space) is not;
# no hex, no inf/nan, no digit separators.
_DOUBLE = re.compile(r"[ \t\n\v\f\r]*[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")

@dataclass(frozen=True, slots=True)
class Parsed:
    """The outcome of reading one file leniently: the robot (None if there is no <robot>)
    and every finding made while reading it."""

    path: str
    robot: Robot | None
    diagnostics: tuple[Diagnostic, ...]


def is_xacro_path(path: str | Path) -> bool:
    """True for ``.xacro`` files (``robot.xacro``, ``robot.urdf.xacro``)."""
    return str(path).lower().endswith(".xacro")


def read(source: str | Path | bytes, *, path: str | None = None) -> Parsed:
    """Read a URDF leniently, collecting every finding instead of stopping at the first.

    Args:
        source: A file path, or the document itself as bytes.
        path: The name to report for bytes (default ``<string>``).

    Raises:
        InputError: The file cannot be read.
        XmlSyntaxError: The file is not well-formed XML.
        UnsupportedInputError: The file is a .xacro file.
    """
    if isinstance(source, bytes):
        data, name = source, path or STRING_PATH
    else:
        name = path or str(source)
        if is_xacro_path(source):
            raise UnsupportedInputError(
                "this is a xacro file; xacro input is not supported yet "
                "(expand it to URDF first, e.g. `xacro robot.urdf.xacro > robot.urdf`; "
                "`fishbot expand` is coming)",
                path=name,
            )
        data = read_bytes(source)
    root = parse_xml(data, name)
    reader = _Reader(Locator(data, name))
    robot = reader.robot(root)
    return Parsed(name, robot, tuple(reader.diagnostics))


def parse(text: str | bytes, *, path: str | None = None) -> Robot:
    """Parse URDF text into a Robot.

    Raises:
        XmlSyntaxError: The text is not well-formed XML.
        RobotError: An element is malformed (``.diagnostics`` lists every finding).
    """
    data = text.encode("utf-8") if isinstance(text, str) else text
    if isinstance(text, str):
        # A str has been decoded already: an encoding declaration would mislead lxml.
        data = re.sub(rb"^\s*<\?xml[^>]*\?>", b"", data, count=1)
    return _strict(read(data, path=path or STRING_PATH))


def load(path: str | Path) -> Robot:
    """Load a URDF file into a Robot.

    Tree structure (undefined links, cycles, ...) is checked by ``fishbot_urdf.check``.

    Raises:
        InputError: The file cannot be read.
        XmlSyntaxError: The file is not well-formed XML.
        RobotError: An element is malformed (``.diagnostics`` lists every finding).
    """
    return _strict(read(path))


def _strict(parsed: Parsed) -> Robot:
    errors = [d for d in parsed.diagnostics if d.is_error]
    if errors or parsed.robot is None:
        raise RobotError(errors, path=parsed.path)
    return parsed.robot


def _xml_text(element: etree._Element) -> str:
    """An element URDF does not define, as compact XML text (layout white space dropped, so
    that a robot written out with another indentation reads back equal)."""
    copy = etree.fromstring(etree.tostring(element, with_tail=False))
    for node in copy.iter():
        if node.text is not None and not node.text.strip():
            node.text = None
        if node.tail is not None and not node.tail.strip():
            node.tail = None
    return etree.tostring(copy, encoding="unicode")


class _Reader:
    """Builds the model from the lxml tree, collecting findings as it goes."""

    def __init__(self, locator: Locator) -> None:
        self.locator = locator
        self.diagnostics: list[Diagnostic] = []

    # -- findings ---------------------------------------------------------------------------
    def error(
        self,
        rule: str,
        message: str,
        location: Location | None,
        hint: str | None = None,
        severity: Severity = Severity.ERROR,
    ) -> None:
        self.diagnostics.append(
            diagnostic(rule, message, location, hint=hint, severity=severity, path=self.locator.path)
        )

    def warn(self, rule: str, message: str, location: Location, hint: str | None = None) -> None:
        self.error(rule, message, location, hint, Severity.WARNING)

    # -- attributes -------------------------------------------------------------------------
    def text(self, el: etree._Element, at: Location, attr: str, owner: str) -> str | None:
        """A required string attribute; reports ``missing-attribute`` when absent or empty."""
        value = el.get(attr)
        if value is None or value == "":
            self.error(
                "missing-attribute",
                f"{owner}: <{el.tag}> has no {attr!r} attribute",
                at,
                f"write <{el.tag} {attr}=\"...\">",
            )
            return None
        return value

    def number(
        self,
        el: etree._Element,
        at: Location,
        attr: str,
        owner: str,
        default: float | None = None,
        *,
        required: bool = False,
    ) -> float | None:
        value = el.get(attr)
        if value is None:
            if required:
                self.error(
                    "missing-attribute",
                    f"{owner}: <{el.tag}> has no {attr!r} attribute",
                    at,
                    f"write <{el.tag} {attr}=\"NUMBER\">",
                )
            return default
        number = _to_double(value)
        if number is None:
            self._bad_number(el, at, attr, owner, value)
            return default
        return number

    def _bad_number(
        self, el: etree._Element, at: Location, attr: str, owner: str, value: str
    ) -> None:
        self.error(
            "bad-number",
            f"{owner}: <{el.tag} {attr}=\"{value}\"> is not a number",
            self.locator.attribute(at, attr),
            "write a finite decimal like 0.5 or 1e-3, with no units or trailing spaces",
        )

    def vector(
        self,
        el: etree._Element,
        at: Location,
        attr: str,
        owner: str,
        default: tuple[float, ...],
        *,
        required: bool = False,
        meaning: str = "x y z",
    ) -> tuple[float, ...]:
        value = el.get(attr)
        if value is None:
            if required:
                self.error(
                    "missing-attribute",
                    f"{owner}: <{el.tag}> has no {attr!r} attribute",
                    at,
                    f"write <{el.tag} {attr}=\"{meaning}\">",
                )
            return default
        # urdfdom splits on single spaces only and drops empty pieces; other white space
        # must then be leading white space of a number to be accepted.
        pieces = [p for p in value.split(" ") if p]
        numbers = [_to_double(p) for p in pieces]
        count = len(default)
        if len(numbers) != count:
            self.error(
                "bad-vector",
                f"{owner}: <{el.tag} {attr}=\"{value}\"> has {len(numbers)} "
                f"value{'s' if len(numbers) != 1 else ''}, {count} are needed",
                self.locator.attribute(at, attr),
                f"write {attr}=\"{meaning}\" separated by spaces",
            )
            return default
        if any(n is None for n in numbers):
            bad = next(p for p, n in zip(pieces, numbers, strict=True) if n is None)
            self.error(
                "bad-number",
                f"{owner}: <{el.tag} {attr}=\"{value}\">: {bad!r} is not a number",
                self.locator.attribute(at, attr),
                f"write {attr}=\"{meaning}\" as finite decimals separated by spaces",
            )
            return default
        return tuple(n for n in numbers if n is not None)

    def vector3(
        self,
        el: etree._Element,
        at: Location,
        attr: str,
        owner: str,
        default: tuple[float, float, float] = ZERO3,
        *,
        required: bool = False,
    ) -> tuple[float, float, float]:
        x, y, z = self.vector(el, at, attr, owner, default, required=required)
        return (x, y, z)

    # -- elements ---------------------------------------------------------------------------
    def robot(self, el: etree._Element) -> Robot | None:
        at = self.locator.locate(el)
        if el.tag != "robot":
            self.error(
                "no-robot",
                f"the root element is <{el.tag}>, not <robot>",
                at,
                "a URDF file holds one <robot name=\"...\"> element",
            )
            return None
        name = el.get("name")
        if not name:
            self.error(
                "robot-name",
                "<robot> has no name",
                at,
                "write <robot name=\"my_robot\">",
            )
        version = el.get("version")
        if version is not None and version not in ("1.0", "1.1"):
            self.error(
                "robot-version",
                f"<robot version=\"{version}\"> is not a URDF version this tool knows",
                self.locator.attribute(at, "version"),
                "use version=\"1.0\" or leave the attribute out",
            )
        links: list[Link] = []
        joints: list[Joint] = []
        materials: list[Material] = []
        extras: list[str] = []
        for child in el:
            if not isinstance(child.tag, str):
                continue  # comments and processing instructions
            if child.tag == "link":
                links.append(self.link(child, self.locator.locate(child)))
            elif child.tag == "joint":
                joints.append(self.joint(child, self.locator.locate(child)))
            elif child.tag == "material":
                materials.append(self.material(child, self.locator.locate(child), "robot"))
            else:
                extras.append(_xml_text(child))
        return Robot(
            name=name or "",
            links=tuple(links),
            joints=tuple(joints),
            materials=tuple(materials),
            version=version,
            extras=tuple(extras),
            source=at,
        )

    def material(self, el: etree._Element, at: Location, owner: str) -> Material:
        name = el.get("name")
        if name is None:
            # urdfdom accepts name="" (an anonymous colour, common in exported robots).
            self.error(
                "missing-attribute",
                f"{owner}: <material> has no name",
                at,
                "write <material name=\"...\">",
            )
        color = texture = None
        for child in el:
            if child.tag == "color":
                c_at = self.locator.locate(child)
                rgba = self.vector(
                    child, c_at, "rgba", f"material {name!r}", (0.0, 0.0, 0.0, 0.0),
                    required=True, meaning="red green blue alpha",
                )
                color = (rgba[0], rgba[1], rgba[2], rgba[3])
                if any(not 0.0 <= v <= 1.0 for v in color):
                    self.error(
                        "bad-color",
                        f"material {name!r}: <color rgba=\"{child.get('rgba')}\"> "
                        "has a value outside 0..1",
                        self.locator.attribute(c_at, "rgba"),
                        "each of red, green, blue and alpha is between 0 and 1",
                    )
            elif child.tag == "texture":
                self.locator.locate(child)
                # An empty <texture/> is common in exported robots; urdfdom ignores it too.
                texture = child.get("filename") or None
        return Material(name=name or "", color=color, texture=texture, source=at)

    def link(self, el: etree._Element, at: Location) -> Link:
        name = self.text(el, at, "name", "link") or ""
        owner = f"link {name!r}"
        inertial: Inertial | None = None
        visuals: list[Visual] = []
        collisions: list[Collision] = []
        extras: list[str] = []
        for child in el:
            tag = child.tag
            if tag == "visual":
                visuals.append(self.visual(child, self.locator.locate(child), owner))
            elif tag == "collision":
                collisions.append(self.collision(child, self.locator.locate(child), owner))
            elif tag == "inertial":
                c_at = self.locator.locate(child)
                if inertial is None:
                    inertial = self.inertial(child, c_at, owner)
                else:
                    self.warn(
                        "duplicate-element",
                        f"{owner}: a second <inertial> is ignored",
                        c_at,
                        "a link has at most one <inertial>",
                    )
                    extras.append(_xml_text(child))
            elif isinstance(tag, str):
                extras.append(_xml_text(child))
        return Link(
            name=name,
            inertial=inertial,
            visuals=tuple(visuals),
            collisions=tuple(collisions),
            extras=tuple(extras),
            source=at,
        )

    def inertial(self, el: etree._Element, at: Location, owner: str) -> Inertial:
        origin = Origin()
        mass = 0.0
        inertia = Inertia()
        has_mass = has_inertia = False
        for child in el:
            if child.tag == "origin":
                origin = self._joint_origin(child, self.locator.locate(child), owner)
            elif child.tag == "mass":
                c_at = self.locator.locate(child)
                has_mass = True
                mass = self.number(child, c_at, "value", owner, 0.0, required=True) or 0.0
            elif child.tag == "inertia":
                c_at = self.locator.locate(child)
                has_inertia = True
                values = [
                    self.number(child, c_at, key, owner, 0.0, required=True) or 0.0
                    for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
                ]
                inertia = Inertia(*values, source=c_at)
            elif isinstance(child.tag, str):
                self._ignored(child, owner, "<inertial> holds <origin>, <mass> and <inertia>")
        if not has_mass:
            self.error("missing-element", f"{owner}: <inertial> has no <mass>", at,
                       "write <mass value=\"KG\"/>")
        if not has_inertia:
            self.error("missing-element", f"{owner}: <inertial> has no <inertia>", at,
                       "write <inertia ixx=\"..\" ixy=\"0\" ixz=\"0\" iyy=\"..\" iyz=\"0\" "
                       "izz=\"..\"/>")
        return Inertial(mass=mass, inertia=inertia, origin=origin, source=at)

    def _ignored(self, el: etree._Element, owner: str, allowed: str) -> None:
        self.warn(
            "unknown-element",
            f"{owner}: <{el.tag}> is not allowed inside <{el.getparent().tag}> "  # type: ignore[union-attr]
            "and is ignored",
            self.locator.locate(el),
            allowed,
        )

    def visual(self, el: etree._Element, at: Location, owner: str) -> Visual:
        origin = Origin()
        geometry: Geometry | None = None
        material: Material | None = None
        seen_geometry = False
        for child in el:
            if child.tag == "origin":
                origin = self._joint_origin(child, self.locator.locate(child), owner)
            elif child.tag == "geometry":
                if not seen_geometry:
                    geometry = self.geometry(child, self.locator.locate(child), owner)
                seen_geometry = True
            elif child.tag == "material":
                material = self.material(child, self.locator.locate(child), owner)
            elif isinstance(child.tag, str):
                self._ignored(child, owner, "<visual> holds <origin>, <geometry> and <material>")
        if not seen_geometry:
            self._no_geometry(el, at, owner)
        return Visual(
            geometry=geometry or Box(ZERO3),
            origin=origin,
            material=material,
            name=el.get("name"),
            source=at,
        )

    def collision(self, el: etree._Element, at: Location, owner: str) -> Collision:
        origin = Origin()
        geometry: Geometry | None = None
        seen_geometry = False
        for child in el:
            if child.tag == "origin":
                origin = self._joint_origin(child, self.locator.locate(child), owner)
            elif child.tag == "geometry":
                if not seen_geometry:
                    geometry = self.geometry(child, self.locator.locate(child), owner)
                seen_geometry = True
            elif child.tag == "material":
                self.warn(
                    "collision-material",
                    f"{owner}: <material> inside <collision> is ignored",
                    self.locator.locate(child),
                    "colours belong in <visual>; move the <material> there",
                )
            elif isinstance(child.tag, str):
                self._ignored(child, owner, "<collision> holds <origin> and <geometry>")
        if not seen_geometry:
            self._no_geometry(el, at, owner)
        return Collision(
            geometry=geometry or Box(ZERO3), origin=origin, name=el.get("name"), source=at
        )

    def _no_geometry(self, el: etree._Element, at: Location, owner: str) -> None:
        self.error(
            "missing-element",
            f"{owner}: <{el.tag}> has no <geometry>",
            at,
            "write <geometry> with one <box>, <cylinder>, <sphere> or <mesh>",
        )

    def geometry(self, el: etree._Element, at: Location, owner: str) -> Geometry | None:
        shapes = [c for c in el if isinstance(c.tag, str)]
        if not shapes:
            self.error(
                "missing-element",
                f"{owner}: <geometry> is empty",
                at,
                "write one <box>, <cylinder>, <sphere> or <mesh> inside it",
            )
            return None
        shape = shapes[0]
        s_at = self.locator.locate(shape)
        for extra in shapes[1:]:
            self.warn(
                "duplicate-element",
                f"{owner}: <geometry> holds more than one shape; <{extra.tag}> is ignored",
                self.locator.locate(extra),
                "one <geometry> has exactly one shape; use another <visual> or <collision>",
            )
        tag = shape.tag
        if tag == "box":
            return Box(self.vector3(shape, s_at, "size", owner, required=True), source=s_at)
        if tag == "cylinder":
            radius = self.number(shape, s_at, "radius", owner, 0.0, required=True) or 0.0
            length = self.number(shape, s_at, "length", owner, 0.0, required=True) or 0.0
            return Cylinder(radius=radius, length=length, source=s_at)
        if tag == "sphere":
            radius = self.number(shape, s_at, "radius", owner, 0.0, required=True) or 0.0
            return Sphere(radius=radius, source=s_at)
        if tag == "mesh":
            filename = self.text(shape, s_at, "filename", owner) or ""
            scale = None
            if shape.get("scale") is not None:
                scale = self.vector3(shape, s_at, "scale", owner, (1.0, 1.0, 1.0))
            return Mesh(filename=filename, scale=scale, source=s_at)
        self.error(
            "unknown-geometry",
            f"{owner}: <{tag}> is not a URDF shape",
            s_at,
            "use <box>, <cylinder>, <sphere> or <mesh>",
        )
        return None

    def joint(self, el: etree._Element, at: Location) -> Joint:
        name = self.text(el, at, "name", "joint") or ""
        owner = f"joint {name!r}"
        type_text = el.get("type")
        joint_type = JointType.FIXED
        if type_text is None or type_text == "":
            self.error(
                "joint-type",
                f"{owner}: has no type",
                at,
                "write type=\"revolute|continuous|prismatic|fixed|floating|planar\"",
            )
        else:
            try:
                joint_type = JointType(type_text)
            except ValueError:
                self.error(
                    "joint-type",
                    f"{owner}: type {type_text!r} is not a URDF joint type",
                    self.locator.attribute(at, "type"),
                    "use revolute, continuous, prismatic, fixed, floating or planar",
                )
        fields: dict[str, object] = {}
        parent = child_link = ""
        ends: dict[str, Location] = {}
        seen: set[str] = set()
        extras: list[str] = []
        for child in el:
            tag = child.tag
            if not isinstance(tag, str):
                continue
            handler = self._JOINT_CHILDREN.get(tag)
            if handler is None or tag in seen:
                if tag in seen:
                    self.warn("duplicate-element", f"{owner}: a second <{tag}> is ignored",
                              self.locator.locate(child))
                else:
                    extras.append(_xml_text(child))
                continue
            seen.add(tag)
            c_at = self.locator.locate(child)
            if tag in ("parent", "child"):
                link_name = self.text(child, c_at, "link", owner) or ""
                if tag == "parent":
                    parent = link_name
                else:
                    child_link = link_name
                ends[tag] = c_at
                continue
            fields[handler] = getattr(self, "_joint_" + handler)(child, c_at, owner)
        for tag in ("parent", "child"):
            if tag not in seen:
                self.error(
                    "missing-element",
                    f"{owner}: has no <{tag}>",
                    at,
                    f"write <{tag} link=\"LINK_NAME\"/>",
                )
        return Joint(
            name=name,
            type=joint_type,
            parent=parent,
            child=child_link,
            origin=fields.get("origin", Origin()),  # type: ignore[arg-type]
            axis=fields.get("axis", DEFAULT_AXIS),  # type: ignore[arg-type]
            limit=fields.get("limit"),  # type: ignore[arg-type]
            dynamics=fields.get("dynamics"),  # type: ignore[arg-type]
            calibration=fields.get("calibration"),  # type: ignore[arg-type]
            mimic=fields.get("mimic"),  # type: ignore[arg-type]
            safety_controller=fields.get("safety_controller"),  # type: ignore[arg-type]
            extras=tuple(extras),
            source=at,
            parent_source=ends.get("parent"),
            child_source=ends.get("child"),
        )

    _JOINT_CHILDREN = {
        "parent": "parent",
        "child": "child",
        "origin": "origin",
        "axis": "axis",
        "limit": "limit",
        "dynamics": "dynamics",
        "calibration": "calibration",
        "mimic": "mimic",
        "safety_controller": "safety_controller",
    }

    def _joint_origin(self, el: etree._Element, at: Location, owner: str) -> Origin:
        return Origin(
            xyz=self.vector3(el, at, "xyz", owner),
            rpy=self.vector3(el, at, "rpy", owner),
            source=at,
        )

    def _joint_axis(self, el: etree._Element, at: Location, owner: str) -> tuple[float, ...]:
        return self.vector3(el, at, "xyz", owner, DEFAULT_AXIS, required=True)

    def _joint_limit(self, el: etree._Element, at: Location, owner: str) -> Limit:
        lower = self.number(el, at, "lower", owner, 0.0) or 0.0
        upper = self.number(el, at, "upper", owner, 0.0) or 0.0
        effort = self.number(el, at, "effort", owner, 0.0, required=True) or 0.0
        velocity = self.number(el, at, "velocity", owner, 0.0, required=True) or 0.0
        return Limit(effort=effort, velocity=velocity, lower=lower, upper=upper, source=at)

    def _joint_dynamics(self, el: etree._Element, at: Location, owner: str) -> Dynamics:
        damping = self.number(el, at, "damping", owner, 0.0) or 0.0
        friction = self.number(el, at, "friction", owner, 0.0) or 0.0
        return Dynamics(damping=damping, friction=friction, source=at)

    def _joint_calibration(self, el: etree._Element, at: Location, owner: str) -> Calibration:
        rising = self.number(el, at, "rising", owner)
        falling = self.number(el, at, "falling", owner)
        return Calibration(rising=rising, falling=falling, source=at)

    def _joint_mimic(self, el: etree._Element, at: Location, owner: str) -> Mimic:
        joint = self.text(el, at, "joint", owner) or ""
        multiplier = self.number(el, at, "multiplier", owner, 1.0)
        offset = self.number(el, at, "offset", owner, 0.0) or 0.0
        return Mimic(
            joint=joint,
            multiplier=1.0 if multiplier is None else multiplier,
            offset=offset,
            source=at,
        )

    def _joint_safety_controller(
        self, el: etree._Element, at: Location, owner: str
    ) -> SafetyController:
        return SafetyController(
            k_velocity=self.number(el, at, "k_velocity", owner, 0.0, required=True) or 0.0,
            k_position=self.number(el, at, "k_position", owner, 0.0) or 0.0,
            soft_lower_limit=self.number(el, at, "soft_lower_limit", owner, 0.0) or 0.0,
            soft_upper_limit=self.number(el, at, "soft_upper_limit", owner, 0.0) or 0.0,
            source=at,
        )


def _to_double(text: str) -> float | None:
    """Parse a number the way urdfdom does, and also refuse values that overflow to inf."""
    if _DOUBLE.fullmatch(text) is None:
        return None
    value = float(text)
    return value if math.isfinite(value) else None
