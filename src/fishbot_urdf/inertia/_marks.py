"""What RViz draws for a link's inertial ("Mass Properties"): a ball of lead of the link's
mass at its centre of mass, and the box of uniform density with the same mass and principal
moments, on the principal axes.

The sizes are those of rviz_default_plugins' robot link (``createMass``, ``createInertia``),
which takes the box from gz-math's ``MassMatrix3::EquivalentBox``: the same tests decide
when there is no box, and an inertia whose products are all within 1e-6 of its largest
moment is taken as already on its axes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

from ..model import Inertial, Vector3
from ..spatial import IDENTITY, Matrix3, eigh

__all__ = [
    "LEAD_DENSITY",
    "EquivalentBox",
    "NoBox",
    "equivalent_box",
    "mass_sphere_diameter",
    "why_no_box",
]

LEAD_DENSITY = 11340.0
"""kg/m^3: the density RViz sizes a link's mass sphere with (a ball of lead)."""

_ON_AXES = 1e-6  # products within this share of the largest moment: already diagonal
_ROUNDING = 10 * 2.0**-52  # of the largest moment there can be: gz-math's tolerance


@dataclass(frozen=True, slots=True)
class EquivalentBox:
    """The box of uniform density with an inertial's mass and principal moments.

    Attributes:
        size: Its sides (m), along the columns of ``axes``.
        axes: The principal axes, as the columns of a rotation, in the frame of the
            inertial's origin (the frame its ``<inertia>`` is written in).
        moments: The principal moment about each of ``axes`` (kg*m^2).
    """

    size: Vector3
    axes: Matrix3
    moments: Vector3


class NoBox(Enum):
    """Why an inertial has no equivalent box (RViz draws none), in the order it is tested."""

    NOT_FINITE = "not-finite"
    """Its mass or a term of its inertia is not a finite number, or so large that their
    products overflow."""
    MASS = "mass"
    """Its mass is not positive."""
    NOT_DEFINITE = "not-definite"
    """Its inertia matrix is not positive definite."""
    TRIANGLE = "triangle"
    """A principal moment is larger than the other two together."""


def mass_sphere_diameter(mass: float) -> float:
    """The diameter (m) of a ball of lead (:data:`LEAD_DENSITY`) of ``mass`` kg:
    ``2 * cbrt(3 m / (4 pi 11340))``. A negative mass gives the ball of its size (RViz
    scales its sphere by a negative diameter, which draws the same ball); 0 gives 0."""
    volume = abs(mass) / LEAD_DENSITY
    return 2.0 * float((0.75 * volume / math.pi) ** (1.0 / 3.0))  # (math.cbrt: 3.11 on)


def equivalent_box(inertial: Inertial) -> EquivalentBox | None:
    """The box RViz draws for ``inertial``'s inertia, or None where it draws none.

    With principal moments I1, I2, I3 (kg*m^2) and mass m (kg), the box's sides are
    ``sqrt(6 (I2 + I3 - I1) / m)`` and its two cyclic permutations (m), each along the
    axis of its moment: a uniform box of sides a, b, c has the moments m (b^2 + c^2) / 12,
    and so on. There is no box (None) when the mass is not positive, the inertia matrix
    is not positive definite (its leading minors, ixx, ixx iyy - ixy^2 and the determinant,
    not all positive), or a principal moment is larger than the other two together (beyond
    rounding): no solid has such an inertia.
    """
    found = _box(inertial)
    return found if isinstance(found, EquivalentBox) else None


def why_no_box(inertial: Inertial) -> NoBox | None:
    """Why ``inertial`` has no equivalent box (see `equivalent_box`), or None when it has
    one: the first of its mass and inertia's faults that RViz (gz-math) tests for."""
    found = _box(inertial)
    return found if isinstance(found, NoBox) else None


def _box(inertial: Inertial) -> EquivalentBox | NoBox:
    mass = inertial.mass
    i = inertial.inertia
    m = i.matrix()
    if not all(math.isfinite(x) for x in (mass, *m[0], *m[1], *m[2])):
        return NoBox.NOT_FINITE
    if not mass > 0.0:
        return NoBox.MASS
    minor, determinant = i.ixx * i.iyy - i.ixy * i.ixy, _determinant(m)
    if not (math.isfinite(minor) and math.isfinite(determinant)):
        return NoBox.NOT_FINITE  # products overflow: RViz's doubles find no box either
    if not (i.ixx > 0.0 and minor > 0.0 and determinant > 0.0):
        return NoBox.NOT_DEFINITE
    largest = max(i.ixx, i.iyy, i.izz)
    if all(abs(p) <= _ON_AXES * largest for p in (i.ixy, i.ixz, i.iyz)):
        moments: Vector3 = (i.ixx, i.iyy, i.izz)
        axes = IDENTITY
    else:
        moments, axes = eigh(m)
    a, b, c = moments
    slack = _ROUNDING * 0.5 * abs(a + b + c)
    if min(moments) + slack < 0.0:
        return NoBox.NOT_DEFINITE
    if a + b + slack < c or b + c + slack < a or c + a + slack < b:
        return NoBox.TRIANGLE
    size = (_side(b + c - a, mass), _side(c + a - b, mass), _side(a + b - c, mass))
    return EquivalentBox(size, axes, moments)


def _side(twice: float, mass: float) -> float:
    # (A difference within rounding of 0, let through above, is a side of 0.)
    return math.sqrt(max(6.0 * twice / mass, 0.0))


def _determinant(m: Matrix3) -> float:
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )
