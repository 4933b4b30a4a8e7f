"""What a mimic joint follows: one rule for both evaluators of the kinematics.

A mimic joint is at ``multiplier * leader + offset``. A chain of mimics is followed to its
end, the multipliers and offsets combined. A chain that ends at a joint whose position is
not one number (fixed, planar, floating) holds the joint at its combined offset, the leader
counting as at 0; a chain that loops, or names no joint, leaves the joint to move on its own.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ..model import Joint, JointType

__all__ = ["Follows", "follows"]

ONE_NUMBER = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)
"""The joints whose position is one number."""


@dataclass(frozen=True, slots=True)
class Follows:
    """Where a mimic joint is: ``multiplier * position of leader + offset``, or at ``offset``
    when ``leader`` is None (its chain ends at a joint whose position is not one number)."""

    leader: str | None
    multiplier: float
    offset: float


def follows(joints: Mapping[str, Joint], joint: Joint) -> Follows | None:
    """What ``joint`` follows, or None when it moves on its own (no mimic, a mimic of no
    joint, or mimics that loop)."""
    if joint.mimic is None:
        return None
    multiplier, offset = 1.0, 0.0
    seen = {joint.name}
    current = joint
    while current.mimic is not None:
        leader = joints.get(current.mimic.joint)
        if leader is None or leader.name in seen:
            return None
        multiplier, offset = (
            multiplier * current.mimic.multiplier,
            multiplier * current.mimic.offset + offset,
        )
        if leader.type not in ONE_NUMBER:
            return Follows(None, 0.0, offset)
        seen.add(leader.name)
        current = leader
    return Follows(current.name, multiplier, offset)
