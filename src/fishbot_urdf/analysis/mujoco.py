"""The bodies MuJoCo makes of a robot's links, one body per link, and what it refuses of them:
each body's inertial (its link's own, as written, unless MuJoCo would refuse it on a body of
its own, which then joins the inertial of a body it is fixed to, summed exactly), which
bodies move, and which MuJoCo refuses. Owned here, so that the MJCF converter writes them
and the check foretells its refusals from the same facts, without writing the MJCF."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Literal, NamedTuple

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
from . import Analysis

__all__ = [
    "BASES",
    "Base",
    "Mass",
    "MujocoBodies",
    "masses",
    "moves",
    "mujoco_bodies",
    "no_tree",
    "own",
    "principal",
    "refused",
]

Base = Literal["auto", "fixed", "floating"]
BASES: tuple[Base, ...] = ("auto", "fixed", "floating")
"""How the robot's base may be held: as the robot says, fixed to the world, or free."""

WORLD = "world"
LEAST_MASS = 1e-15  # MuJoCo's mjMINVAL: a moving body's mass must be above it

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
            if step is not None and step.kind is JointType.FIXED and parent != WORLD:
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


def no_tree(analysis: Analysis) -> str | None:
    """Why MuJoCo cannot name the robot's links and joints, or build them as a tree of
    bodies (a name used twice, a joint loop), or None."""
    robot = analysis.robot
    if len(analysis.links) != len(robot.links) or len(analysis.joints) != len(robot.joints):
        return "a link or joint name used twice, which MJCF refuses"
    if analysis.loops:
        return "a joint loop, which no tree of bodies holds"
    return None


def moves(kind: JointType, *, top: bool, base: Base) -> bool:
    """Whether the body a joint of ``kind`` places has joints of its own in MuJoCo: a fixed
    joint gives none (but a free one, for a child of ``world`` whose base floats), a
    floating one from ``world`` none when the base is fixed."""
    if kind is JointType.FIXED:
        return top and base == "floating"
    if kind is JointType.FLOATING:
        return not (top and base == "fixed")
    return True


class MujocoBodies(NamedTuple):
    """The bodies MuJoCo makes of a robot's links (see `mujoco_bodies`)."""

    masses: Mapping[str, Mass]
    """Each body's inertial, by link (a body without one has none)."""
    joined: Mapping[str, str]
    """Each link whose inertial joined another body's, with that body."""
    moving: tuple[str, ...]
    """The links whose bodies have joints (a free joint included)."""
    refusals: tuple[tuple[str, str], ...]
    """Each body MuJoCo refuses, by link, and why."""


def mujoco_bodies(analysis: Analysis, base: Base = "auto") -> MujocoBodies:
    """The bodies MuJoCo makes of ``analysis``'s links held as ``base`` says (``auto``: a
    root other than ``world`` is free, ``fixed``: fixed to the world, ``floating``: free, and
    each child of ``world`` too), and those it refuses: an inertia no solid has that no link
    fixed to it can take, and a moving body that, with the bodies fixed to it, has no mass.

    Raises:
        FishbotUrdfError: The robot has no kinematic plan (see `Analysis.plan`).
    """
    plan = analysis.plan
    found, joined = masses(analysis)
    moving = [root for root in plan.roots if root != WORLD and base != "fixed"]
    welded: dict[str, list[tuple[str, Pose]]] = {}  # the bodies fixed to each, and where
    for step in plan.steps:
        parent, link = plan.links[step.parent], plan.links[step.link]
        if moves(step.kind, top=parent == WORLD, base=base):
            moving.append(link)
        elif parent != WORLD:
            welded.setdefault(parent, []).append((link, step.origin))
    refusals = []
    for name, mass in found.items():
        why = refused(mass)
        if why is not None:
            refusals.append((name, f"{why}, and nothing fixed to it can take it"))
    # MuJoCo judges a moving body with the bodies fixed to it (and to them): children first
    together: dict[str, Mass] = {}
    for link in reversed(plan.links):
        total = found.get(link, _NONE)
        for child, at in welded.pop(link, ()):
            total = _sum(total, together[child], at, child)
        together[link] = total
    for name in moving:
        why = _massless(together[name])
        if why is not None:
            refusals.append((name, f"it moves, and {why}"))
    return MujocoBodies(found, joined, tuple(moving), tuple(refusals))


def _massless(mass: Mass) -> str | None:
    """Why MuJoCo refuses ``mass`` on a moving body (with the bodies fixed to it): its mass,
    or a principal moment, not above mjMINVAL; or None."""
    if mass.mass < LEAST_MASS:
        return "neither it nor a link fixed to it has mass"
    moments = eigenvalues(mass.tensor)  # smallest first
    if moments[0] < LEAST_MASS:
        shown = ", ".join(f"{m:.3g}" for m in moments)
        return f"with the links fixed to it it has no inertia about some axis ({shown} kg*m^2)"
    return None
