"""Mass and inertia, link by link and body by body (links fused over fixed joints)."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping

from ...analysis import Body
from ...catalog.physics import (
    INERTIA_NOT_POSITIVE,
    INERTIA_TRIANGLE,
    MASSLESS_LINK,
    MISSING_INERTIAL,
    InertiaFacts,
    MassFacts,
    W,
)
from ...catalog.reading import BAD_NUMBER, NEGATIVE_MASS
from ...diagnostics import Diagnostic
from ...inertia import combine
from ...model import Inertial, Joint, Link, Vector3
from ...spatial import Pose
from ._common import TINY, link_subject, moment_text, moments_text, physical, place, tolerance

# The reading rules this module reports are about the inertial alone (Diagnostic.element).


def finite(inertial: Inertial) -> bool:
    i = inertial.inertia
    return all(map(math.isfinite, (inertial.mass, i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz)))


def _inertials(body: Body) -> list[tuple[Link, Inertial, Pose]]:
    """The members that have an inertial, with it."""
    return [(link, link.inertial, pose) for link, pose in body.members if link.inertial]


def body_findings(
    body: Body,
    path: str,
    moments: Mapping[str, Vector3],
    jointed: bool,
    *,
    millimetres: bool = False,
    lost: tuple[str, ...] = (),
) -> Iterator[Diagnostic]:
    """The findings about one body's masses and inertias (``millimetres``: the robot reads
    as written in millimetres, so an inertial is computed from its shapes only once they are
    in metres; ``lost``: the links Gazebo leaves out below the body for its lack of mass)."""
    having = _inertials(body)
    all_finite = all(link.name in moments for link, _, _ in having)
    # Fused with its fixed neighbours a body may be physical although one link's own numbers
    # are not: simulators that merge fixed links load it, so that is only a warning.
    merged = (
        all_finite
        and len(having) > 1
        and physical(combine((inertial, pose) for _, inertial, pose in having).principal_moments)
    )
    for link, inertial, _ in having:
        own = moments.get(link.name)
        if own is None or inertial.mass < 0 or not physical(own):  # (seldom)
            yield from _inertial(link, inertial, path, merged, own)
    if all_finite:
        yield from _moving(body, having, path, moments, jointed, millimetres, lost)


def _inertial(
    link: Link, inertial: Inertial, path: str, merged: bool, moments: Vector3 | None
) -> Iterator[Diagnostic]:
    if moments is None:  # not finite
        owner = link_subject(link)
        yield BAD_NUMBER.report(
            f"{owner}: the mass or inertia is not finite",
            inertial.source,
            path=path,
            subject=owner,
            hint="write finite numbers",
            element="inertial",
        )
        return
    if inertial.mass < 0:
        owner = link_subject(link)
        yield NEGATIVE_MASS.report(
            f"{owner}: mass {inertial.mass:g} kg is negative",
            inertial.source,
            path=path,
            subject=owner,
            hint="mass is >= 0 kg",
            element="inertial",
        )
    tol = tolerance(moments)
    negative = moments[0] < -tol
    if not negative and physical(moments, tol):
        return
    owner = link_subject(link)
    where = place(link, inertial.inertia.source or inertial.source)
    also = (
        "; merged with the links fixed to it the body is physical, so simulators that merge "
        "fixed links load it, but the numbers are still wrong"
        if merged
        else ""
    )
    facts = InertiaFacts(principal_moments=moments, merged_body_physical=merged)
    if negative:
        # A negative moment written in the file is a sign slip, merged or not.
        slip = any(getattr(inertial.inertia, f) < 0 for f in ("ixx", "iyy", "izz"))
        yield INERTIA_NOT_POSITIVE.report(
            f"{owner}: the inertia is not positive definite: principal moments "
            f"{moments_text(moments)} kg*m^2",
            where,
            path=path,
            subject=owner,
            hint=_negative_hint(inertial) + ("" if slip else also),
            severity=None if slip or not merged else W,
            data=facts,
        )
    else:
        yield INERTIA_TRIANGLE.report(
            f"{owner}: principal moments {moments_text(moments)} kg*m^2 break the triangle "
            f"inequality ({moment_text(moments[0], moments)} + {moment_text(moments[1], moments)} "
            f"< {moment_text(moments[2], moments)})",
            where,
            path=path,
            subject=owner,
            hint="no rigid body has one moment larger than the other two together; "
            "MuJoCo refuses it" + also,
            severity=W if merged else None,
            data=facts,
        )


def _negative_hint(inertial: Inertial) -> str:
    negative = [f for f in ("ixx", "iyy", "izz") if getattr(inertial.inertia, f) < 0]
    if negative:
        listed = ", ".join(f"{f}={getattr(inertial.inertia, f):g}" for f in negative)
        return f"moments of inertia are >= 0, but {listed}"
    return "the products ixy, ixz, iyz are too large for the moments ixx, iyy, izz"


def _moves(joint: Joint) -> str:
    return f"moves (joint {joint.name!r} is {joint.type.value})"


def _moving(
    body: Body,
    having: list[tuple[Link, Inertial, Pose]],
    path: str,
    moments: Mapping[str, Vector3],
    jointed: bool,
    millimetres: bool,
    lost: tuple[str, ...],
) -> Iterator[Diagnostic]:
    joint = body.moved_by
    below = ", ".join(repr(name) for name in lost if name != body.base.name)
    # what Gazebo loses with it (gazebo-dropped-link reports only what these rules do not)
    with_it = f" ({below})" if below else ""
    shapes = "collision shapes" + (" once they are in metres" if millimetres else "")
    # A body without inertial: its first link with collision shapes, if any.
    link = None if having else next((link for link, _ in body.members if link.collisions), None)
    if joint is None:
        # The root's body: a mobile robot's base, unless the robot is bolted to the world.
        if link is not None and body.base.name != "world" and jointed:
            yield MISSING_INERTIAL.report(
                f"link {link.name!r} has collision geometry but no <inertial>, and nothing "
                "it is fixed to has one: the robot's base weighs nothing",
                link.source,
                path=path,
                subject=link_subject(link),
                hint="Gazebo drops a link without an inertial; give it one computed from its "
                + shapes,
            )
        return
    if not having:
        if link is not None:
            yield MISSING_INERTIAL.report(
                f"link {link.name!r} has collision geometry and {_moves(joint)} but no <inertial>",
                link.source,
                path=path,
                subject=link_subject(link),
                hint=f"Gazebo drops it with everything below it{with_it}, as it drops one of "
                "mass 0; "
                "give it one computed from its " + shapes,
            )
        return
    if any(inertial.mass < 0 for _, inertial, _ in having):
        return  # reported as a negative mass
    first_link, first, _ = having[0]
    if len(having) == 1:  # the link alone: its own mass and moments
        mass, principal = first.mass, moments[first_link.name]
    else:
        together = combine((inertial, pose) for _, inertial, pose in having)
        mass, principal = together.mass, together.principal_moments
    flat = -tolerance(principal) <= principal[0] <= TINY
    if mass > TINY and not flat:
        return  # (the most common case, so the words below are made only when needed)
    moves, owner = _moves(joint), link_subject(body.base)
    if mass <= TINY:
        yield MASSLESS_LINK.report(
            f"{owner} {moves} but its mass is {mass:g} kg",
            place(first_link, first.source),
            path=path,
            subject=owner,
            hint="a moving body needs a mass (MuJoCo: above 1e-15)"
            + (f"; Gazebo drops it with everything below it{with_it}" if below else "")
            + "; give its real mass",
            data=MassFacts(mass=mass),
        )
    else:  # flat
        # (below that the link's own inertia is reported as not positive definite)
        yield MASSLESS_LINK.report(
            f"{owner} {moves} but has no inertia about some axis: principal moments "
            f"{moments_text(principal)} kg*m^2",
            place(first_link, first.source),
            path=path,
            subject=owner,
            hint="a moving body needs every moment above 1e-15 kg*m^2 (MuJoCo refuses it "
            "otherwise); compute them from the body's shape",
            data=MassFacts(mass=mass, principal_moments=principal),
        )
