"""The inertial of each MJCF body: its link's own, as written, unless MuJoCo would refuse it
on a body of its own (a link on a fixed joint whose inertia is no solid's), which then joins
the inertial of the body it is fixed to, summed exactly."""

from __future__ import annotations

from collections.abc import Mapping
from typing import NamedTuple

from ..analysis import Analysis
from ..model import Inertial, JointType, Vector3
from ..spatial import (
    Matrix3,
    Pose,
    add,
    eigenvalues,
    eigh,
    mat_add,
    point_mass_tensor,
    rotate_tensor,
    rpy_matrix,
    scale,
)

__all__ = ["Mass", "masses", "own", "principal", "refused"]

_ZERO: Matrix3 = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


class Mass(NamedTuple):
    """A body's inertial: mass (kg), centre of mass (m) and inertia about it (kg*m^2), both
    in the body's frame; ``joined`` names the links whose inertials were added to its own."""

    mass: float
    centre: Vector3
    tensor: Matrix3
    joined: tuple[str, ...] = ()


_NONE = Mass(0.0, (0.0, 0.0, 0.0), _ZERO)
"""No mass at all."""


def own(inertial: Inertial) -> Mass:
    """A link's inertial in its own frame."""
    i = inertial.inertia
    tensor = ((i.ixx, i.ixy, i.ixz), (i.ixy, i.iyy, i.iyz), (i.ixz, i.iyz, i.izz))
    turned = rotate_tensor(rpy_matrix(inertial.origin.rpy), tensor)
    return Mass(inertial.mass, inertial.origin.xyz, turned)


def principal(tensor: Matrix3) -> tuple[Vector3, Matrix3]:
    """The principal moments of ``tensor`` and its principal axes, as the columns of a
    rotation (right-handed)."""
    moments, axes = eigh(tensor)
    (a, b, c), (d, e, f), (g, h, i) = axes
    if a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g) < 0.0:
        axes = ((a, b, -c), (d, e, -f), (g, h, -i))  # the third axis turned round
    return moments, axes


def refused(mass: Mass) -> str | None:
    """Why MuJoCo refuses ``mass`` on a body (its inertia is not positive semi-definite, or
    its principal moments break the triangle inequality), or None."""
    a, b, c = eigenvalues(mass.tensor)  # smallest first
    if a < 0.0:
        return "its inertia is not positive definite"
    if a + b < c:
        return "its principal moments break the triangle inequality (A + B >= C)"
    return None


def _sum(into: Mass, part: Mass, at: Pose, name: str) -> Mass:
    """``into`` with ``part`` (given in the frame ``at`` places in ``into``'s) added."""
    centre = at.apply(part.centre)
    tensor = rotate_tensor(at.rotation, part.tensor)
    total = into.mass + part.mass
    if total == 0.0:
        return into._replace(joined=(*into.joined, name, *part.joined))
    middle = scale(add(scale(into.centre, into.mass), scale(centre, part.mass)), 1.0 / total)
    summed = mat_add(
        mat_add(into.tensor, point_mass_tensor(into.mass, _minus(into.centre, middle))),
        mat_add(tensor, point_mass_tensor(part.mass, _minus(centre, middle))),
    )
    return Mass(total, middle, summed, (*into.joined, name, *part.joined))


def _minus(a: Vector3, b: Vector3) -> Vector3:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def masses(analysis: Analysis) -> tuple[Mapping[str, Mass], Mapping[str, str]]:
    """Each body's inertial (by link; a body without one has none), and each link whose
    inertial joined another body's, with that body.

    Children first: a link whose inertial, with those that joined it, MuJoCo refuses joins
    its parent's when a fixed joint holds it to a link (and so on up), else the first of its
    children on a fixed joint whose sum with it MuJoCo takes (a root's placeholder inertia
    joins its base's); both move together, so the sum is the same body's."""
    plan = analysis.plan
    steps = {plan.links[s.link]: s for s in plan.steps}
    below: dict[str, list[tuple[Mass, Pose, str]]] = {}  # what joins each link
    found: dict[str, Mass] = {}
    moved: dict[str, str] = {}  # link -> the link its inertial joined
    for link in reversed(plan.links):
        inertial = analysis.links[link].inertial
        mass = own(inertial) if inertial is not None and inertial.mass != 0.0 else None
        for part, at, name in below.pop(link, ()):
            mass = _sum(mass or _NONE, part, at, name)
        if mass is None:
            continue
        if refused(mass) is not None:
            step = steps.get(link)
            parent = None if step is None else plan.links[step.parent]
            if step is not None and step.kind is JointType.FIXED and parent != "world":
                assert parent is not None
                below.setdefault(parent, []).append((mass, step.origin, link))
                moved[link] = parent
                continue
            child = _down(analysis, link, mass, found, moved)
            if child is not None:
                moved[link] = child
                continue
        found[link] = mass
    joined = {}
    for link in moved:
        body = link
        while body in moved:
            body = moved[body]
        joined[link] = body
    return found, joined


def _down(
    analysis: Analysis,
    link: str,
    mass: Mass,
    found: dict[str, Mass],
    moved: Mapping[str, str],
) -> str | None:
    """The first child of ``link`` on a fixed joint whose inertial, with ``mass`` added, is
    one MuJoCo takes (``found`` then holds the sum), or None."""
    plan = analysis.plan
    for joint in analysis.topology.children[link]:
        child = joint.child
        if joint.type is not JointType.FIXED or child in moved or child not in plan.index:
            continue
        if analysis.parent_joint.get(child) is not joint:
            continue
        summed = _sum(found.get(child, _NONE), mass, Pose.of(joint.origin).inverse(), link)
        if refused(summed) is None:
            found[child] = summed
            return child
    return None
