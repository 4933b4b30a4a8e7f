"""Rules about how joints move: axes, limits in the wrong units, angles in degrees, mimics."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ..analysis import Analysis
from ..diagnostics import Diagnostic, Kind, Severity, Subject, subject
from ..model import Cylinder, Joint, JointType, Link, Mimic, Origin, Vector3
from . import Consumer, Family, Rule

__all__ = ["REPORTS", "joints"]

W = Severity.WARNING
_ALL = (Consumer.URDFDOM, Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
_TURN = 2 * math.pi
_SLACK = 1e-3  # rounding in written angles (6.2832 for 2 pi)
_TURNED = _TURN + _SLACK  # an angle beyond this is more than a whole turn

_WHEEL = """\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="wheel_link">
    <collision><origin rpy="1.5708 0 0"/>
      <geometry><cylinder radius="0.03" length="0.02"/></geometry>
    </collision>
    <inertial><mass value="0.1"/>
      <inertia ixx="2.583e-5" iyy="4.5e-5" izz="2.583e-5" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_link"/><axis xyz="{axis}"/>
  </joint>
</robot>
"""
_ARM = """\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="arm_link"/>
  <joint name="arm_joint" type="{type}">
    <origin xyz="0 0 0.1" rpy="{rpy}"/>
    <parent link="base_link"/><child link="arm_link"/><axis xyz="{axis}"/>
    <limit lower="{lower}" upper="{upper}" effort="{effort}" velocity="{velocity}"/>
  </joint>
</robot>
"""
_GOOD_ARM = {
    "type": "revolute",
    "rpy": "0 0 1.5708",
    "axis": "0 0 1",
    "lower": "-1.5708",
    "upper": "1.5708",
    "effort": "10",
    "velocity": "3.14",
}


def _arm(**changes: str) -> str:
    return _ARM.format(**{**_GOOD_ARM, **changes})


WHEEL_AXIS = Rule(
    "wheel-axis",
    W,
    Family.JOINTS,
    summary="A wheel's continuous joint turns about another axis than its cylinder's.",
    explanation="A continuous joint whose child collides as one flat cylinder is a wheel, and a "
    "wheel turns about its cylinder's axis. A cylinder lies along its own z axis, so a wheel "
    'turned on its side with `rpy="1.5708 0 0"` rolls about y; with the joint\'s axis left at '
    "`0 0 1` it spins like a turntable and the robot does not drive. Set the joint's `<axis>` to "
    "the cylinder's axis in the wheel link's frame.",
    bad=_WHEEL.format(axis="0 0 1"),
    good=_WHEEL.format(axis="0 1 0"),
    consumers=(Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET),
)
AXIS_LENGTH = Rule(
    "axis-length",
    W,
    Family.JOINTS,
    summary="A moving joint's axis is not of length 1.",
    explanation="URDF expects a unit axis. urdfdom and KDL keep what is written, and what each "
    "program does with a longer or shorter axis differs: some normalise it, some scale the "
    "joint's motion or its Jacobian by its length. Write the unit vector (`0 1 0`, or "
    "`0 0.7071 0.7071` for a diagonal).",
    bad=_arm(axis="0 0 2"),
    good=_arm(),
    consumers=_ALL,
)
WIDE_LIMIT = Rule(
    "wide-limit",
    W,
    Family.JOINTS,
    summary="A revolute joint's limits reach past two whole turns (4 pi), as degrees would.",
    explanation="Joint limits are in radians. A lower or upper limit beyond +-12.566 is more "
    "than two full turns each way, which means degrees were written (90 for 1.5708), or a "
    "large number stands for 'no limit'. Real joints that turn a little more than once (a "
    "wrist's +-400 degrees) stay below it. A joint that turns without end is `continuous`; "
    "otherwise convert the limits to radians.",
    bad=_arm(lower="-90", upper="90"),
    good=_arm(),
    consumers=_ALL,
)
VELOCITY_DEGREES = Rule(
    "velocity-degrees",
    W,
    Family.JOINTS,
    summary="A revolute joint's velocity limit reads as degrees per second.",
    explanation="Velocity limits are in radians per second. A revolute joint limited to a round "
    "number of degrees per second (45, 90, 180, 360: a multiple of 15 from 45 up) is beyond "
    "what robot joints do (fast legged-robot motors reach about 30 rad/s), so planners and "
    "controllers take the joint as many times faster than it is. Divide by 57.3 (180 deg/s is "
    "3.1416 rad/s).",
    bad=_arm(velocity="180"),
    good=_arm(),
    consumers=_ALL,
)
ZERO_LIMIT = Rule(
    "zero-limit",
    W,
    Family.JOINTS,
    summary="A moving joint's effort or velocity limit is 0.",
    explanation='A `<limit>` with `effort="0"` or `velocity="0"` says the joint may not push '
    "or may not move: Gazebo and ros2_control clamp every command to nothing, and MoveIt cannot "
    "plan for it. It usually comes from copying a fixed joint's template. Give the motor's real "
    "limits.",
    bad=_arm(effort="0"),
    good=_arm(),
    consumers=_ALL,
)
RPY_DEGREES = Rule(
    "rpy-degrees",
    W,
    Family.JOINTS,
    summary="An <origin>'s rpy holds an angle beyond a whole turn (2 pi), as degrees would.",
    explanation="Roll, pitch and yaw are in radians. An angle beyond +-6.2832 is more than a "
    "whole turn, which almost always means degrees were written (90 for a quarter turn, which "
    "is 1.5708). Write radians; xacro's `${radians(90)}` or `${pi/2}` help.",
    bad=_arm(rpy="0 0 90"),
    good=_arm(),
    consumers=_ALL,
)
MIMIC_CHAIN = Rule(
    "mimic-chain",
    W,
    Family.JOINTS,
    summary="A joint mimics a joint that mimics another, or mimics with a multiplier of 0.",
    explanation="robot_state_publisher and MoveIt follow one step of mimicry: a joint that "
    "mimics a mimic joint is moved by the first joint's value in some programs and the second's "
    "in others. A multiplier of 0 holds the joint still at its offset, which a fixed joint says "
    "plainly. Point every mimic at the joint that is really driven, with a non-zero multiplier.",
    bad="""\
<robot name="gripper">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="continuous">
    <parent link="palm"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous">
    <parent link="palm"/><child link="right"/><mimic joint="left_joint" multiplier="0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="gripper">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="continuous">
    <parent link="palm"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous">
    <parent link="palm"/><child link="right"/><mimic joint="left_joint" multiplier="-1"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)

MIMIC_FIXED = Rule(
    "mimic-fixed",
    W,
    Family.JOINTS,
    summary="A fixed joint has a <mimic>, or a joint mimics a fixed joint.",
    explanation="A fixed joint never moves: a `<mimic>` on it moves nothing, and a joint that "
    "mimics it follows a joint that has no position. check_urdf accepts both, and "
    "robot_state_publisher publishes a fixed joint once, as a static transform, whatever it "
    "mimics. A joint that mimics a fixed joint is where programs part: joint_state_publisher "
    "leaves fixed joints out and fails with a KeyError when it publishes the follower; "
    "pinocchio, asked to read mimics, refuses the file (the mimicked joint is not in its "
    "kinematic tree) and otherwise moves the joint on its own; fishbot's kinematics hold it at "
    "its offset. A robot reduced by turning joints fixed often keeps their mimics. Delete the "
    "`<mimic>` of a fixed joint; point a follower at the joint that really drives it, or make "
    "it fixed too.",
    bad="""\
<robot name="gripper">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="fixed">
    <parent link="palm"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous">
    <parent link="palm"/><child link="right"/><mimic joint="left_joint" multiplier="-1"/>
  </joint>
</robot>
""",
    good="""\
<robot name="gripper">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="continuous">
    <parent link="palm"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous">
    <parent link="palm"/><child link="right"/><mimic joint="left_joint" multiplier="-1"/>
  </joint>
</robot>
""",
    consumers=(Consumer.URDFDOM,),
)

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
        unit = " ".join(f"{v / length:.4g}" for v in joint.axis)
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


def _named(joint: Joint) -> str:
    return f"joint {joint.name!r}"


def _subject(joint: Joint) -> Subject:
    return subject(Kind.JOINT, joint.name)


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
    fit = " ".join(f"{0.0 if abs(v) < 1e-9 else v:.4g}" for v in along)
    yield WHEEL_AXIS.report(
        f"joint {joint.name!r} turns about {_vector(joint.axis)}, but its wheel "
        f"{child.name!r} is a cylinder along {fit}",
        joint.source,
        path=analysis.path,
        subject=_subject(joint),
        hint=f'a wheel turns about its cylinder\'s axis: <axis xyz="{fit}"/>',
    )


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


def _vector(values: Vector3) -> str:
    return " ".join(f"{v:g}" for v in values)


REPORTS: tuple[Rule, ...] = (
    AXIS_LENGTH,
    MIMIC_CHAIN,
    MIMIC_FIXED,
    RPY_DEGREES,
    VELOCITY_DEGREES,
    WHEEL_AXIS,
    WIDE_LIMIT,
    ZERO_LIMIT,
)
"""Every rule this module's check may report: the check runs only when one is selected."""
