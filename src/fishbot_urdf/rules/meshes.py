"""Rules about mesh files: the name resolves to a file, with the right case, in a format the
robot's programs load."""

from __future__ import annotations

import math
import os
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from ..analysis import Analysis
from ..catalog import Rule
from ..catalog.meshes import (
    MESH_CASE,
    MESH_FACES,
    MESH_FORMAT,
    MESH_INVALID,
    MESH_NOT_FOUND,
    MESH_UNITS,
    MESH_URI,
)
from ..diagnostics import Diagnostic, Kind, Severity, Subject, closest
from ..errors import FishbotUrdfError
from ..model import Box, Cylinder, Link, Mesh, Sphere

if TYPE_CHECKING:
    from ..meshfile import MeshFacts
    from ..packages import PackageFinder

__all__ = ["REPORTS", "meshes"]


_LOADED = frozenset({".stl", ".obj", ".dae"})
_REMOTE = ("http://", "https://", "model://")  # not ours to fetch: Gazebo's model path, the web
_MOST_FACES = 20_000  # a collision mesh above this is slow to simulate
_LARGEST_PART = 5.0  # metres: a robot part larger than this is implausible


def meshes(
    analysis: Analysis,
    packages: Mapping[str, str | Path] | PackageFinder | None = None,
    environ: Mapping[str, str] | None = None,
) -> Iterator[Diagnostic]:
    """Every finding about the robot's mesh files. ``packages`` and ``environ`` are where
    ``package://`` names are looked up (as for xacro's ``$(find)``); or ``packages`` is a
    `fishbot_urdf.packages.PackageFinder` that keeps its answers for other robots (its own
    environment is read then)."""
    from ..packages import PackageFinder

    if not isinstance(packages, PackageFinder):
        packages = PackageFinder(packages, os.environ if environ is None else environ)
    finder = _Finder(analysis.path, packages)
    for link in analysis.robot.links:
        shapes = [(part.geometry, False) for part in link.visuals]
        shapes += [(part.geometry, True) for part in link.collisions]
        for shape, collides in shapes:
            if isinstance(shape, Mesh) and shape.filename:
                yield from _mesh(analysis, link, shape, finder, collides)
    for unknown, named in finder.unknown.values():
        link, mesh = named[0]
        others = len(named) - 1
        also = f" (nor {others} other mesh{'es' if others > 1 else ''} of it)" if others else ""
        yield MESH_NOT_FOUND.report(
            f"link {link.name!r}: mesh {mesh.filename!r} is in package {unknown.package!r}, "
            f"which is not found, so the file cannot be checked{also}",
            mesh.source,
            path=analysis.path,
            subject=Subject(Kind.LINK, link.name),
            hint=f"searched: {'; '.join(unknown.searched)}",
            data={"package": unknown.package},
            severity=Severity.WARNING,
        )


def _mesh(
    analysis: Analysis, link: Link, mesh: Mesh, finder: _Finder, collides: bool
) -> Iterator[Diagnostic]:
    path, name = analysis.path, mesh.filename
    subject = Subject(Kind.LINK, link.name)
    named = f"link {link.name!r}: mesh {name!r}"
    where = mesh.source

    def report(rule: Rule, what: str, hint: str, severity: Severity | None = None) -> Diagnostic:
        return rule.report(
            f"{named} {what}", where, path=path, subject=subject, hint=hint, severity=severity
        )

    malformed = _malformed(name)
    if malformed:
        yield report(MESH_URI, malformed[0], malformed[1])
        return
    if name.startswith(_REMOTE):
        return
    extension = os.path.splitext(name)[1].lower()
    if extension not in _LOADED:
        kind = f"is a {extension} file" if extension else "has no file extension"
        yield report(
            MESH_FORMAT,
            kind,
            "Gazebo loads STL, OBJ and COLLADA; MuJoCo and PyBullet STL and OBJ: export it "
            "as one of those",
        )
    try:
        file = finder.file(name)
    except _Unknown as exc:  # reported once per package, after every mesh is seen
        finder.unknown.setdefault(exc.package, (exc, []))[1].append((link, mesh))
        return
    if file is None:
        return  # a relative name with no robot file to be relative to
    exact, other = finder.exists(file)
    if exact:
        facts = finder.facts(file)
        if facts is None:
            fault = finder.fault(file) if extension in (".stl", ".obj") else None
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
        units = _millimetres(link, facts.extent(mesh.scale))
        if units is not None:
            yield report(
                MESH_UNITS,
                units,
                'if it is in millimetres, add scale="0.001 0.001 0.001" to the <mesh>',
            )
        return
    if other is not None:
        yield report(
            MESH_CASE,
            f"is found only as {other!r}, a name that differs in case",
            "Linux file names are case-sensitive: write the name exactly as the file's",
        )
        return
    close = finder.close(file)
    guess = f"did you mean {close!r}? " if close else ""
    yield report(MESH_NOT_FOUND, f"is not found (looked for {file})", guess + _fix(name))


def _millimetres(link: Link, extent: float) -> str | None:
    """Why a mesh ``extent`` metres across reads as millimetres, or None if it does not.

    Plain sense: no robot part is more than 5 m across, unless the link's other shapes or
    its inertia say it is that large too. Against them: a mesh 200 to 5000 times larger
    than what they say.
    """
    shrunk = extent / 1000.0
    sizes = list(_sizes(link))
    if any(size >= extent / 20 for size, _ in sizes):
        return None  # the rest of the link is as large: a big part, in metres
    if extent > _LARGEST_PART and shrunk >= 0.001:
        return (
            f"is {extent:.4g} m across, more than any robot part; in millimetres it would be "
            f"{shrunk:.4g} m"
        )
    for size, what in sizes:
        if extent > 0.3 and 200 <= extent / size <= 5000:
            return (
                f"is {extent:.4g} m across, but {what} says the link is about {size:.3g} m; "
                f"in millimetres it would be {shrunk:.4g} m"
            )
    return None


def _sizes(link: Link) -> Iterator[tuple[float, str]]:
    """How large the link's other evidence says it is (m): its shapes, its inertia."""
    shapes = [part.geometry for part in link.visuals]
    shapes += [part.geometry for part in link.collisions]
    for shape in shapes:
        if isinstance(shape, Box):
            size, what = max(shape.size), "its box"
        elif isinstance(shape, Cylinder):
            size, what = max(2 * shape.radius, shape.length), "its cylinder"
        elif isinstance(shape, Sphere):
            size, what = 2 * shape.radius, "its sphere"
        else:
            continue
        if size > 0:
            yield size, what
    inertial = link.inertial
    if inertial is not None and inertial.mass > 0:
        i = inertial.inertia
        largest = max(i.ixx, i.iyy, i.izz)
        if largest > 0:
            # A rod of length L has I = m L^2 / 12: the longest the inertia allows.
            yield math.sqrt(12.0 * largest / inertial.mass), "its inertia"


def _fix(name: str) -> str:
    if name.startswith("package://"):
        return "package:// names a file inside the package's folder"
    if name.startswith("file://"):
        return "file:// names an absolute path on this machine"
    return "a relative name is read beside the robot file"


def _malformed(name: str) -> tuple[str, str] | None:
    """What is wrong with a mesh name written as a URI, and the fix; None if nothing is."""
    if "\\" in name:
        return "holds backslashes", "write forward slashes (/): backslashes work only on Windows"
    if name.startswith("package://"):
        package, _, rest = name[len("package://") :].partition("/")
        if not package:
            return (
                "names a package with no name (package:///)",
                "write package://PACKAGE/path, with the package's name after the two slashes",
            )
        if not rest:
            return "names a package but no file in it", "write package://PACKAGE/path/to/mesh"
        return None
    if name.startswith(("package:", "package//")):
        return "is not a package:// URI", "write package://PACKAGE/path, with two slashes"
    if name.startswith("file://") and not name.startswith("file:///"):
        return (
            "is a file:// URI with a relative path (the first folder is read as a host name)",
            "write file:///absolute/path, or a path relative to the robot file without file://",
        )
    return None


class _Unknown(Exception):
    def __init__(self, package: str, searched: tuple[str, ...]) -> None:
        self.package, self.searched = package, searched


class _Finder:
    """Mesh names to files, with each package and folder looked up once."""

    def __init__(self, robot: str, packages: PackageFinder):
        # A robot read from a string or stdin has no folder for relative names.
        self.robot = None if robot.startswith("<") or robot == "-" else robot
        self.packages = packages
        self.found: dict[str, Path | _Unknown] = {}
        self.listings: dict[Path, list[str] | None] = {}
        self.read: dict[Path, MeshFacts | None] = {}
        # Packages not found: the error, and every (link, mesh) in them.
        self.unknown: dict[str, tuple[_Unknown, list[tuple[Link, Mesh]]]] = {}

    def file(self, name: str) -> Path | None:
        if name.startswith("package://"):
            package, _, rest = name[len("package://") :].partition("/")
            folder = self.found.get(package)
            if folder is None:
                folder = self.found[package] = self._package(package)
            if isinstance(folder, _Unknown):
                raise folder
            return folder / rest
        if name.startswith("file://"):
            return Path(name[len("file://") :])
        path = Path(name)
        if path.is_absolute():
            return path
        return None if self.robot is None else Path(self.robot).parent / path

    def _package(self, package: str) -> Path | _Unknown:
        from ..packages import PackageNotFoundError

        try:
            return self.packages.find(package, near=self.robot)
        except PackageNotFoundError as exc:
            return _Unknown(package, exc.searched)

    def _listing(self, folder: Path) -> list[str] | None:
        if folder not in self.listings:
            try:
                self.listings[folder] = sorted(os.listdir(folder))
            except OSError:
                self.listings[folder] = None
        return self.listings[folder]

    def exists(self, file: Path) -> tuple[bool, str | None]:
        """Whether ``file`` is there under exactly its name, and else the name of a file
        whose name differs only in case."""
        names = self._listing(file.parent)
        if names is None:
            # The folder is missing, or is named in another case itself.
            return False, self._other_case_folder(file)
        if file.name in names:
            return True, None
        lower = file.name.lower()
        for entry in names:
            if entry.lower() == lower:
                return False, str(file.parent / entry)
        return False, None

    def _other_case_folder(self, file: Path) -> str | None:
        parent = file.parent
        names = self._listing(parent.parent) if parent != parent.parent else None
        for entry in names or ():
            if entry.lower() == parent.name.lower() and entry != parent.name:
                found, other = self.exists(parent.parent / entry / file.name)
                return str(parent.parent / entry / file.name) if found else other
        return None

    def fault(self, file: Path) -> str | None:
        """What is wrong with an STL or OBJ file whose facts could not be read (looked at
        only then: a file read well pays nothing); None for a file that holds nothing (an
        empty placeholder) or cannot be read at all."""
        from ..errors import ShapeError
        from ..meshfile import EmptyMeshError, mesh_triangles  # (for a mesh found malformed)

        try:
            mesh_triangles(file)
        except EmptyMeshError:
            return None
        except ShapeError as exc:
            return exc.message
        except FishbotUrdfError:
            return None  # not readable: another rule's matter
        return None

    def facts(self, file: Path) -> MeshFacts | None:
        if file not in self.read:
            from ..meshfile import mesh_facts  # (read only for a robot with mesh files)

            self.read[file] = mesh_facts(file)
        return self.read[file]

    def close(self, file: Path) -> str | None:
        names = self._listing(file.parent)
        if not names:
            return None
        close = closest(file.name, names)
        return None if close is None else str(file.parent / close)


REPORTS: tuple[Rule, ...] = (
    MESH_CASE,
    MESH_FACES,
    MESH_FORMAT,
    MESH_INVALID,
    MESH_NOT_FOUND,
    MESH_UNITS,
    MESH_URI,
)
"""Every rule this module's check may report: the check runs only when one is selected."""
