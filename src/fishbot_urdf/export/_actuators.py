"""The motors of an MJCF model, from the robot's own description: the wheels its differential
drive plugin turns, and the command interfaces of its ``<ros2_control>`` joints.

Gazebo's drive plugins hold each wheel at the speed asked for with at most their greatest
wheel torque; the model holds it so with a velocity servo whose force is limited to that
torque, as stiff as the time step allows: its gain is the inertia the wheel moves (its own
about the axle, and its share of the robot's mass at its radius) over half a time step
(`WHEEL_RESPONSE`). A stiffer one makes light wheels kick the robot off the floor. A
ros2_control joint commanded by velocity gets a velocity servo, one commanded by position a
critically damped position servo (both as stiff as `SERVO_RESPONSE` says, and limited to
its ``<limit effort>``), one commanded by effort a motor. Each actuator is named after its joint.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from typing import NamedTuple

from ..analysis import Analysis
from ..analysis.drive import Drive, unit, wheel_radius
from ..model import Joint, JointType
from ..spatial import Pose, cross, dot, mat_vec, rotate_tensor
from ._geoms import number, numbers

__all__ = ["SERVO_RESPONSE", "WHEEL_RESPONSE", "Motor", "actuator", "motors", "moved_inertia"]

WHEEL_RESPONSE = 0.001
"""How soon a wheel's servo answers (s): half of MuJoCo's default time step."""
SERVO_RESPONSE = 0.01
"""How soon a ros2_control joint's servo answers (s): a velocity servo's gain is the inertia
its joint moves over this, a position servo's that inertia times (2 pi / (10 x this))^2, so
that it swings at 10 Hz, critically damped. Stiffer, a servo whose force is limited rings
from one step to the next."""
UNLIMITED_GAIN = 1.0
"""The gain of a servo whose joint moves no inertia the robot gives."""

_ONE_NUMBER = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)


class Motor(NamedTuple):
    """What turns one joint.

    Attributes:
        joint: The joint's name (its MJCF joint's and actuator's).
        command: ``velocity``, ``position`` or ``effort``.
        force: The greatest force or torque it gives (None: unlimited).
        by: What the robot says drives it (``plugin 'diff_drive'``, ``<ros2_control>``).
        gain: The servo's gain, when not made from ``force``.
    """

    joint: str
    command: str
    force: float | None
    by: str
    gain: float | None = None


def motors(analysis: Analysis, drives: tuple[Drive, ...] | None = None) -> tuple[Motor, ...]:
    """The motors of ``analysis``'s robot, one per joint, in file order: the wheels of
    ``drives`` (by default its drive plugins' wheel pairs), then its ``<ros2_control>``
    joints' first command interface. Only joints that move along one number are driven."""
    if drives is None:
        drives = tuple(d for d in analysis.drives if d.plugin is not None)
    found: dict[str, Motor] = {}
    for motor in _wheels(analysis, drives):
        found.setdefault(motor.joint, motor)
    for reference in analysis.references:
        if reference.context != "<ros2_control> joint" or reference.name in found:
            continue
        joint = analysis.joints.get(reference.name)
        commands = [i.name for i in reference.interfaces if i.kind == "command"]
        command = next((c for c in commands if c in _COMMANDS), None)
        if joint is None or joint.type not in _ONE_NUMBER or command is None:
            continue
        moved = moved_inertia(analysis, joint)
        gain = None
        if moved > 0 and command == "velocity":
            gain = moved / SERVO_RESPONSE
        elif moved > 0 and command == "position":
            gain = moved * (2.0 * math.pi / (10.0 * SERVO_RESPONSE)) ** 2
        found[joint.name] = Motor(joint.name, command, _effort(joint), "<ros2_control>", gain)
    return tuple(found.values())


def _wheels(analysis: Analysis, drives: tuple[Drive, ...]) -> Iterator[Motor]:
    wheels = [
        analysis.joints[name]
        for drive in drives
        for name in (drive.left, drive.right)
        if name in analysis.joints and analysis.joints[name].type in _ONE_NUMBER
    ]
    mass = sum(link.inertial.mass for link in analysis.robot.links if link.inertial is not None)
    for drive in drives:
        by = "two wheel joints"
        if drive.plugin is not None:
            by = f"plugin {drive.plugin.get('name') or drive.plugin.get('filename')!r}"
        for name in (drive.left, drive.right):
            joint = analysis.joints.get(name)
            if joint is not None and joint.type in _ONE_NUMBER:
                force = drive.torque if drive.torque is not None else _effort(joint)
                link = analysis.links.get(joint.child)
                radius = wheel_radius(link, joint.axis) or drive.radius or 0.0
                moved = max(mass, 0.0) / len(wheels) * radius**2 + moved_inertia(analysis, joint)
                gain = moved / WHEEL_RESPONSE if moved > 0 else None
                yield Motor(name, "velocity", force, by, gain)


def moved_inertia(analysis: Analysis, joint: Joint) -> float:
    """The moment of inertia ``joint`` turns (kg*m^2; for a prismatic joint, the mass it
    moves, kg): every link below it, each inertial about the joint's axis, every joint at
    zero."""
    poses = analysis.zero_poses
    if joint.child not in poses or joint.parent not in poses:
        return 0.0
    frame = poses[joint.parent].then(Pose.of(joint.origin))
    axis = unit(mat_vec(frame.rotation, joint.axis))
    if axis is None:
        return 0.0
    total, below = 0.0, [joint.child]
    while below:
        name = below.pop()
        below.extend(j.child for j in analysis.topology.children.get(name, ()))
        link = analysis.links.get(name)
        if link is None or link.inertial is None or name not in poses:
            continue
        inertial = link.inertial
        if joint.type is JointType.PRISMATIC:
            total += inertial.mass
            continue
        place = poses[name].then(Pose.of(inertial.origin))
        tensor = rotate_tensor(place.rotation, inertial.inertia.matrix())
        (cx, cy, cz), (ox, oy, oz) = place.translation, frame.translation
        arm = (cx - ox, cy - oy, cz - oz)
        across = cross(arm, axis)
        total += dot(axis, mat_vec(tensor, axis)) + inertial.mass * dot(across, across)
    return max(total, 0.0)


def actuator(motor: Motor, joint: Joint) -> ET.Element:
    """The MJCF actuator of ``motor`` on ``joint``."""
    force = motor.force
    if motor.command == "effort":
        element = ET.Element("motor", name=motor.joint, joint=motor.joint)
        if force is not None:
            element.set("ctrlrange", numbers((-force, force)))
        return element
    if motor.command == "velocity":
        gain = motor.gain or UNLIMITED_GAIN
        element = ET.Element("velocity", name=motor.joint, joint=motor.joint, kv=number(gain))
        speed = joint.limit.velocity if joint.limit is not None else 0.0
        if speed > 0 and math.isfinite(speed):
            element.set("ctrlrange", numbers((-speed, speed)))
    else:
        gain = motor.gain or UNLIMITED_GAIN
        element = ET.Element("position", name=motor.joint, joint=motor.joint, kp=number(gain))
        element.set("dampratio", "1")
        limit = joint.limit
        bounded = joint.type is not JointType.CONTINUOUS and limit is not None
        if bounded and limit is not None and limit.lower < limit.upper:
            element.set("ctrlrange", numbers((limit.lower, limit.upper)))
    if force is not None:
        element.set("forcerange", numbers((-force, force)))
    return element


def _effort(joint: Joint) -> float | None:
    limit = joint.limit
    if limit is None or not (limit.effort > 0 and math.isfinite(limit.effort)):
        return None
    return limit.effort


_COMMANDS = ("velocity", "position", "effort")
