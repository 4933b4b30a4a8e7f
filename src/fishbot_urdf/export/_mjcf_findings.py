"""The findings of a conversion to MJCF: what it changed or left out, and what MuJoCo will
refuse of the model it wrote."""

from __future__ import annotations

from ..analysis import Analysis
from ..catalog.meshes import MJCF_LEFT_OUT, MJCF_MESH_CONVERTED, MjcfLeftOutFacts
from ..catalog.physics import MJCF_JOINED_INERTIAL, MJCF_REFUSED
from ..diagnostics import Diagnostic, Kind, Subject
from ..model import Link, Mesh
from ._geoms import Asset
from ._masses import own, refused

__all__ = ["converting", "joining", "leaving_out", "refusal"]


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
