"""The elements of an SDF model as sdformat's URDF converter writes them and its SDF reader
completes them: inertials, visuals, collisions and their geometry, joint limits, and its
numbers (C++'s 16 significant digits, a zero as 0)."""

from __future__ import annotations

import math
import struct
from typing import NamedTuple
from xml.sax.saxutils import escape

from ..model import Box, Cylinder, Geometry, Joint, JointType, Material, Mesh, Sphere
from ..spatial import urdfdom_angles
from ._lumping import Mass, Placement, euler

__all__ = [
    "LUMP",
    "Shape",
    "attr",
    "geometry",
    "inertial",
    "limits",
    "number",
    "numbers",
    "pose",
    "shape",
    "single",
]

LUMP = "_fixed_joint_lump__"  # between a body's name and a lumped shape's


class Shape(NamedTuple):
    """A visual or collision as the converter carries it: its name ("" for none), where it
    is in the link that holds it, its geometry and (visuals) its material."""

    name: str
    placement: Placement
    geometry: Geometry
    material: Material | None = None


def limits(joint: Joint) -> list[str]:
    """The limit's children as the converter writes them and the SDF reader completes them
    (a missing lower and upper read as -1e16 and 1e16)."""
    limit = joint.limit
    lines = []
    if limit is not None:
        if joint.type is not JointType.CONTINUOUS:
            lower, upper = sorted((limit.lower, limit.upper))  # sdformat swaps reversed ones
            lines += [f"<lower>{number(lower)}</lower>", f"<upper>{number(upper)}</upper>"]
        lines += [f"<effort>{number(limit.effort)}</effort>"]
        lines += [f"<velocity>{number(limit.velocity)}</velocity>"]
    if limit is None or joint.type is JointType.CONTINUOUS:
        lines += ["<lower>-1e16</lower>", "<upper>1e16</upper>"]
    return lines


def inertial(mass: Mass) -> list[str]:
    """An ``inertial`` element: its frame, mass (kg) and inertia (kg*m^2)."""
    ixx, ixy, ixz, iyy, iyz, izz = mass.inertia
    return [
        "<inertial>",
        f"  <pose>{pose(mass.frame.xyz, euler(mass.frame.rotation))}</pose>",
        f"  <mass>{number(mass.mass)}</mass>",
        "  <inertia>",
        *(
            f"    <{tag}>{number(value)}</{tag}>"
            for tag, value in zip(
                ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"),
                (ixx, ixy, ixz, iyy, iyz, izz),
                strict=True,
            )
        ),
        "  </inertia>",
        "</inertial>",
    ]


def shape(kind: str, link: str, count: int, item: Shape) -> list[str]:
    """A ``visual`` or ``collision`` element, the ``count``-th of ``link``, named as the
    converter names it (``LINK_fixed_joint_lump__NAME_visual_1`` for a lumped one)."""
    name = f"{item.name or link}_{kind}" + (f"_{count}" if count else "")
    if not name.startswith(link):
        name = f"{link}{LUMP}{name}"
    lines = [
        f"<{kind} name={attr(name)}>",
        f"  <pose>{pose(item.placement.xyz, urdfdom_angles(item.placement.rotation))}</pose>",
        *(f"  {line}" for line in geometry(item.geometry)),
    ]
    if item.material is not None:
        lines += [f"  {line}" for line in material(item.material)]
    return [*lines, f"</{kind}>"]


def geometry(solid: Geometry) -> list[str]:
    """A ``geometry`` element; a mesh's ``package://`` becomes ``model://``."""
    if isinstance(solid, Box):
        inner = ["<box>", f"  <size>{numbers(solid.size)}</size>", "</box>"]
    elif isinstance(solid, Cylinder):
        inner = [
            "<cylinder>",
            f"  <length>{number(solid.length)}</length>",
            f"  <radius>{number(solid.radius)}</radius>",
            "</cylinder>",
        ]
    elif isinstance(solid, Sphere):
        inner = ["<sphere>", f"  <radius>{number(solid.radius)}</radius>", "</sphere>"]
    elif isinstance(solid, Mesh):
        scale = solid.scale or (1.0, 1.0, 1.0)
        uri = solid.filename.replace("package://", "model://", 1)
        inner = [
            "<mesh>",
            # the converter writes a mesh's scale with C++'s default 6 digits
            f"  <scale>{' '.join(f'{v:g}' for v in scale)}</scale>",
            f"  <uri>{escape(uri)}</uri>",
            "</mesh>",
        ]
    else:  # pragma: no cover - the model has no other geometry
        return []
    return ["<geometry>", *(f"  {line}" for line in inner), "</geometry>"]


def material(given: Material) -> list[str]:
    """urdfdom's colour (single precision; black if none) as Gazebo's diffuse and ambient."""
    rgba = given.color or (0.0, 0.0, 0.0, 1.0)
    r, g, b, a = (single(v) for v in rgba)
    diffuse = [min(max(c / 0.8, 0.0), 1.0) for c in (r, g, b)]
    ambient = [min(max(0.5 * c / 0.4, 0.0), 1.0) for c in (r, g, b)]
    return [
        "<material>",
        f"  <diffuse>{numbers((*diffuse, a))}</diffuse>",
        f"  <ambient>{numbers((*ambient, a))}</ambient>",
        "</material>",
    ]


def single(value: float) -> float:
    """``value`` as a C float holds it (beyond its range, an infinity)."""
    try:
        held: float = struct.unpack("f", struct.pack("f", value))[0]
    except OverflowError:
        return math.copysign(math.inf, value)
    return held


def number(value: float) -> str:
    """A number as the converter prints it: C++'s 16 significant digits, a zero as 0."""
    return "0" if value == 0 else f"{value:.16g}"


def numbers(values: tuple[float, ...] | list[float]) -> str:
    """Numbers as the converter prints them, separated by spaces."""
    return " ".join(number(v) for v in values)


def pose(xyz: tuple[float, float, float], rpy: tuple[float, float, float]) -> str:
    """A pose's text: x y z (metres), roll pitch yaw (radians)."""
    return numbers((*xyz, *rpy))


def attr(value: str) -> str:
    """An attribute's value in single quotes, as sdformat writes one."""
    return "'" + escape(value, {"'": "&apos;"}) + "'"
