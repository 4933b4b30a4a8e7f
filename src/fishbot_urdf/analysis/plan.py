"""The kinematic plan of one robot: built once, read by both evaluators of its kinematics.

As pinocchio's Model is to its Data: the plan holds what does not change with the joint
positions (the links in an order that puts every parent before its children, each link's
parent and joint, the joint's origin, type and unit axis, the configuration's columns, and
each mimic joint resolved to the joint that drives it), and an evaluator fills in poses for
one configuration (`fishbot_urdf.analysis.poses`, for `check`) or a batch of them
(`fishbot_urdf.kinematics.Kinematics`, numpy).

A configuration holds one number per *column*, in `Plan.variables` order: the joints that
move on their own, in file order (a mimic joint follows the column of its driver), with

- revolute, continuous: the angle (rad) about the axis;
- prismatic: the distance (m) along the axis;
- planar: ``x``, ``y`` (m) along `Step.plane`, then ``yaw`` (rad) about the axis;
- floating: ``x``, ``y``, ``z`` (m), then ``roll``, ``pitch``, ``yaw`` (rad, as in an
  ``<origin rpy>``).

A joint moves its child by ``multiplier * q[column] + offset``: 1 and 0 for a joint with a
column of its own, its mimic chain's combined values for a mimic (`mimic.follows`), and
column -1 (held at its offset) when the chain ends at a joint whose position is not one
number, or at a joint that places no link. A fixed joint never moves, mimic or not; a
planar or floating joint's position is not one number, so it keeps its columns whatever
it mimics; a revolute, continuous or prismatic joint whose axis is 0 0 0 does not move.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import NamedTuple

from ..model import Joint, JointType, Robot, Vector3
from ..spatial import Pose, rpy_matrix
from .mimic import ONE_NUMBER, Follows, follows
from .topology import Topology

__all__ = ["PARTS", "Plan", "Step", "build"]

PARTS = {
    JointType.PLANAR: ("x", "y", "yaw"),
    JointType.FLOATING: ("x", "y", "z", "roll", "pitch", "yaw"),
}
"""The columns of the joints whose position is more than one number, by name suffix."""

_ZERO: Vector3 = (0.0, 0.0, 0.0)


class Step(NamedTuple):
    """How one link is placed from its parent link.

    Attributes:
        link: The link placed (its index in `Plan.links`).
        parent: Its parent link (an index in `Plan.links`, always smaller than ``link``).
        joint: The joint between them.
        kind: How the joint moves the link: its type, or FIXED when it does not move (a
            fixed joint, or a revolute, continuous or prismatic joint whose axis is 0 0 0).
        origin: The joint's ``<origin>``: the joint frame in the parent link's frame.
        axis: The joint's axis, of length 1 (0 0 0 when written so).
        column: The first column of the configuration that moves the joint (a mimic's: its
            driver's); -1 when none does (the joint is held at ``offset``).
        multiplier: The joint is at ``multiplier * q[column] + offset``.
        offset: See ``multiplier``.
        plane: A planar joint's two directions of motion (x, y), in the joint frame: x and y
            turned by the shortest rotation from z to the axis; None for other joints.
    """

    link: int
    parent: int
    joint: Joint
    kind: JointType
    origin: Pose
    axis: Vector3
    column: int
    multiplier: float
    offset: float
    plane: tuple[Vector3, Vector3] | None


@dataclass(frozen=True, slots=True)
class Plan:
    """The kinematic plan of one robot.

    Attributes:
        links: Every link a root reaches, each root followed by the links below it, every
            parent before its children. A link hangs from its first parent joint in file
            order; links on a joint loop that no root reaches are left out.
        roots: The roots, in file order (their poses are the identity: each is the frame of
            its tree).
        steps: How each link that is no root is placed, in ``links`` order.
        index: Each link's index in ``links``.
        variables: The configuration's columns by name: a joint's name, or ``joint.x``-style
            names for planar and floating joints.
        joints: The joints that own columns, in file order.
        columns: Each of ``joints``'s first column.
        mimics: Every joint with a ``<mimic>``, whatever its type, resolved to its driver
            (None when the mimic names no joint, or mimics loop).
    """

    links: tuple[str, ...]
    roots: tuple[str, ...]
    steps: tuple[Step, ...]
    index: Mapping[str, int]
    variables: tuple[str, ...]
    joints: tuple[str, ...]
    columns: Mapping[str, int]
    mimics: Mapping[str, Follows | None]

    def outwards(self) -> tuple[str, ...]:
        """``variables`` from the roots outwards: each joint's columns where its child comes
        in ``links`` (as tf lists the joints), not in file order; those of joints no root
        reaches last, in file order."""
        firsts = list(self.columns.values())
        # (no joints: one end for none, which strict zipping would refuse)
        ends = dict(zip(self.joints, [*firsts[1:], len(self.variables)], strict=False))
        order: list[str] = []
        for name in dict.fromkeys(step.joint.name for step in self.steps):
            if name in ends:
                order.extend(self.variables[self.columns[name] : ends[name]])
        placed = set(order)
        return (*order, *(name for name in self.variables if name not in placed))


def build(
    robot: Robot,
    topology: Topology,
    parent_joint: Mapping[str, Joint],
    joints: Mapping[str, Joint],
) -> Plan:
    """The plan of ``robot`` from its analysis' facts (linear in its size): ``topology``,
    each link's ``parent_joint`` and the ``joints`` by name."""
    # Each link's parent joint's mimic, resolved (a joint of a name used twice has its own).
    sources = {
        child: follows(joints, joint)
        for child, joint in parent_joint.items()
        if joint.mimic is not None and joint.type in ONE_NUMBER
    }
    variables: list[str] = []
    columns: dict[str, int] = {}
    for joint in robot.joints:
        if parent_joint.get(joint.child) is not joint:
            continue
        parts = PARTS.get(joint.type)
        if parts is not None:
            columns[joint.name] = len(variables)
            variables.extend(f"{joint.name}.{p}" for p in parts)
        elif joint.type in ONE_NUMBER and sources.get(joint.child) is None:
            columns[joint.name] = len(variables)
            variables.append(joint.name)
    index: dict[str, int] = {}
    order: list[str] = []
    steps: list[Step] = []
    children = topology.children
    for root in topology.roots:
        if root in index:
            continue
        index[root] = len(order)
        order.append(root)
        pending = [root]
        while pending:  # depth first, without recursion: a 10 000-link chain is fine
            name = pending.pop()
            for joint in children[name]:
                child = joint.child
                if child in index or parent_joint.get(child) is not joint:
                    continue
                index[child] = len(order)
                order.append(child)
                pending.append(child)
                steps.append(_step(joint, index[name], index[child], columns, sources.get(child)))
    return Plan(
        links=tuple(order),
        roots=topology.roots,
        steps=tuple(steps),
        index=index,
        variables=tuple(variables),
        joints=tuple(columns),
        columns=columns,
        mimics={j.name: follows(joints, j) for j in joints.values() if j.mimic is not None},
    )


def _step(
    joint: Joint,
    parent: int,
    link: int,
    columns: Mapping[str, int],
    source: Follows | None,
) -> Step:
    kind = joint.type
    origin = Pose(rpy_matrix(joint.origin.rpy), joint.origin.xyz)
    x, y, z = joint.axis
    norm = math.hypot(x, y, z)  # (no underflow for a tiny axis, as a sum of squares has)
    axis = (x / norm, y / norm, z / norm) if norm > 0 else _ZERO
    if kind is JointType.FIXED or (kind in ONE_NUMBER and norm == 0):
        return Step(link, parent, joint, JointType.FIXED, origin, axis, -1, 0.0, 0.0, None)
    plane = _plane(axis) if kind is JointType.PLANAR else None
    if source is None:
        return Step(link, parent, joint, kind, origin, axis, columns[joint.name], 1.0, 0.0, plane)
    column = -1 if source.leader is None else columns.get(source.leader, -1)
    multiplier, offset = source.multiplier, source.offset
    return Step(link, parent, joint, kind, origin, axis, column, multiplier, offset, None)


def _plane(n: Vector3) -> tuple[Vector3, Vector3]:
    """x and y turned by the shortest rotation from z to the unit vector ``n`` (Rodrigues,
    with K the cross product by v = z x n: R = I + K + K^2 / (1 + z . n))."""
    vx, vy, c = -n[1], n[0], n[2]  # v = z x n (its z is 0), c = z . n
    if math.sqrt(vx * vx + vy * vy) < 1e-12:  # n is z, -z (half a turn about x), or 0 0 0
        return ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)) if c > 0 else ((1.0, 0.0, 0.0), (0.0, -1.0, 0.0))
    s = vx * vx + vy * vy  # |v|^2 = 1 - c^2
    # 1 / (1 + c), which near c = -1 (n close to -z) is (1 - c) / |v|^2 without cancelling
    k = 1.0 / (1.0 + c) if c >= 0 else (1.0 - c) / s
    # K^2 = v v^T - |v|^2 I, and v has no z: the columns of R for x and y
    return (
        (1.0 + k * (vx * vx - s), k * vx * vy, -vy),
        (k * vx * vy, 1.0 + k * (vy * vy - s), vx),
    )
