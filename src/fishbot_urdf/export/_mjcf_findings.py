"""The findings of a conversion to MJCF that only writing it finds: the shapes it left out
(the bodies MuJoCo refuses and the inertials moved are foretold by
`fishbot_urdf.rules.mujoco`, which the check runs too)."""

from __future__ import annotations

import os

from ..analysis import Analysis
from ..catalog.meshes import MJCF_EMPTY_SHAPE, MJCF_LEFT_OUT
from ..diagnostics import Diagnostic, Kind, Subject
from ..model import Geometry, Link, Mesh

__all__ = ["emptying", "leaving_out"]


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


def emptying(analysis: Analysis, link: Link, shape: Geometry, kind: str, what: str) -> Diagnostic:
    """A ``kind`` (visual or collision) shape of ``link`` of no size (``what``), left out."""
    return MJCF_EMPTY_SHAPE.report(
        f"link {link.name!r}: <{kind}> {what}, which MuJoCo refuses: left out of the MJCF",
        shape.source,
        path=analysis.path,
        subject=Subject(Kind.LINK, link.name),
        hint="give the shape its real size (m), or delete it",
    )
