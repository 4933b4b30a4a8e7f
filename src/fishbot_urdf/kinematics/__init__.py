"""Forward kinematics: where every link's frame is, at a joint configuration.

`link_poses` is plain Python, for `check` (which imports no numpy); `Kinematics` (in
``_batched``) is numpy, for many configurations at once, frame queries and Jacobians.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..analysis import Analysis, of
from ..errors import ArgumentError, UnknownNameError
from ..model import Joint, JointType, Robot
from ..spatial import Pose, axis_angle, scale
from ._mimic import follows

if TYPE_CHECKING:
    from ._batched import Kinematics, forward_kinematics, jacobian, transform

__all__ = [
    "Kinematics",
    "forward_kinematics",
    "jacobian",
    "joint_positions",
    "link_poses",
    "transform",
]

_MOVING = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)


def joint_positions(
    robot: Robot | Analysis, positions: Mapping[str, float] | None = None
) -> dict[str, float]:
    """The position of every revolute, continuous and prismatic joint (rad or m).

    Joints not named in ``positions`` are at zero, except mimic joints, which follow their
    leader: multiplier * leader + offset (chains followed to their end; see
    :mod:`fishbot_urdf.kinematics._mimic` for a leader that is fixed, and for loops).

    Raises:
        UnknownNameError: ``positions`` names a joint the robot does not have.
        ArgumentError: ``positions`` names a fixed, floating or planar joint (whose pose
            is not one number), or gives a position that is not a finite number, or is
            outside a revolute or prismatic joint's limits.
    """
    model = robot if isinstance(robot, Robot) else robot.robot
    given = dict(positions or {})
    by_name = (
        {joint.name: joint for joint in model.joints} if isinstance(robot, Robot) else robot.joints
    )
    for name in given:
        joint = by_name.get(name)
        if joint is None:
            raise UnknownNameError("joint", name, by_name)
        if joint.type not in _MOVING:
            raise ArgumentError(
                f"joint {name!r} is {joint.type.value}: it takes no position", name=name
            )
        if not math.isfinite(given[name]):
            raise ArgumentError(
                f"joint {name!r}: position {given[name]} is not a finite number", name=name
            )
        limit = joint.limit
        bounded = joint.type is not JointType.CONTINUOUS and limit is not None
        if bounded and limit and not limit.lower - 1e-9 <= given[name] <= limit.upper + 1e-9:
            raise ArgumentError(
                f"joint {name!r}: position {given[name]:g} is outside its limits "
                f"{limit.lower:g} .. {limit.upper:g}",
                name=name,
            )
    values: dict[str, float] = {}
    for joint in model.joints:
        if joint.type not in _MOVING:
            continue
        source = None if joint.name in given else follows(by_name, joint)
        if source is None:
            values[joint.name] = given.get(joint.name, 0.0)
        elif source.leader is None:
            values[joint.name] = source.offset
        else:
            leader = given.get(source.leader, 0.0)
            values[joint.name] = source.multiplier * leader + source.offset
    return values


def joint_motion(joint: Joint, position: float) -> Pose:
    """The child frame relative to the joint frame when the joint is at ``position``."""
    if joint.type in (JointType.REVOLUTE, JointType.CONTINUOUS):
        return Pose(rotation=axis_angle(joint.axis, position))
    if joint.type is JointType.PRISMATIC and position:
        norm = sum(a * a for a in joint.axis) ** 0.5
        return Pose(translation=scale(joint.axis, position / norm) if norm else (0.0, 0.0, 0.0))
    return Pose()


def link_poses(
    robot: Robot | Analysis, positions: Mapping[str, float] | None = None
) -> dict[str, Pose]:
    """The pose of every link reached from a root, in that root's frame.

    Args:
        robot: The robot, or its analysis.
        positions: Joint positions by name (rad for revolute and continuous, m for
            prismatic); the rest are zero (mimic joints follow their leader).

    Returns:
        Link name -> Pose in the frame of its root link (roots map to the identity). Links
        in a joint loop, which no root reaches, are left out.

    Raises:
        UnknownNameError: ``positions`` names a joint that does not exist.
        ArgumentError: ``positions`` names a joint that does not move, or a position that
            is not finite.
    """
    analysis = of(robot)
    values = joint_positions(analysis, positions)
    children, parent_joint = analysis.topology.children, analysis.parent_joint
    poses = {name: Pose() for name in analysis.topology.roots}
    stack = list(poses)
    while stack:  # iterative: a 10k-link chain is fine
        name = stack.pop()
        for joint in children[name]:
            # A link with two parent joints hangs from the first in the file.
            if parent_joint[joint.child] is not joint or joint.child in poses:
                continue
            pose = poses[name].then(Pose.of(joint.origin))
            if joint.name in values:
                pose = pose.then(joint_motion(joint, values[joint.name]))
            poses[joint.child] = pose
            stack.append(joint.child)
    return poses


def __getattr__(name: str) -> Any:
    # The numpy side loads when first used: `check` poses links with the plain code above.
    if name in ("Kinematics", "forward_kinematics", "jacobian", "transform"):
        from . import _batched

        return getattr(_batched, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
