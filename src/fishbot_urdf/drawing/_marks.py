"""What RViz's robot model draws of a link besides its shapes, as triangles in the link's
frame: its mass as a ball of lead at its centre of mass, its inertia as the equivalent box
on its principal axes (sized by `fishbot_urdf.inertia`), and its frame as three axes."""

from __future__ import annotations

import math
from typing import Any, NamedTuple

from ..inertia import NoBox, equivalent_box, mass_sphere_diameter, why_no_box
from ..model import Inertial
from ._shapes import box, origin_matrix, sphere

__all__ = [
    "AXES_SHARE",
    "INERTIA",
    "MASS",
    "SEEN_THROUGH",
    "Mark",
    "axes",
    "axes_length",
    "inertial_marks",
]

AXES_SHARE = 0.1
"""A link frame's axes are this share of the robot's size (the diagonal of the box around
what is drawn of it, or around its links' origins when nothing is) long: small beside a
robot of any size. A robot of one point gets RViz's axes, 0.1 m long."""

MASS = (1.0, 0.0, 0.0, 1.0)  # RViz's mass sphere and inertia box: opaque red
INERTIA = (1.0, 0.0, 0.0, 1.0)
SEEN_THROUGH = 0.4
"""The alpha of the mass sphere and inertia box drawn with the shapes they belong to (RViz
draws them opaque): an inertia far too big, a box around the whole robot, would hide the
shape it is wrong about; seen through, the shape shows inside it."""
_AXES = ((1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0))  # x, y, z: as RViz
_AXIS_WIDTH = 0.1  # of an axis' length
_RVIZ_AXES = 0.1  # metres: RViz's axes' length (rviz_default_plugins), for a robot of no size


class Mark(NamedTuple):
    """Triangles (T, 3, 3) in a link's frame, their colour and the layer they belong to; for
    a mark of lines, the lines too, as segments (N, 2, 3) in the link's frame, which the
    triangles draw as thin boxes."""

    triangles: Any
    color: tuple[float, float, float, float]
    layer: str
    lines: Any = None


def inertial_marks(
    np: Any, inertial: Inertial, layers: tuple[str, ...]
) -> tuple[list[Mark], NoBox | None]:
    """The ``mass`` sphere and ``inertia`` box of an inertial, those of ``layers`` asked for,
    and, when an inertia box was asked for and there is none (RViz draws none either), why.
    A mass of 0 has a ball of size 0: nothing. Opaque red, as RViz draws them; with the
    visual or collision shapes in ``layers``, :data:`SEEN_THROUGH`."""
    marks = []
    mass_color, inertia_color = MASS, INERTIA
    if "visual" in layers or "collision" in layers:
        mass_color, inertia_color = (*MASS[:3], SEEN_THROUGH), (*INERTIA[:3], SEEN_THROUGH)
    frame = origin_matrix(np, inertial.origin)  # the centre of mass, the inertia's axes
    if "mass" in layers:
        diameter = mass_sphere_diameter(inertial.mass)
        if diameter > 0.0 and math.isfinite(diameter):
            marks.append(Mark(sphere(np, diameter / 2) + frame[:3, 3], mass_color, "mass"))
    if "inertia" not in layers:
        return marks, None
    found = equivalent_box(inertial)
    if found is None:
        return marks, why_no_box(inertial)
    if min(found.size) > 0.0:
        turn = frame[:3, :3] @ np.array(found.axes)  # the origin's rpy, then the principal axes
        local = box(np, *found.size) @ turn.T + frame[:3, 3]
        marks.append(Mark(local, inertia_color, "inertia"))
    return marks, None


def axes_length(np: Any, points: Any) -> float:
    """:data:`AXES_SHARE` of the diagonal of the box around ``points`` (N, 3), or RViz's
    0.1 m for a robot of no size."""
    if not len(points):
        return _RVIZ_AXES
    diagonal = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))
    return AXES_SHARE * diagonal if diagonal > 0.0 else _RVIZ_AXES


def axes(np: Any, length: float) -> list[Mark]:
    """A frame's x, y and z axes, ``length`` long from its origin: thin boxes in red, green
    and blue."""
    width = _AXIS_WIDTH * length
    marks = []
    for axis, color in enumerate(_AXES):
        sides = [width, width, width]
        sides[axis] = length
        centre = np.zeros(3)
        centre[axis] = length / 2
        marks.append(Mark(box(np, *sides) + centre, color, "frames"))
    return marks
