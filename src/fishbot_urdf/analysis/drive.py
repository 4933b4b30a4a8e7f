"""The robot's differential drive, read once: the two wheel joints a drive plugin turns, and
what the plugin is told of them, for the checks, the converters and the simulation.

A robot with no drive plugin may still be one: two continuous joints, on either side of
the robot, whose links roll on collision cylinders about their axes, are taken as its
wheels (`wheels`), as a learner's robot before its Gazebo step is.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field

from lxml import etree

from ..model import Cylinder, Joint, JointType, Link, Mesh, Sphere, Vector3
from ..spatial import Pose, dot, mat_vec, rpy_matrix, scale, transpose
from .gazebo import Block, number, plugins, text, texts

__all__ = [
    "ALONG",
    "CLASSIC",
    "GZ",
    "ROS1",
    "Dialect",
    "Drive",
    "dialect",
    "drives",
    "rolling_radius",
    "unit",
    "wheel_radius",
    "wheels",
]

ALONG = 0.99
"""The cosine above which two directions are taken as one."""
_EPS = 1e-9


@dataclass(frozen=True, slots=True)
class Dialect:
    """What one family of drive plugins calls its parameters, and the defaults it takes for
    those left out (metres, N*m).

    Attributes:
        left: The left wheel joint's tag.
        right: The right wheel joint's tag.
        separation: The distance between the wheels' tag.
        size: The wheel's diameter's or radius's tag.
        radius: Whether ``size`` is a radius.
        torque: The greatest wheel torque's tag ("" when the plugin has none).
        default_separation: ``separation`` when not written.
        default_size: ``size`` when not written.
        default_torque: The torque when not written (None: unlimited).
    """

    left: str
    right: str
    separation: str
    size: str
    radius: bool
    torque: str
    default_separation: float
    default_size: float
    default_torque: float | None


# gazebo_ros_diff_drive.cpp (ROS 2 and ROS 1 branches of gazebo_ros_pkgs) and gz-sim's
# DiffDrive system, with the defaults each uses for a tag left out.
CLASSIC = Dialect(
    "left_joint", "right_joint", "wheel_separation", "wheel_diameter", False,
    "max_wheel_torque", 0.34, 0.15, 5.0,
)  # fmt: skip
ROS1 = Dialect(
    "leftJoint", "rightJoint", "wheelSeparation", "wheelDiameter", False,
    "wheelTorque", 0.34, 0.15, 5.0,
)  # fmt: skip
GZ = Dialect(
    "left_joint", "right_joint", "wheel_separation", "wheel_radius", True, "", 1.0, 0.2, None
)


def dialect(plugin: etree._Element) -> Dialect | None:
    """The family of drive plugins ``plugin`` belongs to; None for another plugin."""
    filename = plugin.get("filename") or ""
    if "gazebo_ros_diff_drive" in filename:
        return ROS1 if plugin.find("leftJoint") is not None else CLASSIC
    if "diff-drive-system" in filename or "DiffDrive" in (plugin.get("name") or ""):
        return GZ
    return None


@dataclass(frozen=True, slots=True)
class Drive:
    """A pair of wheels driven as a differential drive.

    Attributes:
        left: The left wheel's joint (as written; it may name no joint).
        right: The right wheel's joint.
        separation: The distance between the wheels the plugin is told, or takes by default
            (metres); None when no plugin drives them or the value is no number.
        radius: The wheel radius the plugin is told, or takes (metres); None likewise.
        torque: The greatest torque the plugin puts on a wheel (N*m); None when unlimited
            or not known.
        plugin: The plugin's element; None for wheels found from the joints.
        block: The ``<gazebo>`` block holding the plugin.
        dialect: The plugin's family.
    """

    left: str
    right: str
    separation: float | None
    radius: float | None
    torque: float | None
    plugin: etree._Element | None = field(default=None, repr=False)
    block: Block | None = field(default=None, repr=False)
    dialect: Dialect | None = field(default=None, repr=False)


def drives(blocks: tuple[Block, ...]) -> tuple[Drive, ...]:
    """Every wheel pair a differential drive plugin of ``blocks`` turns, in file order."""
    found: list[Drive] = []
    for block in blocks:
        for plugin in plugins(block):
            family = dialect(plugin)
            if family is not None:
                found.extend(_pairs(block, plugin, family))
    return tuple(found)


def _pairs(block: Block, plugin: etree._Element, family: Dialect) -> Iterator[Drive]:
    lefts, rights = texts(plugin, family.left), texts(plugin, family.right)
    separations = [_float(t) for t in texts(plugin, family.separation)]
    sizes = [_float(t) for t in texts(plugin, family.size)]
    torque = number(plugin, family.torque) if family.torque else None
    if torque is None and (not family.torque or text(plugin, family.torque) is None):
        torque = family.default_torque
    for index, (left, right) in enumerate(zip(lefts, rights, strict=False)):
        at = 0 if family is GZ else index  # gz-sim's system: one size for every pair
        separation = separations[at] if at < len(separations) else family.default_separation
        size = sizes[at] if at < len(sizes) else family.default_size
        radius = size if family.radius or size is None else size / 2.0
        yield Drive(left, right, separation, radius, torque, plugin, block, family)


def wheel_radius(link: Link | None, axis: tuple[float, float, float]) -> float | None:
    """The radius of ``link``'s largest collision cylinder turning about ``axis`` (in the
    link's frame), if any: the wheel it rolls on."""
    if link is None:
        return None
    along_axis = unit(axis)
    if along_axis is None:
        return None
    found: float | None = None
    for collision in link.collisions:
        shape = collision.geometry
        if not isinstance(shape, Cylinder) or shape.radius <= 0:
            continue
        along = mat_vec(rpy_matrix(collision.origin.rpy), (0.0, 0.0, 1.0))
        if abs(dot(along, along_axis)) >= ALONG and (found is None or shape.radius > found):
            found = shape.radius
    return found


def rolling_radius(
    link: Link | None,
    axis: tuple[float, float, float],
    bounds: Callable[[Mesh], tuple[Vector3, Vector3] | None] | None = None,
) -> float | None:
    """The radius ``link`` rolls on about ``axis`` (in its frame): its largest collision
    cylinder turning about the axis (`wheel_radius`); else its largest ball; else its
    largest collision mesh whose box, given by ``bounds`` (in the mesh's frame, unscaled),
    is as wide as it is high across the axis (within 5%), turning about its middle."""
    found = wheel_radius(link, axis)
    if found is not None or link is None:
        return found
    along = unit(axis)
    if along is None:
        return None
    balls = [c.geometry.radius for c in link.collisions if isinstance(c.geometry, Sphere)]
    if balls:
        return max(balls)
    for collision in link.collisions:
        shape = collision.geometry
        box = bounds(shape) if bounds is not None and isinstance(shape, Mesh) else None
        if box is None or not isinstance(shape, Mesh):
            continue
        scaled = shape.scale or (1.0, 1.0, 1.0)
        low, high = box
        size = [abs(h - lo) * s for lo, h, s in zip(low, high, scaled, strict=True)]
        middle = [(lo + h) / 2 * s for lo, h, s in zip(low, high, scaled, strict=True)]
        local = mat_vec(transpose(rpy_matrix(collision.origin.rpy)), along)
        turning = max(range(3), key=lambda k: abs(local[k]))
        if abs(local[turning]) < ALONG:
            continue
        across = [k for k in range(3) if k != turning]
        wide, high_ = size[across[0]], size[across[1]]
        centred = all(abs(middle[k] + collision.origin.xyz[k]) < 0.05 * wide for k in across)
        if wide > 0 and abs(wide - high_) <= 0.05 * max(wide, high_) and centred:
            radius = max(wide, high_) / 2.0
            found = radius if found is None else max(found, radius)
    return found


def wheels(
    joints: Mapping[str, Joint],
    links: Mapping[str, Link],
    poses: Mapping[str, Pose],
    bounds: Callable[[Mesh], tuple[Vector3, Vector3] | None] | None = None,
) -> Drive | None:
    """The wheel pair of a robot with no drive plugin: two continuous joints whose links roll
    (`rolling_radius`) on one radius about their axes, on either side of the root (left:
    +y), with axes along the line between them; None when no pair is that plain.

    ``poses`` are the links' poses in the root's frame (every joint at zero); ``bounds``
    gives a collision mesh's box, for wheels that roll on meshes."""
    rolling: list[tuple[Joint, float]] = []
    for joint in joints.values():
        if joint.type is not JointType.CONTINUOUS or joint.child not in poses:
            continue
        radius = rolling_radius(links.get(joint.child), joint.axis, bounds)
        if radius is not None:
            rolling.append((joint, radius))
    pairs = []
    for index, (one, r1) in enumerate(rolling):
        for other, r2 in rolling[index + 1 :]:
            if abs(r1 - r2) > 1e-6 * max(r1, r2):
                continue
            p1, p2 = poses[one.child], poses[other.child]
            (x1, y1, z1), (x2, y2, z2) = p1.translation, p2.translation
            between = (x1 - x2, y1 - y2, z1 - z2)
            length = math.sqrt(dot(between, between))
            if length < _EPS or abs(between[1]) / length < ALONG:
                continue
            across = [unit(mat_vec(p.rotation, j.axis)) for p, j in ((p1, one), (p2, other))]
            if any(a is None or abs(a[1]) < ALONG for a in across):
                continue
            left, right = (one, other) if between[1] > 0 else (other, one)
            pairs.append(Drive(left.name, right.name, length, r1, None))
    return pairs[0] if len(pairs) == 1 else None


def unit(vector: tuple[float, float, float]) -> tuple[float, float, float] | None:
    """``vector`` scaled to length 1; None for a vector of about no length."""
    length = math.sqrt(dot(vector, vector))
    return scale(vector, 1 / length) if length > _EPS else None


def _float(value: str) -> float | None:
    try:
        found = float(value)
    except ValueError:
        return None
    return found if math.isfinite(found) else None
