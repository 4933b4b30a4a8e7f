"""The findings of a conversion to MJCF: what it changed or left out, and what MuJoCo will
refuse of the model it wrote."""

from __future__ import annotations

import os

from ..analysis import Analysis
from ..catalog.meshes import MJCF_LEFT_OUT
from ..catalog.physics import MJCF_JOINED_INERTIAL, MJCF_REFUSED
from ..diagnostics import Diagnostic, Kind, Subject
from ..model import Link, Mesh
from ._masses import own, refused

__all__ = ["joining", "leaving_out", "refusal"]


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


def leaving_out(analysis: Analysis, link: Link, mesh: Mesh, kind: str) -> Diagnostic:
    """A ``kind`` (visual or collision) mesh of ``link`` MuJoCo cannot read, left out."""
    path = analysis.mesh_paths.get(mesh.filename)
    if path.found:
        suffix = os.path.splitext(mesh.filename)[1].lower()
        why = f"is a {suffix} file, which MuJoCo cannot read" if suffix else "has no suffix"
        hint = "export it as STL or OBJ"
    else:
        why, hint = "is not found", "name the file that is there"
    return MJCF_LEFT_OUT.report(
        f"link {link.name!r}: {kind} mesh {mesh.filename!r} {why}: left out of the MJCF",
        mesh.source,
        path=analysis.path,
        subject=Subject(Kind.LINK, link.name),
        hint=hint,
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
