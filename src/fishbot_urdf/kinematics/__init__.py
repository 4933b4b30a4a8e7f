"""Forward kinematics: where every link's frame is, at a joint configuration.

Two evaluators read one kinematic plan (`fishbot_urdf.analysis.plan`, built once per robot
by its analysis):
`link_poses` is plain Python, for `check` (which imports no numpy); `Kinematics` (in
``_batched``) is numpy, for many configurations at once, frame queries and Jacobians.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..analysis import Analysis, of
from ..analysis.poses import place
from ..model import Robot
from ..spatial import Pose
from . import _batched  # (numpy loads with the first Kinematics, not with it)
from .positions import MOVING, check_joint

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


def joint_positions(
    robot: Robot | Analysis, positions: Mapping[str, float] | None = None
) -> dict[str, float]:
    """The position of every revolute, continuous and prismatic joint (rad or m).

    Joints not named in ``positions`` are at zero, except mimic joints, which follow their
    leader: multiplier * leader + offset (chains followed to their end; see
    :mod:`fishbot_urdf.analysis.mimic` for a leader that is fixed, and for loops).

    Raises:
        UnknownNameError: ``positions`` names a joint the robot does not have.
        ArgumentError: ``positions`` names a fixed, floating or planar joint (whose pose
            is not one number), or gives a position that is not a finite number, or is
            outside a revolute or prismatic joint's limits.
    """
    analysis = of(robot)
    given = _checked(analysis, positions)
    plan = analysis.plan
    values: dict[str, float] = {}
    for joint in analysis.robot.joints:
        if joint.type not in MOVING:
            continue
        source = None if joint.name in given else plan.mimics.get(joint.name)
        if source is None:
            values[joint.name] = given.get(joint.name, 0.0)
        elif source.leader is None or source.leader not in plan.columns:
            values[joint.name] = source.offset  # its chain ends where no position is given
        else:
            leader = given.get(source.leader, 0.0)
            values[joint.name] = source.multiplier * leader + source.offset
    return values


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
    given = _checked(analysis, positions)
    plan = analysis.plan
    q = [0.0] * len(plan.variables)
    held: dict[str, float] = {}
    for name, value in given.items():
        column = plan.columns.get(name)
        if column is None:
            held[name] = value  # a mimic joint given its own position
        else:
            q[column] = value
    return dict(zip(plan.links, place(plan, q, held), strict=True))


def _checked(analysis: Analysis, positions: Mapping[str, float] | None) -> dict[str, float]:
    """``positions``, each of a revolute, continuous or prismatic joint, finite, and within
    the joint's limits (see `joint_positions` for what is raised)."""
    return {name: check_joint(analysis, name, value) for name, value in (positions or {}).items()}


def __getattr__(name: str) -> Any:
    if name in ("Kinematics", "forward_kinematics", "jacobian", "transform"):
        return getattr(_batched, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
