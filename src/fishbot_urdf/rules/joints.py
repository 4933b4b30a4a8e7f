"""Rules about how joints move: axes, limits in the wrong units, angles in degrees, mimics."""

from __future__ import annotations

import math
from collections.abc import Iterator

from .. import catalog
from ..analysis import Analysis
from ..catalog import Rule, rules_in
from ..catalog.joints import (
    AXIS_LENGTH,
    LIMIT_UNSET,
    MIMIC_CHAIN,
    MIMIC_FIXED,
    RPY_DEGREES,
    VELOCITY_DEGREES,
    WHEEL_AXIS,
    WIDE_LIMIT,
    ZERO_LIMIT,
)
from ..diagnostics import Diagnostic, Kind, Severity, Subject
from ..model import Cylinder, Joint, JointType, Limit, Link, Mimic, Origin, Vector3

__all__ = ["REPORTS", "joints"]

_TURN = 2 * math.pi
_SLACK = 1e-3  # rounding in written angles (6.2832 for 2 pi)
_TURNED = _TURN + _SLACK  # an angle beyond this is more than a whole turn
_ROUNDING = 1e-4  # a suggested axis's component this near -1, 0 or 1 is written as that
_LEANS = 0.05  # a joint axis whose cosine with a wheel's is below this gives it no sense


_MOVING = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)


def joints(analysis: Analysis) -> Iterator[Diagnostic]:
    """Every finding about how the robot's joints move, and angles written in degrees."""
    for joint in analysis.robot.joints:
        yield from _joint(analysis, joint)
    for link in analysis.robot.links:
        inertial = link.inertial
        if (
            (inertial is None or not _beyond_a_turn(inertial.origin.rpy))
            and not any(_beyond_a_turn(visual.origin.rpy) for visual in link.visuals)
            and not any(_beyond_a_turn(collision.origin.rpy) for collision in link.collisions)
        ):
            continue  # (nearly always)
        for part, origin in _origins(link):
            if _beyond_a_turn(origin.rpy):
                yield _rpy(
                    analysis, f"link {link.name!r}: {part}", origin, Subject(Kind.LINK, link.name)
                )


def _joint(analysis: Analysis, joint: Joint) -> Iterator[Diagnostic]:
    path = analysis.path
    if _beyond_a_turn(joint.origin.rpy):
        yield _rpy(analysis, _named(joint), joint.origin, _subject(joint))
    if joint.mimic is not None:
        yield from _mimic_fixed(analysis, joint, joint.mimic)
    if joint.type not in _MOVING and joint.type is not JointType.PLANAR:
        return
    x, y, z = joint.axis
    length = math.sqrt(x * x + y * y + z * z)
    if length > 0 and abs(length - 1.0) > _SLACK:
        unit = _vector(_clean((x / length, y / length, z / length)), ".4g")
        yield AXIS_LENGTH.report(
            f"{_named(joint)}: axis {_vector(joint.axis)} has length {length:.4g}",
            joint.source,
            path=path,
            subject=_subject(joint),
            hint=f'write the unit vector: <axis xyz="{unit}"/>',
        )
    if joint.type is JointType.CONTINUOUS and length > 0:
        yield from _wheel(analysis, joint, length)
    if joint.mimic is not None:
        yield from _mimic(analysis, joint)
    limit = joint.limit
    if limit is None or joint.type not in _MOVING:
        return
    where = limit.source or joint.source
    if limit.unset and joint.type.needs_limit:
        yield _unset(analysis, joint, limit)
    if joint.type is JointType.REVOLUTE:
        wide = [
            (n, v)
            for n, v in (("lower", limit.lower), ("upper", limit.upper))
            if abs(v) > 2 * _TURN + _SLACK
        ]
        if wide:
            said = " and ".join(f"{n} limit {v:g}" for n, v in wide)
            first = wide[0][1]
            degrees = (
                f"if {first:g} is degrees, it is {math.radians(first):.4g} rad; "
                if abs(first) <= 720
                else ""
            )
            yield WIDE_LIMIT.report(
                f"{_named(joint)}: {said} {'are' if len(wide) > 1 else 'is'} more than two "
                "whole turns",
                where,
                path=path,
                subject=_subject(joint),
                hint=f"limits are in radians: {degrees}a joint that turns without end is "
                "continuous",
            )
        velocity = limit.velocity
        if velocity >= 45 and velocity % 15 == 0:
            yield VELOCITY_DEGREES.report(
                f"{_named(joint)}: velocity limit {velocity:g} reads as degrees per second",
                where,
                path=path,
                subject=_subject(joint),
                hint=f"velocity limits are in rad/s ({velocity:g} deg/s is "
                f"{math.radians(velocity):.4g} rad/s)",
            )
    if joint.mimic is None and (limit.effort == 0 or limit.velocity == 0):
        zero = [n for n, v in (("effort", limit.effort), ("velocity", limit.velocity)) if v == 0]
        what = {
            "effort": "no motor may drive it",
            "velocity": "it may not move",
        }
        said = " and ".join(zero) + (" limits are" if len(zero) > 1 else " limit is")
        yield ZERO_LIMIT.report(
            f"{_named(joint)}: {said} 0: {' and '.join(what[z] for z in zero)}",
            where,
            path=path,
            subject=_subject(joint),
            hint="give the motor's real limits, or make the joint fixed",
        )


def _unset(analysis: Analysis, joint: Joint, limit: Limit) -> Diagnostic:
    """A revolute or prismatic joint whose <limit> leaves out a bound (read as 0)."""
    said = f"<limit> has no {' and no '.join(limit.unset)}"
    severity = None
    if limit.lower > limit.upper:
        # The one bound written is on the wrong side of 0: limit-range's fault too, said
        # here once, as the error it is there.
        what = (
            f"{said}, read as 0, which leaves lower {limit.lower:g} above upper "
            f"{limit.upper:g}: Drake refuses the joint, MuJoCo and PyBullet leave it free"
        )
        severity = Severity.ERROR
    elif len(limit.unset) == 2:
        what = (
            f"{said}, so urdfdom reads both as 0 and holds the joint at 0 (robot_state_publisher, "
            "MoveIt, Gazebo, pinocchio), while MuJoCo and PyBullet leave it free"
        )
    else:
        what = (
            f"{said}, so urdfdom reads it as 0 and limits the joint to {limit.lower:g} .. "
            f"{limit.upper:g}, while MuJoCo leaves it free"
        )
    hint = 'write both bounds: <limit lower=".." upper=".." effort=".." velocity=".."/>'
    if joint.type is JointType.REVOLUTE:
        hint = f"a joint that turns without end (a wheel) is continuous; else {hint}"
    return LIMIT_UNSET.report(
        f"{_named(joint)}: {what}",
        limit.source or joint.source,
        path=analysis.path,
        subject=_subject(joint),
        hint=hint,
        severity=severity,
    )


def _named(joint: Joint) -> str:
    return f"joint {joint.name!r}"


def _subject(joint: Joint) -> Subject:
    return Subject(Kind.JOINT, joint.name)


def _mimic(analysis: Analysis, joint: Joint) -> Iterator[Diagnostic]:
    mimic = joint.mimic
    if mimic is None:
        return
    path, named, subject = analysis.path, _named(joint), _subject(joint)
    target = analysis.joints.get(mimic.joint)
    if mimic.multiplier == 0:
        yield MIMIC_CHAIN.report(
            f"{named} mimics {mimic.joint!r} with multiplier 0: it never moves",
            mimic.source or joint.source,
            path=path,
            subject=subject,
            hint="make it a fixed joint, or give the multiplier its real value",
        )
    # A chain through a fixed joint ends there (mimic-fixed says so).
    if (
        target is not None
        and target.mimic is not None
        and target is not joint
        and target.type is not JointType.FIXED
    ):
        first = target.mimic.joint
        yield MIMIC_CHAIN.report(
            f"{named} mimics {mimic.joint!r}, which mimics {first!r} in turn",
            mimic.source or joint.source,
            path=path,
            subject=subject,
            hint=f"mimic {first!r} directly, with the multipliers and offsets combined",
        )


def _mimic_fixed(analysis: Analysis, joint: Joint, mimic: Mimic) -> Iterator[Diagnostic]:
    """A fixed joint with a mimic, or a joint that mimics a fixed joint."""
    leader = analysis.joints.get(mimic.joint)
    if joint.type is JointType.FIXED:
        message = f"{_named(joint)} is fixed, but mimics {mimic.joint!r}: it never moves"
        hint = "delete its <mimic>, or give it the type of a joint that moves"
    elif leader is not None and leader.type is JointType.FIXED and leader is not joint:
        message = (
            f"{_named(joint)} mimics {mimic.joint!r}, a fixed joint, which has no position: "
            f"it stays at its offset {mimic.offset:g}"
        )
        hint = f"mimic the joint that drives it, or make {joint.name!r} fixed"
    else:
        return
    yield MIMIC_FIXED.report(
        message,
        mimic.source or joint.source,
        path=analysis.path,
        subject=_subject(joint),
        hint=hint,
    )


def _wheel(analysis: Analysis, joint: Joint, length: float) -> Iterator[Diagnostic]:
    """A continuous joint whose child collides as one flat cylinder: a wheel."""
    child = analysis.links.get(joint.child)
    if child is None or len(child.collisions) != 1:
        return
    collision = child.collisions[0]
    shape = collision.geometry
    if not isinstance(shape, Cylinder) or not 0 < shape.length <= 2 * shape.radius:
        return
    along = _z_of(collision.origin)
    cosine = abs(sum(a * b for a, b in zip(along, joint.axis, strict=True))) / length
    if cosine >= math.cos(math.radians(10)):
        return
    along = _clean(along)
    # A cylinder has no sense along its axis: the axis keeps the sense the joint's leans
    # to, else the positive one (0 1 0 for a wheel turned by rpy="1.5708 0 0", as written
    # in ROS's differential-drive robots); the other sense turns the wheel the other way.
    lean = sum(a * b for a, b in zip(along, joint.axis, strict=True)) / length
    sense = lean if abs(lean) >= _LEANS else max(along, key=abs)
    fit = along if sense > 0 else _clean((-along[0], -along[1], -along[2]))
    other = _clean((-fit[0], -fit[1], -fit[2]))
    yield WHEEL_AXIS.report(
        f"joint {joint.name!r} turns about {_vector(joint.axis)}, but its wheel "
        f"{child.name!r} is a cylinder along {_vector(along, '.4g')}",
        joint.source,
        path=analysis.path,
        subject=_subject(joint),
        hint=f'a wheel turns about its cylinder\'s axis: <axis xyz="{_vector(fit, ".4g")}"/> '
        f"({_vector(other, '.4g')} turns it the other way)",
    )


def _clean(axis: Vector3) -> Vector3:
    """An axis to suggest, each component within :data:`_ROUNDING` of -1, 0 or 1 written as
    that (an angle of 1.57079 for pi/2 leaves cos = 6.3e-06 in a rotated axis)."""
    x, y, z = (float(round(v)) + 0.0 if abs(v - round(v)) <= _ROUNDING else v for v in axis)
    return (x, y, z)


def _z_of(origin: Origin) -> Vector3:
    """The z axis of ``origin``'s frame, in its parent's (the third column of R(rpy))."""
    roll, pitch, yaw = origin.rpy
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (cy * sp * cr + sy * sr, sy * sp * cr - cy * sr, cp * cr)


def _origins(link: Link) -> Iterator[tuple[str, Origin]]:
    if link.inertial is not None:
        yield "<inertial>", link.inertial.origin
    for visual in link.visuals:
        yield "<visual>", visual.origin
    for collision in link.collisions:
        yield "<collision>", collision.origin


def _beyond_a_turn(rpy: Vector3) -> bool:
    """Whether an angle of ``rpy`` is more than a whole turn (and finite)."""
    roll, pitch, yaw = rpy
    if -_TURNED < roll < _TURNED and -_TURNED < pitch < _TURNED and -_TURNED < yaw < _TURNED:
        return False  # (nearly always: one test of each angle)
    return any(abs(v) > _TURNED and math.isfinite(v) for v in rpy)


def _rpy(analysis: Analysis, named: str, origin: Origin, subject: Subject) -> Diagnostic:
    radians = " ".join(f"{math.radians(v):.4g}" for v in origin.rpy)
    return RPY_DEGREES.report(
        f"{named}: rpy {_vector(origin.rpy)} holds an angle beyond a whole turn",
        origin.source,
        path=analysis.path,
        subject=subject,
        hint=f'angles are in radians; if these are degrees, write rpy="{radians}"',
    )


def _vector(values: Vector3, spec: str = "g") -> str:
    return " ".join(format(v, spec) for v in values)


REPORTS: tuple[Rule, ...] = rules_in(catalog.joints)
"""Every rule this module's check may report: the check runs only when one is selected."""
