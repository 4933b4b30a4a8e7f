"""What the physics rules share: tolerances, number formats, and how a finding is made."""

from __future__ import annotations

from ...diagnostics import Kind, Severity, Subject
from ...model import Link, Location
from .. import Consumer, Family, Rule

# MuJoCo refuses a moving body whose mass or a principal moment is below this (mjMINVAL).
TINY = 1e-15


def tolerance(moments: tuple[float, float, float]) -> float:
    # Inertias are printed with a handful of digits: allow their rounding, and nothing near
    # a real violation.
    return max(1e-6 * max(abs(m) for m in moments), TINY)


def physical(moments: tuple[float, float, float]) -> bool:
    """Moments no lower than zero that obey the triangle inequality (within rounding)."""
    tol = tolerance(moments)
    return moments[0] >= -tol and moments[0] + moments[1] >= moments[2] - tol


def short(value: float) -> str:
    """A length or moment, short: 0.10, 0.12, 0.032, 3.9e-05."""
    if value == 0.0:
        return "0"
    return f"{value:.2f}" if abs(value) >= 0.1 else f"{value:.2g}"


def moments_text(values: tuple[float, float, float]) -> str:
    """Principal moments for a message; rounding noise (-1e-22 next to 3e-06) shows as 0."""
    return ", ".join(moment_text(v, values) for v in values)


def moment_text(value: float, values: tuple[float, float, float]) -> str:
    return "0" if abs(value) <= tolerance(values) else f"{value:.3g}"


def place(link: Link, where: Location | None) -> Location | None:
    """Where to report about a part of ``link``: the part itself, unless a xacro macro from
    another file wrote it (common_inertia.xacro's inertia, say); then the link, which is
    near the macro's call."""
    if where is None or link.source is None or where.path == link.source.path:
        return where or link.source
    return link.source


def link_subject(link: Link) -> Subject:
    return Subject(Kind.LINK, link.name)


_SIMULATORS = (Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
E, W = Severity.ERROR, Severity.WARNING

MASSLESS_LINK = Rule(
    "massless-link",
    E,
    Family.PHYSICS,
    summary="A moving body (links fused over fixed joints) has no mass or no inertia about "
    "some axis.",
    consumers=_SIMULATORS,
)
INERTIA_NOT_POSITIVE = Rule(
    "inertia-not-positive",
    E,
    Family.PHYSICS,
    summary="An inertia has a negative principal moment.",
    consumers=_SIMULATORS,
)
INERTIA_TRIANGLE = Rule(
    "inertia-triangle",
    E,
    Family.PHYSICS,
    summary="One principal moment is larger than the other two together.",
    consumers=(Consumer.MUJOCO, Consumer.DRAKE),
)
MISSING_INERTIAL = Rule(
    "missing-inertial",
    W,
    Family.PHYSICS,
    summary="A moving link, or the robot's base, has collision shapes but no <inertial>.",
    consumers=(Consumer.GAZEBO, Consumer.MUJOCO, Consumer.PYBULLET),
)
INERTIA_MISMATCH = Rule(
    "inertia-mismatch",
    W,
    Family.PHYSICS,
    summary="An inertia is that of another shape than the link's one collision box, "
    "cylinder or sphere.",
    consumers=_SIMULATORS,
)
BELOW_GROUND = Rule(
    "below-ground",
    W,
    Family.PHYSICS,
    summary="A collision shape reaches below the ground (z = 0 of a footprint root).",
    consumers=(Consumer.GAZEBO, Consumer.PYBULLET),
)
ABOVE_GROUND = Rule(
    "above-ground",
    W,
    Family.PHYSICS,
    summary="The robot's lowest point is above the ground (z = 0 of a footprint root): it floats.",
    consumers=(Consumer.GAZEBO, Consumer.PYBULLET),
)
