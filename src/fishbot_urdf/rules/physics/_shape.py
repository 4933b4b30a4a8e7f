"""An inertia against the link's own collision box, cylinder or sphere."""

from __future__ import annotations

import math
from itertools import chain
from operator import sub

from ...catalog.physics import INERTIA_MISMATCH, ROBOT_UNITS, CollisionFacts
from ...diagnostics import Diagnostic
from ...inertia import solid_moments
from ...model import Box, Cylinder, Link, Origin, Sphere, Vector3
from ...spatial import (
    IDENTITY,
    Matrix3,
    diagonal,
    eigenvalues,
    rotate_tensor,
    rpy_matrix,
    transpose,
)
from ._common import TINY, link_subject, place, short, tolerance

MISMATCH = 0.10
"""How far (relative to the largest moment) an inertia may be from its collision shape's."""


def mismatch(
    link: Link, path: str, moments: Vector3, *, millimetres: bool = False
) -> Diagnostic | None:
    """The inertia against the link's one collision box, cylinder or sphere (None: it fits,
    or there is nothing to compare). When the robot reads as ``millimetres``, the finding
    says to scale it first, and follows from that one (`robot-units`).

    Otherwise the finding's data names the collision's shape (``shape``: box, cylinder or sphere,
    with ``size`` or ``radius`` and ``length``), the ``mass``, and the collision origin's
    ``xyz`` and ``rpy``: what it takes to compute the inertial that matches it.
    """
    inertial = link.inertial
    if inertial is None or len(link.collisions) != 1 or not inertial.mass > 0:
        return None
    collision = link.collisions[0]
    shape = collision.geometry
    if not isinstance(shape, Box | Cylinder | Sphere):
        return None
    if moments[0] < -tolerance(moments) or moments[2] <= TINY:
        return None  # reported as not positive definite, or a point mass
    closed = solid_moments(shape, inertial.mass)  # in the collision's frame, where it is diagonal
    largest = max(closed)
    if largest <= 0.0:
        return None
    i = inertial.inertia
    own = rpy_matrix(inertial.origin.rpy)
    turn = rpy_matrix(collision.origin.rpy)
    if own is IDENTITY and turn is IDENTITY:  # the common case: both in the link's frame
        seen = None
        gap = max(
            abs(i.ixx - closed[0]),
            abs(i.iyy - closed[1]),
            abs(i.izz - closed[2]),
            abs(i.ixy),
            abs(i.ixz),
            abs(i.iyz),
        )
    else:
        declared = rotate_tensor(own, i.matrix())
        if own is not IDENTITY and not all(map(math.isfinite, chain(*declared))):
            return None  # turned, numbers past the floats' range: nothing to compare
        wanted = rotate_tensor(turn, diagonal(closed))
        gap = max(map(abs, map(sub, chain(*declared), chain(*wanted))))
        # What the numbers are, seen in the collision's own frame.
        seen = declared if turn is IDENTITY else rotate_tensor(transpose(turn), declared)
    if gap <= MISMATCH * largest:
        return None
    # Numbers that fit no shape of the collision's kind were measured (CAD), not computed: a
    # collision shape only approximates those.
    found = _describe(shape, seen or i.matrix(), inertial.mass, turn)
    if found is None:
        return None
    owner = link_subject(link)
    if millimetres:  # no inertial to propose for a box of 200 m: the lengths come first
        return INERTIA_MISMATCH.report(
            f"{owner}: {found}",
            place(link, inertial.source),
            path=path,
            subject=owner,
            hint="the robot reads as written in millimetres: multiply its lengths by 0.001 "
            "first, then compare",
            follows=(ROBOT_UNITS.id,),
        )
    return INERTIA_MISMATCH.report(
        f"{owner}: {found}",
        place(link, inertial.source),
        path=path,
        subject=owner,
        hint="fix the one that is wrong",
        data=_collision_facts(shape, inertial.mass, collision.origin),
    )


def _collision_facts(shape: Box | Cylinder | Sphere, mass: float, origin: Origin) -> CollisionFacts:
    """What it takes to compute the inertial that matches the collision."""
    size = shape.size if isinstance(shape, Box) else None
    length = shape.length if isinstance(shape, Cylinder) else None
    radius = None if isinstance(shape, Box) else shape.radius
    kind = "box" if size is not None else "cylinder" if length is not None else "sphere"
    return CollisionFacts(
        shape=kind,
        mass=mass,
        xyz=origin.xyz,
        rpy=origin.rpy,
        size=size,
        radius=radius,
        length=length,
    )


def _off_diagonal(m: Matrix3) -> bool:
    scale = max(abs(m[0][0]), abs(m[1][1]), abs(m[2][2]))
    return max(abs(m[0][1]), abs(m[0][2]), abs(m[1][2])) > 1e-3 * scale


def _axis(turn: Matrix3, index: int) -> str:
    """The link axis closest to the collision frame's axis ``index``."""
    column = [turn[k][index] for k in range(3)]
    best = max(range(3), key=lambda k: abs(column[k]))
    if abs(column[best]) > math.cos(math.radians(5)):
        return "xyz"[best]
    return "(" + " ".join(f"{c:.2f}" for c in column) + ")"


def _differs(a: float, b: float) -> bool:
    return abs(a - b) > 0.05 * max(abs(a), abs(b)) and short(a) != short(b)


def _describe(
    shape: Box | Cylinder | Sphere, seen: Matrix3, mass: float, turn: Matrix3
) -> str | None:
    """Which shape of the collision's kind the declared inertia (in the collision's frame)
    matches, against the collision itself; None when it matches none."""
    if isinstance(shape, Sphere):
        moments = eigenvalues(seen)
        radius = math.sqrt(max(0.0, 5.0 * sum(moments) / 3.0 / (2.0 * mass)))
        if moments[2] - moments[0] <= MISMATCH * moments[2] and _differs(radius, shape.radius):
            return (
                f"inertial matches a sphere r={short(radius)}, "
                f"but the collision sphere has r={short(shape.radius)}"
            )
        return None
    if _off_diagonal(seen):
        return None
    on_diagonal = (seen[0][0], seen[1][1], seen[2][2])
    if isinstance(shape, Box):
        total = on_diagonal[0] + on_diagonal[1] + on_diagonal[2]
        xx = 6.0 * (total - 2.0 * on_diagonal[0]) / mass
        yy = 6.0 * (total - 2.0 * on_diagonal[1]) / mass
        zz = 6.0 * (total - 2.0 * on_diagonal[2]) / mass
        if xx < 0 or yy < 0 or zz < 0:
            return None
        x, y, z = math.sqrt(xx), math.sqrt(yy), math.sqrt(zz)
        w, h, d = shape.size
        return (
            f"inertial matches a box {short(x)} x {short(y)} x {short(z)}, "
            f"but the collision box is {short(w)} x {short(h)} x {short(d)}"
        )
    # A cylinder: its axis is where the odd moment out is; with three equal moments
    # (1, 1, 1, a placeholder) any axis fits, and only the size can be wrong.
    equal = max(on_diagonal) - min(on_diagonal) <= MISMATCH * max(on_diagonal)
    k = (
        2
        if equal
        else min(range(3), key=lambda i: abs(on_diagonal[(i + 1) % 3] - on_diagonal[(i + 2) % 3]))
    )
    across = (on_diagonal[(k + 1) % 3] + on_diagonal[(k + 2) % 3]) / 2.0
    if abs(on_diagonal[(k + 1) % 3] - on_diagonal[(k + 2) % 3]) > MISMATCH * across:
        return None
    radius = math.sqrt(max(0.0, 2.0 * on_diagonal[k] / mass))  # rounding may leave -1e-17
    square = 12.0 * across / mass - 3.0 * radius * radius
    if square < 0:
        return None
    length = math.sqrt(square)
    found = f"inertial matches a cylinder r={short(radius)} h={short(length)}"
    if equal:
        found += " (its three moments are equal, so along any axis)"
    if k != 2:
        return (
            f"{found} along the link's {_axis(turn, k)} axis, "
            f"but the collision cylinder lies along its {_axis(turn, 2)} axis"
        )
    wrong = [
        f"{name}={short(real)}"
        for name, fit, real in (("r", radius, shape.radius), ("h", length, shape.length))
        if _differs(fit, real)
    ]
    if not wrong:
        return None
    return f"{found}, but the collision cylinder has {' '.join(wrong)}"
