"""The elements of an SDF model as sdformat's URDF converter writes them (its reader
completes them, see _reader): inertials, visuals, collisions and their geometry, colours,
joint limits, and its numbers (C++'s 16 significant digits, a zero as 0)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import NamedTuple

from ..analysis.sdformat import stod
from ..model import Box, Cylinder, Geometry, Joint, JointType, Material, Mesh, Sphere
from ..spatial import urdfdom_angles
from ._lumping import Mass, Placement, euler
from ._reader import Element, single

__all__ = [
    "LUMP",
    "Shape",
    "colours",
    "geometry",
    "inertial",
    "limits",
    "number",
    "numbers",
    "pose",
    "shape",
    "short",
    "vector3",
]

LUMP = "_fixed_joint_lump__"  # between a body's name and a lumped shape's


class Shape(NamedTuple):
    """A visual or collision as the converter carries it: its name ("" for none), where it
    is in the link that holds it, its geometry and (visuals) its material."""

    name: str
    placement: Placement
    geometry: Geometry
    material: Material | None = None


def limits(joint: Joint) -> list[Element]:
    """The limit's children as the converter writes them (the reader adds a missing lower
    and upper, as -1e16 and 1e16)."""
    limit = joint.limit
    if limit is None:
        return []
    found = []
    if joint.type is not JointType.CONTINUOUS:
        lower, upper = sorted((limit.lower, limit.upper))  # sdformat swaps reversed ones
        found += [Element("lower", number(lower)), Element("upper", number(upper))]
    return [
        *found,
        Element("effort", number(limit.effort)),
        Element("velocity", number(limit.velocity)),
    ]


def inertial(mass: Mass) -> Element:
    """An ``inertial`` element: its frame, mass (kg) and inertia (kg*m^2)."""
    tags = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    inertia = [Element(tag, number(value)) for tag, value in zip(tags, mass.inertia, strict=True)]
    return Element(
        "inertial",
        children=[
            Element("pose", pose(mass.frame.xyz, euler(mass.frame.rotation))),
            Element("mass", number(mass.mass)),
            Element("inertia", children=inertia),
        ],
    )


def shape(kind: str, link: str, count: int, item: Shape) -> Element:
    """A ``visual`` or ``collision`` element, the ``count``-th of ``link``, named as the
    converter names it (``LINK_fixed_joint_lump__NAME_visual_1`` for a lumped one), without
    its material."""
    name = f"{item.name or link}_{kind}" + (f"_{count}" if count else "")
    if not name.startswith(link):
        name = f"{link}{LUMP}{name}"
    placed = pose(item.placement.xyz, urdfdom_angles(item.placement.rotation))
    children = [Element("pose", placed), *geometry(item.geometry)]
    return Element(kind, attributes=[("name", name)], children=children)


def geometry(solid: Geometry) -> list[Element]:
    """A ``geometry`` element; a mesh's ``package://`` becomes ``model://``."""
    if isinstance(solid, Box):
        inner = Element("box", children=[Element("size", numbers(solid.size))])
    elif isinstance(solid, Cylinder):
        inner = Element(
            "cylinder",
            children=[
                Element("length", number(solid.length)),
                Element("radius", number(solid.radius)),
            ],
        )
    elif isinstance(solid, Sphere):
        inner = Element("sphere", children=[Element("radius", number(solid.radius))])
    elif isinstance(solid, Mesh):
        scale = solid.scale or (1.0, 1.0, 1.0)
        uri = solid.filename.replace("package://", "model://", 1)
        inner = Element(
            "mesh",
            children=[
                # the converter writes a mesh's scale with C++'s default 6 digits
                Element("scale", " ".join(f"{v:g}" for v in scale)),
                Element("uri", uri),
            ],
        )
    else:  # pragma: no cover - the model has no other geometry
        return []
    return [Element("geometry", children=[inner])]


def colours(given: Material) -> tuple[str, str]:
    """urdfdom's colour (single precision; black if none) as Gazebo's diffuse and ambient."""
    rgba = given.color or (0.0, 0.0, 0.0, 1.0)
    r, g, b, a = (single(v) for v in rgba)
    diffuse = [min(max(c / 0.8, 0.0), 1.0) for c in (r, g, b)]
    ambient = [min(max(0.5 * c / 0.4, 0.0), 1.0) for c in (r, g, b)]
    return numbers((*diffuse, a)), numbers((*ambient, a))


def vector3(text: str) -> tuple[float, float, float]:
    """Three numbers as the converter's ParseVector3 reads them (split at spaces; anything
    but three numbers is 0 0 0)."""
    values = []
    for piece in text.split(" "):
        if piece:
            value = stod(piece)
            if value is None:
                return (0.0, 0.0, 0.0)
            values.append(value)
    return (values[0], values[1], values[2]) if len(values) == 3 else (0.0, 0.0, 0.0)


def short(values: Iterable[float]) -> str:
    """Numbers as C++ streams print them by default (6 significant digits)."""
    return " ".join(f"{v:g}" for v in values)


def number(value: float) -> str:
    """A number as the converter prints it: C++'s 16 significant digits, a zero as 0."""
    return "0" if value == 0 else f"{value:.16g}"


def numbers(values: tuple[float, ...] | list[float]) -> str:
    """Numbers as the converter prints them, separated by spaces."""
    return " ".join(number(v) for v in values)


def pose(xyz: tuple[float, float, float], rpy: tuple[float, float, float]) -> str:
    """A pose's text: x y z (metres), roll pitch yaw (radians)."""
    return numbers((*xyz, *rpy))
