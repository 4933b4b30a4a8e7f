"""MuJoCo's refusals of the MJCF `fishbot mjcf` writes, foretold without writing it: the
bodies it refuses (`mjcf-refused`), and the inertials the converter moves to a body that
can hold them (`mjcf-joined-inertial`). The converter reports the same findings, from the
same facts (`fishbot_urdf.analysis.mujoco`)."""

from __future__ import annotations

from collections.abc import Iterator

from ..analysis import Analysis
from ..analysis.mujoco import Base, MujocoBodies, mujoco_bodies, no_tree, own, refused
from ..catalog import Rule
from ..catalog.physics import MJCF_JOINED_INERTIAL, MJCF_REFUSED
from ..diagnostics import Diagnostic, Kind, Subject
from ..errors import FishbotUrdfError
from ..model import Link

__all__ = ["REPORTS", "joining", "mjcf_findings", "predict", "refusal"]


def predict(analysis: Analysis, base: Base = "auto") -> Iterator[Diagnostic]:
    """What MuJoCo will refuse of the MJCF of ``analysis`` (with its base held as ``base``
    says), and the inertials its conversion moves; nothing for a robot MJCF cannot hold as a
    tree (the structure rules report why)."""
    if no_tree(analysis) is not None:
        return
    try:
        bodies = mujoco_bodies(analysis, base)
    except FishbotUrdfError:  # no kinematic plan: the structure rules' finding
        return
    yield from mjcf_findings(analysis, bodies)


def mjcf_findings(analysis: Analysis, bodies: MujocoBodies) -> Iterator[Diagnostic]:
    """The findings of ``bodies``: each inertial joined to another body's, then each body
    MuJoCo refuses."""
    for link, holder in bodies.joined.items():
        yield joining(analysis, analysis.links[link], holder)
    for link, why in bodies.refusals:
        yield refusal(analysis, link, why)


def joining(analysis: Analysis, link: Link, holder: str) -> Diagnostic:
    """`link`'s inertial, which MuJoCo refuses on a body of its own, joins ``holder``'s."""
    inertial = link.inertial
    assert inertial is not None
    why = refused(own(inertial))
    return MJCF_JOINED_INERTIAL.report(
        f"link {link.name!r}: {why}, which MuJoCo refuses on a body of its own: its "
        f"inertial joins that of {holder!r}, to which it is fixed",
        inertial.source,
        path=analysis.path,
        subject=Subject(Kind.LINK, link.name),
        hint="give it the inertia of its shape",
        element="inertial",
    )


def refusal(analysis: Analysis, name: str, why: str) -> Diagnostic:
    """The body of link ``name``, which MuJoCo will refuse for ``why``."""
    link = analysis.links[name]
    where = link.inertial.source if link.inertial is not None else link.source
    return MJCF_REFUSED.report(
        f"link {name!r}: {why}: MuJoCo refuses the model",
        where,
        path=analysis.path,
        subject=Subject(Kind.LINK, name),
        hint="give it the mass and inertia of its shape",
    )


REPORTS: tuple[Rule, ...] = (MJCF_JOINED_INERTIAL, MJCF_REFUSED)
"""Every rule this module's check may report: the check runs only when one is selected."""
