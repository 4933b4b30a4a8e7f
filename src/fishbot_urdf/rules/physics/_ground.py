"""Where a robot on a footprint root stands: below or above the ground at zero."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ...analysis import Analysis
from ...catalog.physics import ABOVE_GROUND, BELOW_GROUND, GroundFacts
from ...diagnostics import Diagnostic
from ...model import Box, Collision, Cylinder, JointType, Link, Sphere
from ...spatial import Pose
from ._common import link_subject

GROUND_TOLERANCE = 0.002
"""How far (m) the lowest collision point may be from the ground before it is reported."""


def _extent(collision: Collision, pose: Pose) -> tuple[float, float] | None:
    """The lowest and highest z of a collision shape placed by its link's ``pose`` (None for
    a mesh, whose points are not read)."""
    frame = pose.then(Pose.of(collision.origin))
    z = frame.translation[2]
    row = frame.rotation[2]  # how each of the shape's axes leans on the vertical
    shape = collision.geometry
    if isinstance(shape, Sphere):
        reach = shape.radius
    elif isinstance(shape, Box):
        reach = sum(abs(row[k]) * shape.size[k] / 2.0 for k in range(3))
    elif isinstance(shape, Cylinder):
        upright = min(1.0, abs(row[2]))
        reach = upright * shape.length / 2.0 + math.sqrt(1.0 - upright * upright) * shape.radius
    else:
        return None
    return z - reach, z + reach


# Joints whose motion leaves a round part's lowest point where it is: a wheel on its axle.
_STANDING = (JointType.FIXED, JointType.CONTINUOUS)


def ground(analysis: Analysis, tolerance: float) -> Iterator[Diagnostic]:
    """Whether a robot on a footprint root stands on its z = 0 at the zero configuration.

    The findings' data give the distance and the tolerance, in mm (``distance_mm``,
    ``tolerance_mm``).
    """
    robot, path = analysis.robot, analysis.path
    name = analysis.topology.root
    root = analysis.links.get(name) if name is not None else None
    if root is None or root.visuals or root.collisions or root.inertial:
        return  # the ground is z = 0 of a footprint root, a bare frame
    if root.name == "world":
        return  # Gazebo's name for the world itself: the robot is mounted, not standing
    # Only links the root holds through fixed joints and wheel axles: an arm's height at
    # the zero configuration says nothing about the ground. The plan puts parents first.
    plan = analysis.plan
    links = plan.links
    held = {root.name}
    for step in plan.steps:
        if step.joint.type in _STANDING and links[step.parent] in held:
            held.add(links[step.link])
    # At the zero configuration a wheel's axle does not move it: the robot's own poses.
    poses = analysis.zero_poses
    spans: list[tuple[float, float, Link, Collision]] = []
    # Whether the robot may stand on something we cannot place: a mesh, or a leg or an
    # arm (a link on a joint that is neither fixed nor a wheel's axle).
    unknown = False
    for link in robot.links:
        if link.name not in held or link is root:
            unknown = unknown or (link.name not in held and bool(link.collisions))
            continue
        for collision in link.collisions:
            span = _extent(collision, poses[link.name])
            if span is None:
                unknown = True
            else:
                spans.append((*span, link, collision))
    if not spans:
        return
    bottom = min(spans, key=lambda item: item[0])
    top = max(item[1] for item in spans)
    if top <= -bottom[0]:
        return  # the root sits inside the robot (a pelvis, a waist): not on the ground
    where = f"the ground (z = 0 of {root.name!r}) at the zero configuration"
    passes = f"up to {tolerance * 1000:g} mm passes"
    # Compared to the micrometre: a wheel turned by rpy 1.57079 rather than pi/2 sinks
    # 0.0001 mm more than its radius says, which is no finding.
    reported: set[str] = set()
    for z, _, link, collision in sorted(spans, key=lambda item: item[0]):
        if z < -tolerance - _MICROMETRE and link.name not in reported:
            reported.add(link.name)
            depth = _mm(-z, tolerance)
            yield BELOW_GROUND.report(
                f"link {link.name!r} reaches {depth} mm below {where}",
                collision.source or link.source,
                path=path,
                subject=link_subject(link),
                hint=f"raise the joints above it or shorten the shape by {depth} mm; {passes}",
                data=GroundFacts(distance_mm=-z * 1000, tolerance_mm=tolerance * 1000),
            )
    z, _, link, collision = bottom
    if z > tolerance + _MICROMETRE and not unknown:
        height = _mm(z, tolerance)
        yield ABOVE_GROUND.report(
            f"link {link.name!r}, the robot's lowest point, is {height} mm above {where}",
            collision.source or link.source,
            path=path,
            subject=link_subject(link),
            hint=f"the robot floats: lower the joint below {root.name!r} by {height} mm; " + passes,
            data=GroundFacts(distance_mm=z * 1000, tolerance_mm=tolerance * 1000),
        )


_MICROMETRE = 1e-6


def _mm(metres: float, tolerance: float) -> str:
    """A distance in mm, with the digits that show it is beyond ``tolerance``."""
    for digits in (1, 2, 3, 4):
        text = f"{metres * 1000:.{digits}f}"
        if float(text) != round(tolerance * 1000, digits):
            return text
    return f"{metres * 1000:.4f}"
