"""The motors of an MJCF model, from the robot's own description: the wheels its differential
drive plugin turns, and the command interfaces of its ``<ros2_control>`` joints.

Gazebo's drive plugins hold each wheel at the speed asked for with at most their greatest
wheel torque; the model holds it so with a velocity servo whose force is limited to that
torque, as stiff as the time step allows: its gain is the inertia the wheel moves (its own
about the axle, and its share of the robot's mass at its radius) over half a time step
(`WHEEL_RESPONSE`). A stiffer one makes light wheels kick the robot off the floor. A
ros2_control joint commanded by velocity gets a velocity servo (limited to its ``<limit
effort>``), one commanded by position a critically damped position servo, one commanded by
effort a motor. Each actuator is named after its joint.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from typing import NamedTuple

from ..analysis import Analysis
from ..analysis.drive import Drive, unit, wheel_radius
from ..model import Joint, JointType, Link
from ..spatial import dot, mat_vec, rpy_matrix, transpose
from ._geoms import number, numbers

__all__ = ["VELOCITY_STIFFNESS", "WHEEL_RESPONSE", "Motor", "actuator", "motors"]

WHEEL_RESPONSE = 0.001
"""How soon a wheel's servo answers (s): half of MuJoCo's default time step."""
VELOCITY_STIFFNESS = 10.0
"""A velocity servo's gain is its force limit times this (per rad/s, or m/s): it gives its
whole torque at a tenth of a unit off, as stiff as Gazebo's joint motors feel."""
POSITION_STIFFNESS = 20.0
"""A position servo's gain is its force limit times this (per rad, or m): its whole effort
at 0.05 rad off."""
UNLIMITED_GAIN = 100.0
"""The gain of a servo whose joint gives no effort limit (N*m per rad, or per rad/s)."""

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
        found[joint.name] = Motor(joint.name, command, _effort(joint), "<ros2_control>")
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
                moved = max(mass, 0.0) / len(wheels) * radius**2 + _axial(link, joint.axis)
                gain = moved / WHEEL_RESPONSE if moved > 0 else None
                yield Motor(name, "velocity", force, by, gain)


def _axial(link: Link | None, axis: tuple[float, float, float]) -> float:
    """``link``'s moment of inertia about ``axis`` through its centre of mass (0 without an
    inertial)."""
    if link is None or link.inertial is None:
        return 0.0
    along = unit(axis)
    if along is None:
        return 0.0
    inertial = link.inertial
    rotation = rpy_matrix(inertial.origin.rpy)
    local = mat_vec(transpose(rotation), along)  # the axis in the inertia's frame
    return max(dot(local, mat_vec(inertial.inertia.matrix(), local)), 0.0)


def actuator(motor: Motor, joint: Joint) -> ET.Element:
    """The MJCF actuator of ``motor`` on ``joint``."""
    force = motor.force
    if motor.command == "effort":
        element = ET.Element("motor", name=motor.joint, joint=motor.joint)
        if force is not None:
            element.set("ctrlrange", numbers((-force, force)))
        return element
    if motor.command == "velocity":
        gain = motor.gain or (UNLIMITED_GAIN if force is None else VELOCITY_STIFFNESS * force)
        element = ET.Element("velocity", name=motor.joint, joint=motor.joint, kv=number(gain))
        speed = joint.limit.velocity if joint.limit is not None else 0.0
        if speed > 0 and math.isfinite(speed):
            element.set("ctrlrange", numbers((-speed, speed)))
    else:
        gain = motor.gain or (UNLIMITED_GAIN if force is None else POSITION_STIFFNESS * force)
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
