"""The findings of a conversion to MJCF that only writing it finds: the shapes it converted
or left out (the bodies MuJoCo refuses and the inertials moved are foretold by
`fishbot_urdf.rules.mujoco`, which the check runs too)."""

from __future__ import annotations

from ..analysis import Analysis
from ..catalog.meshes import (
    MJCF_EMPTY_SHAPE,
    MJCF_LEFT_OUT,
    MJCF_MESH_CONVERTED,
    MjcfLeftOutFacts,
)
from ..diagnostics import Diagnostic, Kind, Subject
from ..model import Geometry, Link, Mesh
from ._geoms import Asset

__all__ = ["converting", "emptying", "leaving_out"]


def leaving_out(analysis: Analysis, link: Link, mesh: Mesh, kind: str, asset: Asset) -> Diagnostic:
    """A ``kind`` (visual or collision) mesh of ``link`` MuJoCo cannot read, left out."""
    return MJCF_LEFT_OUT.report(
        f"link {link.name!r}: {kind} mesh {mesh.filename!r} {asset.why}: left out of the MJCF",
        mesh.source,
        path=analysis.path,
        subject=Subject(Kind.LINK, link.name),
        hint=asset.hint,
        data=MjcfLeftOutFacts(convertible=asset.convertible),
    )


def converting(analysis: Analysis, link: Link, mesh: Mesh, kind: str, asset: Asset) -> Diagnostic:
    """A ``kind`` (visual or collision) mesh of ``link``, converted into the mesh folder."""
    return MJCF_MESH_CONVERTED.report(
        f"link {link.name!r}: {kind} mesh {mesh.filename!r} {asset.why}: converted to "
        f"{asset.converted} in the mesh folder",
        mesh.source,
        path=analysis.path,
        subject=Subject(Kind.LINK, link.name),
        hint="export it as binary STL or OBJ to have MuJoCo read it where it is",
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
