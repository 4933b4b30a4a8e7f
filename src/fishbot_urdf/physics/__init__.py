"""Robot -> findings about mass and inertia, and about where the robot stands on the ground.

Simulators merge links joined by fixed joints into one rigid body (Gazebo lumps them,
MuJoCo fuses them), so whether a body can move is judged on the merged body; what no
piece of matter can have (a negative moment) is judged on every link, the root included.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostic
from ..model import Robot
from ..spatial import eigh
from ._ground import GROUND_TOLERANCE, ground
from ._mass import bodies, body_findings, finite
from ._shape import MISMATCH, mismatch

__all__ = ["GROUND_TOLERANCE", "MISMATCH", "physics"]


def physics(
    robot: Robot, path: str, *, ground_tolerance: float = GROUND_TOLERANCE
) -> Iterator[Diagnostic]:
    """Every finding about the robot's masses, inertias and stance on the ground.

    Args:
        robot: The robot.
        path: The file findings without a location are reported against.
        ground_tolerance: How far (m) below or above z = 0 of a footprint root the lowest
            collision point may be.
    """
    # Principal moments, once per link (they do not change when the inertia is turned).
    moments = {
        link.name: eigh(link.inertial.inertia.matrix())[0]
        for link in robot.links
        if link.inertial is not None and finite(link.inertial)
    }
    for body in bodies(robot):
        yield from body_findings(body, path, moments, bool(robot.joints))
    for link in robot.links:
        if link.name in moments:
            yield from mismatch(link, path, moments[link.name])
    yield from ground(robot, path, ground_tolerance)
