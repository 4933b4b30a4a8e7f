"""Mass and inertia, link by link and body by body (links fused over fixed joints)."""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import NamedTuple

from ..diagnostics import Diagnostic
from ..inertia import combine
from ..model import Inertial, JointType, Link, Robot, Vector3
from ..spatial import Pose
from ._common import TINY, moment_text, moments_text, physical, place, report, tolerance


class _Body(NamedTuple):
    """Links welded together by fixed joints, and how each sits in the first one's frame."""

    base: Link
    members: tuple[tuple[Link, Pose], ...]
    moved_by: str | None  # the joint that moves the body, None for a root body
    joint_type: JointType | None

    @property
    def inertials(self) -> list[tuple[Link, Inertial, Pose]]:
        """The members that have an inertial, with it."""
        return [(link, link.inertial, pose) for link, pose in self.members if link.inertial]


def bodies(robot: Robot) -> list[_Body]:
    by_name = {link.name: link for link in robot.links}
    fixed_below: dict[str, list[tuple[str, Pose]]] = {}
    parent_joint: dict[str, tuple[str, JointType]] = {}
    for joint in robot.joints:
        if joint.child in parent_joint or joint.child not in by_name:
            continue
        parent_joint[joint.child] = (joint.name, joint.type)
        if joint.type is JointType.FIXED:
            fixed_below.setdefault(joint.parent, []).append((joint.child, Pose.of(joint.origin)))
    bodies: list[_Body] = []
    alone = Pose()
    for link in robot.links:
        moved_by, joint_type = parent_joint.get(link.name, (None, None))
        if joint_type is JointType.FIXED:
            continue  # part of its parent's body
        if link.name not in fixed_below:  # the common case: a body of one link
            bodies.append(_Body(link, ((link, alone),), moved_by, joint_type))
            continue
        members: list[tuple[Link, Pose]] = []
        stack = [(link.name, alone)]
        seen: set[str] = set()
        while stack:
            name, pose = stack.pop()
            if name in seen or name not in by_name:
                continue
            seen.add(name)
            members.append((by_name[name], pose))
            stack.extend((child, pose.then(o)) for child, o in fixed_below.get(name, ()))
        bodies.append(_Body(link, tuple(members), moved_by, joint_type))
    return bodies


def finite(inertial: Inertial) -> bool:
    return all(
        math.isfinite(v) for v in (inertial.mass, *(getattr(inertial.inertia, f) for f in _FIELDS))
    )


def body_findings(
    body: _Body, path: str, moments: dict[str, Vector3], jointed: bool
) -> Iterator[Diagnostic]:
    having = body.inertials
    parts = [(inertial, pose) for _, inertial, pose in having]
    finite = all(link.name in moments for link, _, _ in having)
    # Fused with its fixed neighbours a body may be physical although one link's own numbers
    # are not: simulators that merge fixed links load it, so that is only a warning.
    merged = finite and len(parts) > 1 and physical(combine(parts).principal_moments)
    for link, _ in body.members:
        inertial = link.inertial
        if inertial is not None:
            yield from _inertial(link, inertial, path, merged, moments.get(link.name))
    if finite:
        yield from _moving(body, having, path, moments, jointed)


def _inertial(
    link: Link, inertial: Inertial, path: str, merged: bool, moments: Vector3 | None
) -> Iterator[Diagnostic]:
    owner = f"link {link.name!r}"
    if moments is None:  # not finite
        yield report(
            "bad-number",
            f"{owner}: the mass or inertia is not finite",
            inertial.source,
            path,
            "write finite numbers",
        )
        return
    if inertial.mass < 0:
        yield report(
            "negative-mass",
            f"{owner}: mass {inertial.mass:g} kg is negative",
            inertial.source,
            path,
            "mass is >= 0 kg",
        )
    where = place(link, inertial.inertia.source or inertial.source)
    also = (
        "; merged with the links fixed to it the body is physical, so simulators that merge "
        "fixed links load it, but the numbers are still wrong"
        if merged
        else ""
    )
    if moments[0] < -tolerance(moments):
        # A negative moment written in the file is a sign slip, merged or not.
        slip = any(getattr(inertial.inertia, f) < 0 for f in ("ixx", "iyy", "izz"))
        yield report(
            "inertia-not-positive",
            f"{owner}: the inertia is not positive definite: principal moments "
            f"{moments_text(moments)} kg*m^2",
            where,
            path,
            _negative_hint(inertial) + ("" if slip else also),
            error=slip or not merged,
        )
    elif not physical(moments):
        yield report(
            "inertia-triangle",
            f"{owner}: principal moments {moments_text(moments)} kg*m^2 break the triangle "
            f"inequality ({moment_text(moments[0], moments)} + {moment_text(moments[1], moments)} "
            f"< {moment_text(moments[2], moments)})",
            where,
            path,
            "no rigid body has one moment larger than the other two together; "
            "MuJoCo refuses it" + also,
            error=not merged,
        )


_FIELDS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def _negative_hint(inertial: Inertial) -> str:
    negative = [f for f in ("ixx", "iyy", "izz") if getattr(inertial.inertia, f) < 0]
    if negative:
        listed = ", ".join(f"{f}={getattr(inertial.inertia, f):g}" for f in negative)
        return f"moments of inertia are >= 0, but {listed}"
    return "the products ixy, ixz, iyz are too large for the moments ixx, iyy, izz"


def _moving(
    body: _Body,
    having: list[tuple[Link, Inertial, Pose]],
    path: str,
    moments: dict[str, Vector3],
    jointed: bool,
) -> Iterator[Diagnostic]:
    with_shape = [link for link, _ in body.members if link.collisions]
    fill = "`fishbot inertia ROBOT --fill -o OUT` adds one from its geometry"
    if body.moved_by is None or body.joint_type is None:
        # The root's body: a mobile robot's base, unless the robot is bolted to the world.
        if not having and with_shape and body.base.name != "world" and jointed:
            link = with_shape[0]
            yield report(
                "missing-inertial",
                f"link {link.name!r} has collision geometry but no <inertial>, and nothing "
                "it is fixed to has one: the robot's base weighs nothing",
                link.source,
                path,
                f"Gazebo drops a link without an inertial; {fill}",
                error=False,
            )
        return
    moves = f"moves (joint {body.moved_by!r} is {body.joint_type.value})"
    owner = f"link {body.base.name!r}"
    if not having:
        if with_shape:
            link = with_shape[0]
            yield report(
                "missing-inertial",
                f"link {link.name!r} has collision geometry and {moves} but no <inertial>",
                link.source,
                path,
                f"simulators drop a link without mass or cannot move it; {fill}",
                error=False,
            )
        return
    if any(inertial.mass < 0 for _, inertial, _ in having):
        return  # reported as a negative mass
    first = having[0][1]
    if len(having) == 1:  # the link alone: its own mass and moments
        mass, principal = first.mass, moments[having[0][0].name]
    else:
        together = combine((inertial, pose) for _, inertial, pose in having)
        mass, principal = together.mass, together.principal_moments
    if mass <= TINY:
        yield report(
            "massless-link",
            f"{owner} {moves} but its mass is {mass:g} kg",
            place(having[0][0], first.source),
            path,
            "a moving body needs a mass (MuJoCo: above 1e-15); give its real mass",
        )
    elif -tolerance(principal) <= principal[0] <= TINY:
        # (below that the link's own inertia is reported as not positive definite)
        yield report(
            "massless-link",
            f"{owner} {moves} but has no inertia about some axis: principal moments "
            f"{moments_text(principal)} kg*m^2",
            place(having[0][0], first.source),
            path,
            "a moving body needs every moment above 1e-15 kg*m^2 (MuJoCo refuses it otherwise); "
            "compute them with `fishbot inertia box|cylinder|sphere`",
        )
