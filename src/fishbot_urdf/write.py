"""Robot -> URDF XML text, losslessly: what ``parse`` reads back is an equal Robot."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping

from lxml import etree

from .errors import ArgumentError, RobotError, UnknownNameError
from .model import (
    DEFAULT_AXIS,
    Box,
    Collision,
    Cylinder,
    Geometry,
    Inertial,
    Joint,
    Link,
    Material,
    Mesh,
    Origin,
    Robot,
    Sphere,
    Visual,
)
from .validation import values
from .xml.source import STRING_PATH, parse_xml

__all__ = ["add_inertials", "inertial_xml", "rounded", "to_urdf"]


def _num(value: float) -> str:
    """The shortest text that reads back as the same float ('1' rather than '1.0')."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _nums(values: Iterable[float]) -> str:
    return " ".join(_num(v) for v in values)


def _sub(parent: etree._Element, tag: str, **attrs: str) -> etree._Element:
    element: etree._Element = etree.SubElement(parent, tag)
    for key, value in attrs.items():
        element.set(key, value)
    return element


def _numbers(parent: etree._Element, tag: str, item: object, names: Iterable[str]) -> None:
    """<tag name="number" ...> for the attributes ``names`` of ``item`` that are not None."""
    element = _sub(parent, tag)
    for name in names:
        value = getattr(item, name)
        if value is not None:
            element.set(name, _num(value))


def _origin(parent: etree._Element, origin: Origin) -> None:
    if origin != Origin():
        _sub(parent, "origin", xyz=_nums(origin.xyz), rpy=_nums(origin.rpy))


def _geometry(parent: etree._Element, geometry: Geometry) -> None:
    holder = _sub(parent, "geometry")
    if isinstance(geometry, Box):
        _sub(holder, "box", size=_nums(geometry.size))
    elif isinstance(geometry, Cylinder):
        _sub(holder, "cylinder", radius=_num(geometry.radius), length=_num(geometry.length))
    elif isinstance(geometry, Sphere):
        _sub(holder, "sphere", radius=_num(geometry.radius))
    elif isinstance(geometry, Mesh):
        mesh = _sub(holder, "mesh", filename=geometry.filename)
        if geometry.scale is not None:
            mesh.set("scale", _nums(geometry.scale))


def _material(parent: etree._Element, material: Material) -> None:
    element = _sub(parent, "material", name=material.name)
    if material.color is not None:
        _sub(element, "color", rgba=_nums(material.color))
    if material.texture is not None:
        _sub(element, "texture", filename=material.texture)


def _extras(parent: etree._Element, extras: Iterable[str]) -> None:
    for text in extras:
        parent.append(parse_xml(text.encode("utf-8")))


_MOMENTS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def _inertial(parent: etree._Element, inertial: Inertial) -> None:
    element = _sub(parent, "inertial")
    _origin(element, inertial.origin)
    _sub(element, "mass", value=_num(inertial.mass))
    _numbers(element, "inertia", inertial.inertia, _MOMENTS)


def _shape(parent: etree._Element, tag: str, item: Visual | Collision) -> etree._Element:
    element = _sub(parent, tag)
    if item.name is not None:
        element.set("name", item.name)
    _origin(element, item.origin)
    _geometry(element, item.geometry)
    return element


def _link(parent: etree._Element, link: Link) -> None:
    element = _sub(parent, "link", name=link.name)
    if link.inertial is not None:
        _inertial(element, link.inertial)
    for visual in link.visuals:
        shape = _shape(element, "visual", visual)
        if visual.material is not None:
            _material(shape, visual.material)
    for collision in link.collisions:
        _shape(element, "collision", collision)
    _extras(element, link.extras)


def _joint(parent: etree._Element, joint: Joint) -> None:
    element = _sub(parent, "joint", name=joint.name, type=joint.type.value)
    _origin(element, joint.origin)
    _sub(element, "parent", link=joint.parent)
    _sub(element, "child", link=joint.child)
    if joint.axis != DEFAULT_AXIS:
        _sub(element, "axis", xyz=_nums(joint.axis))
    # Each optional part, with the attributes it writes, in the order the spec lists them.
    parts = (
        ("calibration", ("rising", "falling")),
        ("dynamics", ("damping", "friction")),
        ("limit", ("lower", "upper", "effort", "velocity")),
        ("safety_controller", ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity")),
    )
    for tag, names in parts:
        part = getattr(joint, tag)
        if part is not None:
            # A bound the file left out stays out: MuJoCo and PyBullet read that otherwise.
            unset = getattr(part, "unset", ())
            _numbers(element, tag, part, [name for name in names if name not in unset])
    if joint.mimic is not None:
        mimic = _sub(element, "mimic", joint=joint.mimic.joint)
        mimic.set("multiplier", _num(joint.mimic.multiplier))
        mimic.set("offset", _num(joint.mimic.offset))
    _extras(element, joint.extras)


def to_urdf(robot: Robot) -> str:
    """Write ``robot`` as URDF XML text (materials, links, joints, then other elements).

    Reading the text back with ``fishbot_urdf.parse`` gives a Robot equal to ``robot``.

    Raises:
        FieldTypeError: A field of ``robot`` holds a value of the wrong type (a TypeError too).
        RobotError: ``robot`` holds what the reader would refuse (a number that is not finite,
            a missing name, a character XML cannot hold); ``.diagnostics`` lists each, as
            `fishbot_urdf.check` reports them.
    """
    refused = values(robot)
    if refused:
        raise RobotError(refused)
    root = etree.Element("robot", name=robot.name)
    if robot.version is not None:
        root.set("version", robot.version)
    for material in robot.materials:
        _material(root, material)
    for link in robot.links:
        _link(root, link)
    for joint in robot.joints:
        _joint(root, joint)
    _extras(root, robot.extras)
    etree.indent(root, space="  ")
    body = etree.tostring(root, encoding="unicode")
    return f'<?xml version="1.0"?>\n{body}\n'


# The digits an inertial told to a user keeps: a float's 17 show the arithmetic's noise
# (0.0037000000000000006 for 1/12 * (3 * 0.1^2 + 0.12^2)), 12 never a real difference.
_DIGITS = 12


def _round(value: float) -> float:
    return float(f"{value:.{_DIGITS}g}")


def rounded(inertial: Inertial) -> Inertial:
    """``inertial`` with every number rounded to 12 significant digits, as it is written
    for a user to read or paste: a float's last digits are the arithmetic's noise."""
    tensor = inertial.inertia
    return dataclasses.replace(
        inertial,
        mass=_round(inertial.mass),
        inertia=dataclasses.replace(
            tensor,
            ixx=_round(tensor.ixx),
            ixy=_round(tensor.ixy),
            ixz=_round(tensor.ixz),
            iyy=_round(tensor.iyy),
            iyz=_round(tensor.iyz),
            izz=_round(tensor.izz),
        ),
        origin=dataclasses.replace(
            inertial.origin,
            xyz=tuple(map(_round, inertial.origin.xyz)),  # type: ignore[arg-type]
            rpy=tuple(map(_round, inertial.origin.rpy)),  # type: ignore[arg-type]
        ),
    )


def inertial_xml(inertial: Inertial) -> str:
    """An ``<inertial>`` element as text, ready to paste in a link.

    Its children are indented by two spaces.

    The numbers are rounded to 12 significant digits (see :func:`rounded`), each written
    as the shortest text that reads back as that (``0.0037``, not
    ``0.0037000000000000006``).
    """
    holder = etree.Element("link")
    _inertial(holder, rounded(inertial))
    element = holder[0]
    if len(element) and element[0].tag != "origin":
        # Always say where the centre of mass is, even at the link origin.
        element.insert(0, etree.Element("origin", xyz="0 0 0", rpy="0 0 0"))
    etree.indent(element, space="  ")
    return etree.tostring(element, encoding="unicode") + "\n"


def add_inertials(
    data: bytes | str, inertials: Mapping[str, Inertial], path: str = STRING_PATH
) -> str:
    """The URDF ``data`` with an ``<inertial>`` added to each link named in ``inertials``.

    ``data`` is text or bytes; each inertial is the first child of its link, and everything
    else (comments, order, spacing) is kept.

    Raises:
        XmlSyntaxError: ``data`` is not well-formed XML.
        UnknownNameError: A name in ``inertials`` is no top-level link of the robot.
        ArgumentError: Such a link has an ``<inertial>`` already.
    """
    if isinstance(data, str):
        data = data.encode("utf-8")
    root = parse_xml(data, path)
    links = {element.get("name"): element for element in root if element.tag == "link"}
    for name, inertial in inertials.items():
        link = links.get(name)
        if link is None:
            raise UnknownNameError("link", name, (n for n in links if n is not None))
        if link.find("inertial") is not None:
            raise ArgumentError(f"link {name!r} has an <inertial> already", name=name)
        inner = link.text if link.text and not link.text.strip() else "\n    "
        holder = etree.Element("link")
        _inertial(holder, inertial)
        element = holder[0]
        etree.indent(element, space="  ", level=0)
        _shift(element, inner)
        element.tail = inner
        link.insert(0, element)
        link.text = inner
    # Top-level comments keep a line each (the parser drops the breaks between them).
    nodes = [*reversed(list(root.itersiblings(preceding=True))), root, *root.itersiblings()]
    head = ['<?xml version="1.0"?>'] if data.lstrip().startswith(b"<?xml") else []
    for node in nodes:
        node.tail = None
    return "\n".join(head + [etree.tostring(n, encoding="unicode") for n in nodes]) + "\n"


def _shift(element: etree._Element, indent: str) -> None:
    """Indent an element's children for an element that itself starts after ``indent``."""
    for child in element.iter():
        if child is element:
            if len(child):
                child.text = indent + "  "
            continue
        parent = child.getparent()
        last = parent is not None and child is parent[-1]
        depth = sum(1 for _ in child.iterancestors()) - sum(1 for _ in element.iterancestors())
        child.tail = indent + "  " * (depth - 1 if last else depth)
        if len(child):
            child.text = indent + "  " * (depth + 1)
