"""Robot -> findings about mass and inertia, and about where the robot stands on the ground.

Simulators merge links joined by fixed joints into one rigid body (Gazebo lumps them,
MuJoCo fuses them), so whether a body can move is judged on the merged body; what no
piece of matter can have (a negative moment) is judged on every link, the root included.
"""

from __future__ import annotations

from collections.abc import Iterator

from ...analysis import Analysis
from ...catalog import Rule
from ...catalog.physics import (
    ABOVE_GROUND,
    BELOW_GROUND,
    INERTIA_MISMATCH,
    INERTIA_NOT_POSITIVE,
    INERTIA_TRIANGLE,
    MASSLESS_LINK,
    MISSING_INERTIAL,
    ROBOT_UNITS,
)
from ...catalog.reading import BAD_NUMBER, NEGATIVE_MASS
from ...diagnostics import Diagnostic
from ...errors import FishbotUrdfError
from ...model import Inertia, Vector3
from ...spatial import eigenvalues
from ._ground import GROUND_TOLERANCE, ground
from ._mass import body_findings, finite
from ._shape import MISMATCH, mismatch
from ._units import millimetres, units

__all__ = [
    "ABOVE_GROUND",
    "BELOW_GROUND",
    "GROUND_TOLERANCE",
    "INERTIA_MISMATCH",
    "INERTIA_NOT_POSITIVE",
    "INERTIA_TRIANGLE",
    "MASSLESS_LINK",
    "MISMATCH",
    "MISSING_INERTIAL",
    "REPORTS",
    "ROBOT_UNITS",
    "physics",
]


def principal(inertia: Inertia) -> Vector3:
    """The principal moments of ``inertia``, smallest first."""
    if inertia.ixy == 0.0 and inertia.ixz == 0.0 and inertia.iyz == 0.0:  # most URDF inertias
        a, b, c = sorted((inertia.ixx, inertia.iyy, inertia.izz))
        return a, b, c
    return eigenvalues(inertia.matrix())


def physics(
    analysis: Analysis, *, ground_tolerance: float = GROUND_TOLERANCE
) -> Iterator[Diagnostic]:
    """Every finding about the robot's masses, inertias and stance on the ground.

    Args:
        analysis: The robot, analysed.
        ground_tolerance: How far (m) below or above z = 0 of a footprint root the lowest
            collision point may be.
    """
    robot, path = analysis.robot, analysis.path
    # Principal moments, once per link (they do not change when the inertia is turned).
    moments = {
        link.name: principal(link.inertial.inertia)
        for link in robot.links
        if link.inertial is not None and finite(link.inertial)
    }
    # Judged first: a robot in millimetres is said to be, before an inertia is proposed
    # for a 200 m box.
    scaled = millimetres(robot)
    if scaled is not None:
        yield units(robot, path, scaled)
    try:
        dropped = analysis.gazebo_lumping.dropped
    except FishbotUrdfError:  # no single root: the structure rules' finding
        dropped = {}
    for body in analysis.bodies:
        yield from body_findings(
            body,
            path,
            moments,
            bool(robot.joints),
            millimetres=scaled is not None,
            lost=dropped.get(body.base.name, ()),
        )
    for link in robot.links:
        own = moments.get(link.name)
        if own is not None:
            found = mismatch(link, path, own, millimetres=scaled is not None)
            if found is not None:
                yield found
    yield from ground(analysis, ground_tolerance)


REPORTS: tuple[Rule, ...] = (
    ABOVE_GROUND,
    BAD_NUMBER,
    BELOW_GROUND,
    INERTIA_MISMATCH,
    INERTIA_NOT_POSITIVE,
    INERTIA_TRIANGLE,
    MASSLESS_LINK,
    MISSING_INERTIAL,
    NEGATIVE_MASS,
    ROBOT_UNITS,
)
"""Every rule this module's check may report: the check runs only when one is selected."""
