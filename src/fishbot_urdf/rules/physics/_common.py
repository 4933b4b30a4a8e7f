"""What the physics rules share: tolerances, number formats, and how a finding is made."""

from __future__ import annotations

from ...diagnostics import Kind, Subject
from ...model import Link, Location

# MuJoCo refuses a moving body whose mass or a principal moment is below this (mjMINVAL).
TINY = 1e-15


def tolerance(moments: tuple[float, float, float]) -> float:
    # Inertias are printed with a handful of digits: allow their rounding, and nothing near
    # a real violation.
    return max(1e-6 * max(abs(moments[0]), abs(moments[1]), abs(moments[2])), TINY)


def physical(moments: tuple[float, float, float], tol: float | None = None) -> bool:
    """Moments no lower than zero that obey the triangle inequality (within rounding;
    ``tol``: their `tolerance`, when known)."""
    if tol is None:
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
