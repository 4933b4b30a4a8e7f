"""Rules about mesh files: the name resolves to a file, with the right case, in a format the
robot's programs load."""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path

from .. import catalog
from ..analysis import Analysis, of
from ..analysis.meshcontents import MeshContents
from ..analysis.meshpaths import MeshPath, State, robot_meshes
from ..catalog import Rule, rules_in
from ..catalog.meshes import (
    MESH_CASE,
    MESH_FACES,
    MESH_FLAT,
    MESH_FORMAT,
    MESH_INVALID,
    MESH_NOT_FOUND,
    MESH_UNITS,
    MESH_URI,
    PACKAGE_NO_NAME,
    MeshNotFoundFacts,
)
from ..diagnostics import Diagnostic, Kind, Severity, Subject
from ..errors import FishbotUrdfError, ShapeError
from ..expansion import EXPAND_HINT, unexpanded
from ..meshfile import EmptyMeshError
from ..model import Link, Mesh
from ..packages import PackageFinder
from ..parsing import is_xacro_path
from ._contents import flat_mesh, millimetres

__all__ = [
    "CONTENTS_REPORTS",
    "NAMES_REPORTS",
    "REPORTS",
    "mesh_contents",
    "mesh_names",
    "meshes",
    "unresolved",
]


_LOADED = frozenset({".stl", ".obj", ".dae"})
_MOST_FACES = 20_000  # a collision mesh above this is slow to simulate


def meshes(
    analysis: Analysis,
    packages: Mapping[str, str | Path] | PackageFinder | None = None,
    environ: Mapping[str, str] | None = None,
) -> Iterator[Diagnostic]:
    """Every finding about the robot's mesh files, found by the analysis's
    ``mesh_paths`` (see `fishbot_urdf.analysis.meshpaths`). ``packages`` and ``environ``, when
    given, are where ``package://`` names are looked up instead (as for xacro's
    ``$(find)``); or ``packages`` is a `fishbot_urdf.packages.PackageFinder` that keeps its
    answers for other robots (its own environment is read then)."""
    if environ is not None and not isinstance(packages, PackageFinder):
        packages = PackageFinder(packages, environ)
    analysis = of(analysis, packages)
    uses = list(robot_meshes(analysis.robot))
    for link, mesh, collides in uses:
        yield from _mesh(analysis, link, mesh, collides)
        yield from _contents(analysis, link, mesh, collides)
    yield from unresolved(analysis, ((link, mesh) for link, mesh, _ in uses))


def mesh_names(analysis: Analysis) -> Iterator[Diagnostic]:
    """The findings of `meshes` that judge the mesh names and whether they lead to files,
    without opening a file (``analysis``: of the packages the check is given)."""
    uses = list(robot_meshes(analysis.robot))
    for link, mesh, collides in uses:
        yield from _mesh(analysis, link, mesh, collides)
    yield from unresolved(analysis, ((link, mesh) for link, mesh, _ in uses))


def mesh_contents(analysis: Analysis) -> Iterator[Diagnostic]:
    """The findings of `meshes` that judge what the mesh files found hold: each is read."""
    for link, mesh, collides in robot_meshes(analysis.robot):
        yield from _contents(analysis, link, mesh, collides)


def unresolved(
    analysis: Analysis, uses: Iterable[tuple[Link, Mesh]], *, drawing: bool = False
) -> Iterator[Diagnostic]:
    """The findings about meshes whose names lead to no file (by the analysis's
    ``mesh_paths``): one for each such mesh, and one for each package not found, for all
    of its meshes. For ``drawing`` (a scene), each says the mesh is not drawn, as a
    warning, and names that lead to nothing to draw (a remote file, a relative name of a
    robot read from text) are findings too."""
    paths = analysis.mesh_paths
    missing: dict[str, list[tuple[Link, Mesh]]] = {}
    for link, mesh in uses:
        path = paths.get(mesh.filename)
        left = _left_unexpanded(analysis, mesh, path)
        if left is not None:  # not a name to look up, nor to suggest another for
            yield MESH_NOT_FOUND.report(
                f"link {link.name!r}: mesh {mesh.filename!r} is not found: {left!r} in it is "
                f"a xacro substitution left unexpanded{', so it is not drawn' if drawing else ''}",
                mesh.source,
                path=analysis.path,
                subject=Subject(Kind.LINK, link.name),
                hint=EXPAND_HINT,
                data=MeshNotFoundFacts(unexpanded=left),
                severity=Severity.WARNING if drawing else None,
            )
            continue
        if path.state is State.NO_PACKAGE:
            missing.setdefault(str(path.package), []).append((link, mesh))
            continue
        finding = _unresolved(analysis, link, mesh, path, drawing)
        if finding is not None:
            yield finding
    for package, named in missing.items():
        link, mesh = named[0]
        path = paths.get(mesh.filename)
        others = len(named) - 1
        also = f" (nor {others} other mesh{'es' if others > 1 else ''} of it)" if others else ""
        then = "it is not drawn" if drawing else "the file cannot be checked"
        yield MESH_NOT_FOUND.report(
            f"link {link.name!r}: mesh {mesh.filename!r} is in package {package!r}, "
            f"which is not found, so {then}{also}",
            mesh.source,
            path=analysis.path,
            subject=Subject(Kind.LINK, link.name),
            hint=f"searched: {'; '.join(path.searched)}",
            data=MeshNotFoundFacts(package=package),
            severity=Severity.WARNING,
        )


def _left_unexpanded(analysis: Analysis, mesh: Mesh, path: MeshPath) -> str | None:
    """The xacro substitution a URDF file's mesh name holds, when it leads to no file (a
    xacro file's expansion leaves none, but for one written ``$${...}`` on purpose)."""
    if path.state is State.FOUND or is_xacro_path(analysis.path):
        return None
    return unexpanded(mesh.filename)


def _unresolved(
    analysis: Analysis, link: Link, mesh: Mesh, path: MeshPath, drawing: bool
) -> Diagnostic | None:
    state = path.state
    if state is State.FOUND or (not drawing and state in (State.REMOTE, State.NO_FOLDER)):
        return None  # found, or not ours to judge
    named = f"link {link.name!r}: mesh {mesh.filename!r}"
    then = ", so it is not drawn" if drawing else ""
    data: MeshNotFoundFacts | None = None
    paths = analysis.mesh_paths
    if state is State.MALFORMED:
        rule, what, hint = MESH_URI, f"{path.problem}{then}", path.fix
    elif state is State.OTHER_CASE:
        rule, what = MESH_CASE, paths.why(path, mesh.source.path if mesh.source else None) + then
        hint = "Linux file names are case-sensitive: write the name exactly as the file's"
    elif state is State.MISSING:
        rule, what = MESH_NOT_FOUND, analysis.mesh_paths.why(path) + then
        hint, data = _not_found(analysis, mesh, path)
    elif state is State.REMOTE:
        rule, what = MESH_NOT_FOUND, f"is not a file on this machine{then}"
        hint = "http://, https:// and model:// files are not fetched"
    else:  # NO_FOLDER
        rule, what = MESH_NOT_FOUND, f"is a relative name, and the robot was read from text{then}"
        hint = "a relative name is read beside the robot file, and text has none"
    return rule.report(
        f"{named} {what}",
        mesh.source,
        path=analysis.path,
        subject=Subject(Kind.LINK, link.name),
        hint=hint,
        data=data,
        severity=Severity.WARNING if drawing else None,
    )


def _not_found(analysis: Analysis, mesh: Mesh, path: MeshPath) -> tuple[str, MeshNotFoundFacts]:
    """The hint and the data of a mesh whose file is not where programs look for it."""
    paths = analysis.mesh_paths
    assert path.file is not None
    data = MeshNotFoundFacts(looked_for=str(path.file))
    beside = paths.beside_writer(mesh)
    if beside is not None:
        # The classic mistake: the name is right beside the xacro file that wrote it.
        data = MeshNotFoundFacts(looked_for=str(path.file), beside_writer=str(beside))
        writer = mesh.source.path if mesh.source else "the file that wrote it"
        held = paths.in_package(beside)
        package, inside = held if held is not None else ("PACKAGE", "path")
        return (
            f"it is beside {writer}, which wrote it, but the expanded robot keeps no trace of "
            f"that file: write package://{package}/{inside} (or $(find {package})/{inside})",
            data,
        )
    close = paths.closest(path.file)
    if close is None:
        return _fix(mesh.filename), data
    written = paths.written(mesh.filename, close, mesh.source.path if mesh.source else None)
    guess = f"did you mean {written!r}? "
    return guess + _fix(mesh.filename), data


def _mesh(analysis: Analysis, link: Link, mesh: Mesh, collides: bool) -> Iterator[Diagnostic]:
    """The findings about one mesh that need no file."""
    name = mesh.filename
    named = f"link {link.name!r}: mesh {name!r}"
    path = analysis.mesh_paths.get(name)
    subject = Subject(Kind.LINK, link.name)
    if path.unnamed:
        yield _unnamed(analysis, named, mesh, path, subject)
    if path.state in (State.MALFORMED, State.REMOTE) or _left_unexpanded(analysis, mesh, path):
        return
    extension = os.path.splitext(name)[1].lower()
    if extension not in _LOADED:
        kind = f"is a {extension} file" if extension else "has no file extension"
        yield MESH_FORMAT.report(
            f"{named} {kind}",
            mesh.source,
            path=analysis.path,
            subject=subject,
            hint="Gazebo loads STL, OBJ and COLLADA; MuJoCo and PyBullet STL and OBJ: export "
            "it as one of those",
        )


def _contents(analysis: Analysis, link: Link, mesh: Mesh, collides: bool) -> Iterator[Diagnostic]:
    """The findings about one mesh's file, found: what it holds."""
    name = mesh.filename
    subject = Subject(Kind.LINK, link.name)
    named = f"link {link.name!r}: mesh {name!r}"

    def report(rule: Rule, what: str, hint: str) -> Diagnostic:
        return rule.report(
            f"{named} {what}", mesh.source, path=analysis.path, subject=subject, hint=hint
        )

    path = analysis.mesh_paths.get(name)
    if path.state in (State.MALFORMED, State.REMOTE) or _left_unexpanded(analysis, mesh, path):
        return
    if not path.found or path.file is None:
        return
    extension = os.path.splitext(name)[1].lower()
    facts = analysis.meshes.facts(path.file)
    if facts is None:
        fault = _fault(analysis.meshes, path.file) if extension in (".stl", ".obj") else None
        if fault is not None:
            yield report(MESH_INVALID, fault, "export the mesh again")
        return
    if collides and facts.faces > _MOST_FACES:
        yield report(
            MESH_FACES,
            f"has {facts.faces} faces, too many for a collision shape",
            "simplify it to a few hundred faces or its convex hull, or collide with boxes, "
            "cylinders and spheres",
        )
    if collides:
        flat = flat_mesh(facts)
        if flat is not None:
            yield report(
                MESH_FLAT,
                flat,
                "collide with a thin box, or give the mesh its thickness",
            )
    units = millimetres(link, facts.extent(mesh.scale))
    if units is not None:
        yield report(
            MESH_UNITS,
            units,
            'if it is in millimetres, add scale="0.001 0.001 0.001" to the <mesh>',
        )


def _unnamed(
    analysis: Analysis, named: str, mesh: Mesh, path: MeshPath, subject: Subject
) -> Diagnostic:
    """A ``package:///`` name: what ROS's tools and the programs that find it by its path
    do with it."""
    what = "names no package (package:///), which ROS's resource_retriever refuses (RViz, MoveIt)"
    hint = "write package://PACKAGE/path, with the package's name after the two slashes"
    if path.found and path.file is not None:
        what += (
            "; PyBullet, yourdfpy and pinocchio (given its package folders) find it by its "
            f"path, as {path.file}"
        )
        paths = analysis.mesh_paths
        # The first folder a package's (example-robot-data's TALOS), else the package
        # that holds the file.
        named_package = "package://" + mesh.filename[len("package:///") :].lstrip("/")
        if paths.get(named_package).file == path.file:
            hint = f"write {named_package}"
        else:
            held = paths.in_package(path.file)
            if held is not None:
                hint = f"write package://{held[0]}/{held[1]}"
    return PACKAGE_NO_NAME.report(
        f"{named} {what}", mesh.source, path=analysis.path, subject=subject, hint=hint
    )


def _fix(name: str) -> str:
    if name.startswith("package:///"):
        return (
            "with no package named, it was looked for from the robot file's folder and each "
            "folder above it, as PyBullet and yourdfpy look"
        )
    if name.startswith("package://"):
        return "package:// names a file inside the package's folder"
    if name.startswith("file://") or os.path.isabs(name):
        return "an absolute path names a file on this machine only: write package://PACKAGE/path"
    return "write package://PACKAGE/path for a file of a ROS package"


def _fault(meshes: MeshContents, file: Path) -> str | None:
    """What is wrong with an STL or OBJ file whose facts could not be read (looked at only
    then: a file read well pays nothing); None for a file that holds nothing (an empty
    placeholder) or cannot be read at all."""
    try:
        meshes.triangles(file)
    except EmptyMeshError:
        return None
    except ShapeError as exc:
        return exc.message
    except FishbotUrdfError:
        return None  # not readable: another rule's matter
    return None


# (shape-not-drawn and nothing-drawn are render's and view's findings: the check never draws;
# mjcf-left-out, mjcf-empty-shape and mjcf-mesh-converted are what `fishbot mjcf` leaves
# out or converts; shape-size is the shapes' check's, which opens no file)
_OTHERS = (
    catalog.meshes.SHAPE_NOT_DRAWN,
    catalog.meshes.NOTHING_DRAWN,
    catalog.meshes.MJCF_LEFT_OUT,
    catalog.meshes.MJCF_MESH_CONVERTED,
    catalog.meshes.MJCF_EMPTY_SHAPE,
    catalog.meshes.SHAPE_SIZE,
)
REPORTS: tuple[Rule, ...] = tuple(r for r in rules_in(catalog.meshes) if r not in _OTHERS)
"""Every rule this module's check may report: the check runs only when one is selected."""
CONTENTS_REPORTS: tuple[Rule, ...] = (MESH_INVALID, MESH_FACES, MESH_FLAT, MESH_UNITS)
"""The rules of `mesh_contents`, the part of the check that reads the mesh files."""
NAMES_REPORTS: tuple[Rule, ...] = tuple(r for r in REPORTS if r not in CONTENTS_REPORTS)
"""The rules of `mesh_names`, the part of the check that opens no file."""
