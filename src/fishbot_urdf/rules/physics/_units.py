"""Whether a robot built of boxes, cylinders and spheres was written in millimetres."""

from __future__ import annotations

import math
import statistics

from ...catalog.physics import ROBOT_UNITS, UnitsFacts
from ...diagnostics import Diagnostic, Kind, Subject
from ...model import Box, Cylinder, Geometry, JointType, Robot, Sphere

# Judged together, so that no one of them alone makes the finding: a ground plane is a box of
# 200 m, a room of 40 m, and neither has joints metres apart; a warehouse or a house in metres
# has its rooms and shelves metres apart, but nothing moves, and nothing (or a kilogram or
# two, a placeholder) weighs it.
_PART = 10.0  # m: the median shape beyond this is no robot part (10 mm read as metres)
_APART = 1.0  # m: the median joint beyond this, with such parts, is millimetres too
_LIGHT = 1e-3  # kg/m^3, a thousandth of air: metal or plastic measured in millimetres and
# weighed in kilograms reads 1e-7 to 2e-5 (its density times 1e-9); a room of 300 m^3 given
# a placeholder kilogram, 3e-3


_MOVING = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)


def millimetres(robot: Robot) -> UnitsFacts | None:
    """What says ``robot`` was written in millimetres (its shapes, its joints, one of which
    moves, and its density, together), or None when they do not all say so."""
    sizes = sorted(size for shape in _shapes(robot) if (size := _largest(shape)) > 0)
    if len(sizes) < 2 or statistics.median(sizes) < _PART:
        return None
    apart = [math.dist((0.0, 0.0, 0.0), map(float, joint.origin.xyz)) for joint in robot.joints]
    apart = [a for a in apart if a > 0 and math.isfinite(a)]
    if not apart or statistics.median(apart) < _APART:
        return None  # nothing held apart by joints: a ground plane, a room
    if not any(joint.type in _MOVING for joint in robot.joints):
        return None  # nothing moves: a world, a building
    density = _density(robot)
    if density is None or density >= _LIGHT:
        return None  # not weighed, or weighing as much as what big things weigh
    return UnitsFacts(
        sizes=(sizes[0], statistics.median(sizes), sizes[-1]),
        joints=statistics.median(apart),
        density=density,
    )


def units(robot: Robot, path: str, facts: UnitsFacts) -> Diagnostic:
    """The finding that ``robot`` reads as millimetres."""
    low, middle, high = facts.sizes
    weighed = f", and its links weigh {facts.density:.2g} kg/m^3, far lighter than air"
    return ROBOT_UNITS.report(
        f"robot {robot.name!r} reads as written in millimetres: its boxes, cylinders and "
        f"spheres are {low:.3g} to {high:.3g} m across (median {middle:.3g} m), its joints "
        f"{facts.joints:.3g} m from their parents{weighed}",
        robot.source,
        path=path,
        subject=Subject(Kind.ROBOT, robot.name),
        hint=f"multiply every length by {facts.factor:g} (sizes and origins; inertias by "
        f"1e-6): {middle:.3g} m is {middle * facts.factor:.3g} m",
        data=facts,
    )


def _shapes(robot: Robot) -> list[Geometry]:
    shapes: list[Geometry] = []
    for link in robot.links:
        shapes += [v.geometry for v in link.visuals]
        shapes += [c.geometry for c in link.collisions]
    return shapes


def _largest(shape: Geometry) -> float:
    """A box's, cylinder's or sphere's largest side, m (0 for a mesh, and for no number)."""
    if isinstance(shape, Box):
        size = max(shape.size)
    elif isinstance(shape, Cylinder):
        size = max(2.0 * shape.radius, shape.length)
    elif isinstance(shape, Sphere):
        size = 2.0 * shape.radius
    else:
        return 0.0
    size = float(size)  # (a number of another kind, given in code, is printed as a float)
    return size if math.isfinite(size) else 0.0


def _volume(shape: Geometry) -> float:
    if isinstance(shape, Box):
        return abs(shape.size[0] * shape.size[1] * shape.size[2])
    if isinstance(shape, Cylinder):
        return math.pi * shape.radius**2 * abs(shape.length)
    if isinstance(shape, Sphere):
        return 4.0 / 3.0 * math.pi * abs(shape.radius) ** 3
    return math.nan  # a mesh: not weighed here


def _density(robot: Robot) -> float | None:
    """The mass of the links that have one over their shapes' volume (their collisions, else
    their visuals), kg/m^3; None when no link can be weighed (a mesh among its shapes)."""
    mass = volume = 0.0
    for link in robot.links:
        inertial = link.inertial
        if inertial is None or not inertial.mass > 0 or not math.isfinite(inertial.mass):
            continue
        parts = [c.geometry for c in link.collisions] or [v.geometry for v in link.visuals]
        filled = sum(_volume(shape) for shape in parts)
        if parts and filled > 0 and math.isfinite(filled):
            mass += inertial.mass
            volume += filled
    return mass / volume if volume > 0 else None
