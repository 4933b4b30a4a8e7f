"""A differential drive plugin held to the robot: its wheel joints, separation and size."""

from __future__ import annotations

import math
from collections.abc import Iterator

from lxml import etree

from ...analysis import Analysis
from ...analysis.drive import ALONG, GZ, Dialect, dialect, unit, wheel_radius
from ...analysis.gazebo import Block, place, plugins, text, texts
from ...catalog.gazebo import DIFF_DRIVE_SIZE, DIFF_DRIVE_WHEELS
from ...diagnostics import Diagnostic, Kind, Subject
from ...location import passed_through
from ...model import Joint, JointType, Location
from ...spatial import Pose, dot, mat_vec

__all__ = ["drives"]

_TOLERANCE = 0.01  # relative: a value 1% off the robot's is wrong
_TURNING = (JointType.CONTINUOUS, JointType.REVOLUTE)
_EPS = 1e-9


def drives(analysis: Analysis, block: Block) -> Iterator[Diagnostic]:
    """Findings about each differential drive plugin of ``block``."""
    for plugin in plugins(block):
        names = dialect(plugin)
        if names is not None:
            yield from _drive(analysis, block, plugin, names)


def _drive(
    analysis: Analysis, block: Block, plugin: etree._Element, names: Dialect
) -> Iterator[Diagnostic]:
    where = place(analysis.references, block, plugin)
    label = f"plugin {plugin.get('name') or ''!r} ({plugin.get('filename')})"
    lefts, rights = texts(plugin, names.left), texts(plugin, names.right)
    separations = [_float(t) for t in texts(plugin, names.separation)]
    sizes = [_float(t) for t in texts(plugin, names.size)]
    base = _base(analysis, plugin)
    for index, (left, right) in enumerate(zip(lefts, rights, strict=False)):
        pair = _pair(analysis, left, right, base)
        if isinstance(pair, list):
            for message, subject in pair:
                named = names.left if subject.name != right or left == right else names.right
                yield DIFF_DRIVE_WHEELS.report(
                    f"{label}: {message}",
                    _at(block, plugin, named, index) or where,
                    path=analysis.path,
                    subject=subject,
                    hint="name the wheels' continuous joints, turning about the axle, left as "
                    f"the wheel on +y{passed_through(_at(block, plugin, named, index))}",
                )
            continue
        if pair is None:
            continue
        apart, radius, wheel = pair
        one = names is GZ  # the new Gazebo's system has one separation and radius for all
        at = 0 if one else index
        given = separations[at] if at < len(separations) else names.default_separation
        written = at < len(separations)
        if given is not None and not _near(given, apart):
            yield _size(
                analysis,
                f"{label}: <{names.separation}> {_is(given, written)}, but joints {left!r} and "
                f"{right!r} are {apart:.4g} m apart along the axle",
                _at(block, plugin, names.separation, at) or where,
                f"write <{names.separation}>{apart:.4g}</{names.separation}>",
            )
        size = sizes[at] if at < len(sizes) else names.default_size
        written = at < len(sizes)
        if radius is None or size is None:
            continue
        want = radius if names.radius else 2 * radius
        if _near(size, want):
            continue
        if _near(size, radius if not names.radius else 2 * radius) and written:
            other = "diameter" if names.radius else "radius"
            message = (
                f"{label}: <{names.size}> is {size:.4g} m, the {other} of wheel {wheel!r}'s "
                f"collision cylinder (radius {radius:.4g} m)"
            )
        else:
            message = (
                f"{label}: <{names.size}> {_is(size, written)}, but wheel {wheel!r}'s "
                f"collision cylinder has radius {radius:.4g} m"
            )
        yield _size(
            analysis,
            message,
            _at(block, plugin, names.size, at) or where,
            f"write <{names.size}>{want:.4g}</{names.size}>",
        )


def _at(block: Block, plugin: etree._Element, tag: str, index: int) -> Location | None:
    """Where the ``index``-th ``<tag>`` of ``plugin`` is written, if it is and the reader
    said."""
    found = plugin.findall(tag)
    return block.place_of(found[index]) if index < len(found) else None


def _size(analysis: Analysis, message: str, where: Location | None, hint: str) -> Diagnostic:
    return DIFF_DRIVE_SIZE.report(
        message,
        where,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, analysis.robot.name),
        hint=hint + passed_through(where),
    )


def _is(value: float, written: bool) -> str:
    return f"is {value:.4g} m" if written else f"is not written (the default is {value:.4g} m)"


def _near(value: float, want: float) -> bool:
    return abs(value - want) <= _TOLERANCE * abs(want) + 1e-6


def _float(value: str) -> float | None:
    try:
        number_ = float(value)
    except ValueError:
        return None
    return number_ if math.isfinite(number_) else None


def _base(analysis: Analysis, plugin: etree._Element) -> Pose | None:
    """The pose of the plugin's base frame (its robot base frame, else the root link)."""
    poses = analysis.zero_poses
    for tag in ("robot_base_frame", "robotBaseFrame", "frame_id"):
        name = text(plugin, tag)
        if name is not None and name.lstrip("/") in poses:
            return poses[name.lstrip("/")]
    return Pose() if poses else None


_Pair = tuple[float, float | None, str]


def _pair(
    analysis: Analysis, left: str, right: str, base: Pose | None
) -> _Pair | list[tuple[str, Subject]] | None:
    """The wheels' distance along the axle, their radius and the link measured, or what is
    wrong with them (their faults), or None when they cannot be judged."""
    joints = [analysis.joints.get(left), analysis.joints.get(right)]
    faults: list[tuple[str, Subject]] = []
    for joint in joints:
        if joint is not None and joint.type not in _TURNING:
            faults.append(
                (
                    f"wheel joint {joint.name!r} is a {joint.type.value} joint, which does not "
                    "turn",
                    Subject(Kind.JOINT, joint.name),
                )
            )
    if faults:
        return faults
    left_joint, right_joint = joints
    poses = analysis.zero_poses
    if left_joint is None or right_joint is None or base is None:
        return None  # an unknown name is unknown-reference's
    if left_joint.child not in poses or right_joint.child not in poses:
        return None
    back = base.inverse()
    left_pose = back.then(poses[left_joint.child])
    right_pose = back.then(poses[right_joint.child])
    (lx, ly, lz), (rx, ry, rz) = left_pose.translation, right_pose.translation
    between = (lx - rx, ly - ry, lz - rz)
    length = math.sqrt(dot(between, between))
    if length < _EPS:
        return None
    for joint, pose in ((left_joint, left_pose), (right_joint, right_pose)):
        axis = unit(mat_vec(pose.rotation, joint.axis))
        if axis is None or abs(dot(axis, between)) / length < ALONG:
            faults.append(
                (
                    f"wheel joint {joint.name!r} turns about {_vector(axis)} in the base frame, "
                    "not about the axle between the wheels",
                    Subject(Kind.JOINT, joint.name),
                )
            )
    if between[1] < -_EPS:
        faults.append(
            (
                f"left wheel joint {left!r} is on the robot's right (y {ly:.4g} m in the base "
                f"frame) and right wheel joint {right!r} on its left (y {ry:.4g} m): left and "
                "right are swapped, so the robot turns the other way from what it is told, "
                "and so does its odometry",
                Subject(Kind.JOINT, left),
            )
        )
    if faults:
        return faults
    radius, wheel = _radius(analysis, left_joint)
    other, _ = _radius(analysis, right_joint)
    if radius is not None and other is not None and not _near(other, radius):
        radius = None  # wheels of two sizes: no one size is right
    return length, radius, wheel


def _radius(analysis: Analysis, joint: Joint) -> tuple[float | None, str]:
    """The radius of the wheel ``joint``'s child rolls on, if any, and the child's name."""
    return wheel_radius(analysis.links.get(joint.child), joint.axis), joint.child


def _vector(vector: tuple[float, float, float] | None) -> str:
    return "nothing" if vector is None else " ".join(f"{v:.3g}" for v in vector)
