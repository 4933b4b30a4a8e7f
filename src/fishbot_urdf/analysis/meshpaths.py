"""Mesh names to files, by one rule, as the programs that load a robot read them.

- ``package://PKG/path``: ``path`` in ROS package PKG's folder, found as for xacro's
  ``$(find PKG)`` (see :mod:`fishbot_urdf.packages`).
- ``package:///path`` (no package named before the third slash), which ROS's
  resource_retriever refuses: as PyBullet and yourdfpy find it, ``path`` in the robot
  file's folder or one above it; else as pinocchio does, in the package its first folder
  names.
- ``file:///absolute/path``, or an absolute path: that file.
- A relative name: beside the robot file, the file a program loads. After xacro the robot
  is one URDF text that keeps no trace of the file that wrote each element, so a relative
  name written in an included xacro file is read beside the top file, never beside the
  include: PyBullet and MuJoCo read it beside the URDF file, Gazebo (sdformat) and Drake
  beside the file they load, pinocchio and yourdfpy beside the URDF file they are given;
  RViz and robot_state_publisher, through ROS's resource_retriever, read only
  ``package://`` and ``file://``. A robot read from text (a string, standard input) has no
  folder: its relative names lead nowhere.
- ``http(s)://`` and ``model://``: not ours to fetch.

A robot's `MeshPaths` is built once, by its analysis (``Analysis.mesh_paths``), and every
command and library function that opens a mesh asks it; what the files hold, it asks the
analysis's ``meshes`` (`fishbot_urdf.analysis.meshcontents`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, replace
from enum import Enum
from pathlib import Path
from typing import TYPE_CHECKING

from ..catalog.meshes import MESH_NOT_FOUND
from ..errors import FishbotUrdfError
from ..inputs import note_looked
from ..model import Link, Mesh, Robot
from ..packages import PackageFinder, PackageNotFoundError, package_name
from ..wording import closest

if TYPE_CHECKING:
    from collections.abc import Iterator

__all__ = ["RULE", "MeshNotFoundError", "MeshPath", "MeshPaths", "State", "robot_meshes"]

RULE = (
    "relative mesh names are read beside the robot file, as Gazebo, MuJoCo, PyBullet, "
    "pinocchio and yourdfpy read them"
)
"""The rule for relative names, in the words findings give it."""

_REMOTE = ("http://", "https://", "model://")  # not ours to fetch: Gazebo's model path, the web


class State(str, Enum):
    """What a mesh name leads to."""

    FOUND = "found"  # a file, under exactly its name
    OTHER_CASE = "other-case"  # only a file whose name differs in upper and lower case
    MISSING = "missing"  # no file there
    NO_PACKAGE = "no-package"  # a package:// name whose package is found nowhere
    MALFORMED = "malformed"  # a URI no program reads (package:/, file://relative, ...)
    REMOTE = "remote"  # http(s)://, model://: not looked at
    NO_FOLDER = "no-folder"  # a relative name of a robot read from text


@dataclass(frozen=True, slots=True)
class MeshPath:
    """Where one mesh name leads.

    Attributes:
        name: The name as written in ``<mesh filename>``.
        state: What it leads to.
        file: The file (FOUND), or where it was looked for (MISSING, OTHER_CASE); None
            for the other states.
        other: For OTHER_CASE, the file whose name differs in case.
        package: For NO_PACKAGE, the package.
        searched: For NO_PACKAGE, the places searched, in order.
        problem: For MALFORMED, what is wrong with the name.
        fix: For MALFORMED, how to write it.
        unnamed: Written ``package:///``, the package's name left out (ROS's
            resource_retriever refuses it): resolved as the programs that read it find it.
    """

    name: str
    state: State
    file: Path | None = None
    other: str | None = None
    package: str | None = None
    searched: tuple[str, ...] = ()
    problem: str | None = None
    fix: str | None = None
    unnamed: bool = False

    @property
    def found(self) -> bool:
        """Whether the name leads to a file that is there."""
        return self.state is State.FOUND

    @property
    def relative(self) -> bool:
        """Whether the name is a relative path (read beside the robot file)."""
        return _relative(self.name)


class MeshNotFoundError(FishbotUrdfError):
    """A mesh name leads to no file (the message says where it was looked for, and why)."""

    rule = MESH_NOT_FOUND.id


def robot_meshes(robot: Robot) -> Iterator[tuple[Link, Mesh, bool]]:
    """Every named mesh of the robot, with its link and whether it is a collision shape,
    in file order (a link's visuals, then its collisions)."""
    for link in robot.links:
        for visual in link.visuals:
            if isinstance(visual.geometry, Mesh) and visual.geometry.filename:
                yield link, visual.geometry, False
        for collision in link.collisions:
            if isinstance(collision.geometry, Mesh) and collision.geometry.filename:
                yield link, collision.geometry, True


class MeshPaths:
    """Every mesh name of one robot, resolved by the one rule, each name, package and
    folder looked up once.

    Args:
        robot_file: The robot file relative names are read beside (``<...>`` or ``-``: the
            robot was read from text).
        packages: Where ``package://`` names are found.
    """

    def __init__(self, robot_file: str, packages: PackageFinder) -> None:
        text = robot_file.startswith("<") or robot_file == "-"
        self.robot_file = None if text else robot_file
        self.packages = packages
        self._paths: dict[str, MeshPath] = {}
        self._folders: dict[str, Path | PackageNotFound] = {}
        self._listings: dict[Path, list[str] | None] = {}

    def get(self, name: str) -> MeshPath:
        """Where mesh name ``name`` leads (looked up once)."""
        known = self._paths.get(name)
        if known is None:
            known = self._paths[name] = self._resolve(name)
        return known

    def file(self, mesh: Mesh) -> Path:
        """The file of ``mesh``, which is there.

        Raises:
            PackageNotFoundError: The name is in a package that is not found.
            MeshNotFoundError: The name leads to no file (or to one that is not ours to
                fetch).
        """
        path = self.get(mesh.filename)
        if path.found and path.file is not None:
            return path.file
        where = mesh.source
        at = where.path if where else None
        line, column = (where.line, where.column) if where else (None, None)
        if path.state is State.NO_PACKAGE:
            package = str(path.package)
            raise PackageNotFoundError(package, path.searched, path=at, line=line, column=column)
        message = f"mesh {mesh.filename!r} {self.why(path, at)}"
        raise MeshNotFoundError(message, path=at, line=line, column=column)

    def why(self, path: MeshPath, writer: str | None = None) -> str:
        """Why ``path`` leads to no file, as a message goes on after the mesh's name (a file
        named in the robot's own form: see `written`; ``writer`` wrote the mesh)."""
        state = path.state
        if state is State.FOUND:
            return f"is {path.file}"
        if state is State.NO_PACKAGE:
            return f"is in package {path.package!r}, which is not found"
        if state is State.MALFORMED:
            return str(path.problem)
        if state is State.REMOTE:
            return "is not a file on this machine"
        if state is State.NO_FOLDER:
            return "is a relative name, and the robot was read from text, with no folder"
        if state is State.OTHER_CASE:
            other = self.written(path.name, str(path.other), writer)
            return f"is found only as {other!r}, a name that differs in case"
        if path.relative:
            return f"is not found (looked for {path.file}; {RULE})"
        return f"is not found (looked for {path.file})"

    def package_folder(self, package: str) -> Path | None:
        """The folder of ROS package ``package``, as ``package://`` names are found (looked
        up once), None when it is not found."""
        folder = self._package(package)
        return None if isinstance(folder, PackageNotFound) else folder

    def beside_writer(self, mesh: Mesh) -> Path | None:
        """For a relative name not found beside the robot file: the file beside the file
        that wrote the ``<mesh>`` (an included xacro file), if it is there. That is where
        the author meant, and where no program that loads the robot looks."""
        path = self.get(mesh.filename)
        source = mesh.source
        if path.state is not State.MISSING or not path.relative or source is None:
            return None
        writer = source.path
        if self.robot_file is None or writer.startswith("<"):
            return None
        if os.path.dirname(os.path.abspath(writer)) == os.path.dirname(
            os.path.abspath(self.robot_file)
        ):
            return None
        there = Path(writer).parent / mesh.filename
        return there if os.path.isfile(there) else None

    def in_package(self, file: Path) -> tuple[str, str] | None:
        """The package that holds ``file`` (the nearest folder above it with a package.xml
        that names it) and the file's path inside it, else None."""
        folder = os.path.dirname(os.path.abspath(file))
        while True:
            manifest = os.path.join(folder, "package.xml")
            if os.path.isfile(manifest):
                name = package_name(manifest)
                if name is None:
                    return None
                inside = os.path.relpath(os.path.abspath(file), folder).replace(os.sep, "/")
                return name, inside
            parent = os.path.dirname(folder)
            if parent == folder:
                return None
            folder = parent

    def written(self, name: str, file: str | Path, writer: str | None = None) -> str:
        """``file`` named in the form the robot names it by ``name``: ``package://PKG/...``
        through the same package, ``file://`` as ``file://``, a relative name relative to
        the robot file's folder, and an absolute path as ``$(find PKG)/...`` when a xacro
        file (``writer``) wrote it and a package holds the file. Anything else, and a file
        outside the package ``name`` names: the absolute path."""
        full = os.path.abspath(file)
        if name.startswith("package://"):
            package = name[len("package://") :].partition("/")[0]
            folder = self._folders.get(package)
            if isinstance(folder, Path):
                inside = os.path.relpath(full, os.path.abspath(folder))
                if not inside.startswith(os.pardir):
                    return f"package://{package}/{inside.replace(os.sep, '/')}"
            return full
        if name.startswith("file://"):
            return "file://" + self.written(name[len("file://") :], full, writer)
        if _relative(name):
            if self.robot_file is None:
                return full
            beside = os.path.dirname(os.path.abspath(self.robot_file))
            return os.path.relpath(full, beside).replace(os.sep, "/")
        if writer is not None and writer.lower().endswith(".xacro"):
            held = self.in_package(Path(full))
            if held is not None:
                return f"$(find {held[0]})/{held[1]}"
        return full

    def closest(self, file: Path) -> str | None:
        """The file beside ``file`` whose name is closest to its name, if any is close."""
        names = self._listing(file.parent)
        if not names:
            return None
        close = closest(file.name, names)
        return None if close is None else str(file.parent / close)

    def found(self, robot: Robot) -> list[Path]:
        """Every file the robot's meshes lead to that is there, once each, in file order."""
        paths = (self.get(mesh.filename) for _, mesh, _ in robot_meshes(robot))
        return list(dict.fromkeys(p.file for p in paths if p.found and p.file is not None))

    # -- resolving ------------------------------------------------------------------------
    def _resolve(self, name: str) -> MeshPath:
        malformed = _malformed(name)
        if malformed is not None:
            what, fix = malformed
            return MeshPath(name, State.MALFORMED, problem=what, fix=fix)
        if name.startswith(_REMOTE):
            return MeshPath(name, State.REMOTE)
        if name.startswith("package:///"):
            return replace(self._unnamed(name[len("package:///") :].lstrip("/")), name=name)
        if name.startswith("package://"):
            package, _, rest = name[len("package://") :].partition("/")
            folder = self._package(package)
            if isinstance(folder, PackageNotFound):
                return MeshPath(name, State.NO_PACKAGE, package=package, searched=folder.searched)
            file = folder / rest
        elif name.startswith("file://"):
            file = Path(name[len("file://") :])
        elif _relative(name):
            if self.robot_file is None:
                return MeshPath(name, State.NO_FOLDER)
            file = Path(self.robot_file).parent / name
        else:
            file = Path(name)
        exact, other = self._exists(file)
        if exact:
            return MeshPath(name, State.FOUND, file)
        if other is not None:
            return MeshPath(name, State.OTHER_CASE, file, other=other)
        return MeshPath(name, State.MISSING, file)

    def _unnamed(self, path: str) -> MeshPath:
        """Where ``package:///path`` leads, as the programs that read it find it: PyBullet
        and yourdfpy join the path to the robot file's folder and to each folder above it,
        pinocchio to each of its package folders (so its first folder is a package's). Found
        nowhere, it is missing beside the robot file, where the first of them looks: its first
        folder is no package to look for."""
        if self.robot_file is not None and path:
            folder = Path(self.robot_file).parent.absolute()
            for above in (folder, *folder.parents):
                if self._exists(above / path)[0]:
                    return MeshPath(path, State.FOUND, above / path, unnamed=True)
        if "/" in path:
            by_package = self._resolve("package://" + path)
            if by_package.state is not State.NO_PACKAGE:  # its first folder is a package's
                return replace(by_package, unnamed=True)
        if self.robot_file is None:
            return MeshPath(path, State.NO_FOLDER, unnamed=True)
        return MeshPath(path, State.MISSING, Path(self.robot_file).parent / path, unnamed=True)

    def _package(self, package: str) -> Path | PackageNotFound:
        known = self._folders.get(package)
        if known is None:
            try:
                known = self.packages.find(package, near=self.robot_file)
            except PackageNotFoundError as exc:
                known = PackageNotFound(exc.searched)
            self._folders[package] = known
        return known

    def _listing(self, folder: Path) -> list[str] | None:
        if folder not in self._listings:
            try:
                self._listings[folder] = sorted(os.listdir(folder))
            except OSError:
                self._listings[folder] = None
        return self._listings[folder]

    def _exists(self, file: Path) -> tuple[bool, str | None]:
        """Whether ``file`` is there under exactly its name, and else the name of a file
        whose name differs only in case."""
        note_looked(str(file))  # an answer that found it missing is stale once it is there
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
                found, other = self._exists(parent.parent / entry / file.name)
                return str(parent.parent / entry / file.name) if found else other
        return None


@dataclass(frozen=True, slots=True)
class PackageNotFound:
    """A package found nowhere, and the places searched."""

    searched: tuple[str, ...]


def _relative(name: str) -> bool:
    return "://" not in name and not os.path.isabs(name)


def _malformed(name: str) -> tuple[str, str] | None:
    """What is wrong with a mesh name written as a URI, and the fix; None if nothing is."""
    if "\\" in name:
        return "holds backslashes", "write forward slashes (/): backslashes work only on Windows"
    if name.startswith("package://"):
        package, _, rest = name[len("package://") :].partition("/")
        if not package:
            if not rest.strip("/"):
                return "names no package and no file", "write package://PACKAGE/path/to/mesh"
            return None  # package:///path: found by its path (see MeshPaths._unnamed)
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
