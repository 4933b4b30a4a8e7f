"""The findings of a conversion to MJCF that only writing it finds: the shapes it left out
(the bodies MuJoCo refuses and the inertials moved are foretold by
`fishbot_urdf.rules.mujoco`, which the check runs too)."""

from __future__ import annotations

import os

from ..analysis import Analysis
from ..catalog.meshes import MJCF_EMPTY_SHAPE, MJCF_LEFT_OUT
from ..diagnostics import Diagnostic, Kind, Subject
from ..model import Geometry, Link, Mesh
from ..rules._contents import hull_refused
from ._geoms import LOADABLE

__all__ = ["MOST_STL_FACES", "emptying", "leaving_out", "unreadable"]


def leaving_out(
    analysis: Analysis, link: Link, mesh: Mesh, kind: str, why: str | None = None
) -> Diagnostic:
    """A ``kind`` (visual or collision) mesh of ``link`` MuJoCo cannot read (``why``, when
    its file is found and of a format MuJoCo reads: see `unreadable`), left out."""
    path = analysis.mesh_paths.get(mesh.filename)
    if why is not None:
        hint = "export it again as a binary STL of at most 200000 triangles, with a volume"
    elif path.found:
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


def unreadable(analysis: Analysis, mesh: Mesh, *, collides: bool) -> str | None:
    """Why MuJoCo refuses a model with the found STL or OBJ file of ``mesh``, or None: an
    STL file written as text, or of more than 200000 triangles, a file with no triangle, an
    OBJ file with normals that some faces do not name, or a mesh that collides and has no
    volume to make a convex hull of."""
    path = analysis.mesh_paths.get(mesh.filename)
    if not path.found or path.file is None or path.file.suffix.lower() not in LOADABLE:
        return None
    facts = analysis.meshes.facts(path.file)
    if facts is None:
        return "holds no triangle MuJoCo can read"
    if facts.binary is False:
        return "is an STL file written as text, which MuJoCo cannot read"
    if facts.missing_normals:
        return "has normals, and faces that name none, which MuJoCo refuses"
    if facts.binary and facts.faces > MOST_STL_FACES:
        return f"has {facts.faces} triangles, more than the {MOST_STL_FACES} MuJoCo reads"
    return hull_refused(facts) if collides else None


MOST_STL_FACES = 200_000  # MuJoCo's STL decoder reads no more


def emptying(analysis: Analysis, link: Link, shape: Geometry, kind: str, what: str) -> Diagnostic:
    """A ``kind`` (visual or collision) shape of ``link`` of no size (``what``), left out."""
    return MJCF_EMPTY_SHAPE.report(
        f"link {link.name!r}: <{kind}> {what}, which MuJoCo refuses: left out of the MJCF",
        shape.source,
        path=analysis.path,
        subject=Subject(Kind.LINK, link.name),
        hint="give the shape its real size (m), or delete it",
    )
