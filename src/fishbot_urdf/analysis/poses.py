"""The plain-Python evaluator of a kinematic plan: every link's pose at one configuration.

`check` poses links with it, and imports no numpy; `_batched` evaluates the same plan in
numpy, for batches.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from ..model import JointType
from ..spatial import Pose, add, axis_angle, rpy_matrix, scale
from .plan import Plan, Step

__all__ = ["place"]

_TURNS = (JointType.REVOLUTE, JointType.CONTINUOUS)
_ORIGIN = Pose()


def place(plan: Plan, q: Sequence[float], held: Mapping[str, float] | None = None) -> list[Pose]:
    """Every link's pose in its root's frame, in ``plan.links`` order.

    Args:
        plan: The robot's kinematic plan.
        q: The configuration, one number per column of ``plan.variables`` (rad, m).
        held: Positions (rad, m) that replace what the plan says of these revolute,
            continuous or prismatic joints (a mimic joint given its own position).
    """
    poses = [_ORIGIN] * len(plan.links)
    for step in plan.steps:
        pose = poses[step.parent].then(step.origin)
        if step.kind is not JointType.FIXED:
            motion = _motion(step, q, held)
            if motion is not None:
                pose = pose.then(motion)
        poses[step.link] = pose
    return poses


def _motion(step: Step, q: Sequence[float], held: Mapping[str, float] | None) -> Pose | None:
    """The child frame in the joint frame (None: where the joint frame is)."""
    kind, column = step.kind, step.column
    if kind is JointType.PLANAR:
        x, y, yaw = q[column], q[column + 1], q[column + 2]
        along, across = step.plane or ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
        return Pose(axis_angle(step.axis, yaw), add(scale(along, x), scale(across, y)))
    if kind is JointType.FLOATING:
        x, y, z, roll, pitch, yaw = q[column : column + 6]
        return Pose(rpy_matrix((roll, pitch, yaw)), (x, y, z))
    name = step.joint.name
    if held and name in held:
        value = held[name]
    elif column >= 0:
        value = step.multiplier * q[column] + step.offset
    else:
        value = step.offset
    if not value:
        return None
    if kind in _TURNS:
        return Pose(rotation=axis_angle(step.axis, value))
    return Pose(translation=scale(step.axis, value))
