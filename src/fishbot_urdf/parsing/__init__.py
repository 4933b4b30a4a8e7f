"""URDF text or file -> Robot. Every element keeps its file, line and column.

``read`` is lenient (it collects every finding); ``load`` and ``parse`` are strict (they raise
RobotError listing every finding).
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..diagnostics import Diagnostic
from ..errors import RobotError
from ..expansion import Expansion, declared_args, expand
from ..expansion._findings import unknown_args, unused_args, xacro_warning
from ..extensions import Reference
from ..inputs import reads_allowed, trusts_expressions
from ..model import Location, Robot
from ..packages import PackageFinder
from ..workspace import Workspace, package_key
from ..xml.source import STRING_PATH, XmlDocument, read_bytes, read_xml
from ..xml.stream import Unstreamable
from ._reader import Reader
from .values import to_double

__all__ = ["Parsed", "is_xacro_path", "load", "parse", "read", "to_double"]


@dataclass(frozen=True, slots=True)
class Parsed:
    """The outcome of reading one file leniently.

    Attributes:
        path: The file read ('<string>' for bytes).
        robot: The robot, possibly with faults; None if the file has no <robot>.
        diagnostics: Every finding made while reading, in document order.
        files: Every file the robot was read from: the file itself and, for xacro, every
            file its expansion read (empty for bytes).
        data: The URDF read: the file's bytes, or a xacro file's expansion.
        references: The names its Gazebo, transmission and ros2_control elements give to
            links and joints, with their places.
    """

    path: str
    robot: Robot | None
    diagnostics: tuple[Diagnostic, ...]
    files: tuple[str, ...] = ()
    data: bytes = field(default=b"", repr=False)
    references: tuple[Reference, ...] = ()


def is_xacro_path(path: str | Path) -> bool:
    """True for ``.xacro`` files (``robot.xacro``, ``robot.urdf.xacro``)."""
    return str(path).lower().endswith(".xacro")


def read(
    source: str | Path | bytes,
    *,
    path: str | None = None,
    args: Mapping[str, str] | None = None,
    packages: Mapping[str, str | Path] | PackageFinder | None = None,
    workspace: Workspace | None = None,
) -> Parsed:
    """Read a URDF (or xacro) file leniently, collecting every finding.

    It does not stop at the first finding.

    A ``.xacro`` file is expanded first (see :func:`fishbot_urdf.expand`), and the robot's
    elements keep the place they were written in the xacro files.

    Args:
        source: A file path, or the document itself as bytes.
        path: The name to report (default: the file path, or ``<string>`` for bytes).
        args: ``<xacro:arg>`` values, for a xacro file (a URDF file reads none: each is
            a `xacro-unknown-arg` warning).
        packages: Package folders for ``$(find NAME)``, for a xacro file (default: the
            workspace's).
        workspace: Where the files are read (an editor's unsaved texts over the disk) and
            each expansion kept, for as long as the files it read are unchanged.

    Raises:
        InputError: The file cannot be read.
        XmlSyntaxError: The file is not XML that urdfdom reads (see
            :func:`fishbot_urdf.xml.source.read_xml`).
        XacroError: The xacro file cannot be expanded.
        PackageNotFoundError: The xacro file names a package that is not found.
    """
    if workspace is None:
        return _read(source, path, args, packages, None)
    with workspace.reading():
        return _read(source, path, args, packages, workspace)


def _read(
    source: str | Path | bytes,
    path: str | None,
    args: Mapping[str, str] | None,
    packages: Mapping[str, str | Path] | PackageFinder | None,
    workspace: Workspace | None,
) -> Parsed:
    origins = None
    notes: tuple[Diagnostic, ...] = ()
    files: tuple[str, ...] = ()
    if isinstance(source, bytes):
        data, name = source, path or STRING_PATH
        notes = tuple(unused_args(args or (), name))
    elif is_xacro_path(source):
        expansion = _expansion(source, args, packages, workspace)
        # A file name that is no UTF-8 (the banner names the file) is no XML text either.
        data = expansion.text.encode("utf-8", "replace")
        name, origins = path or str(source), expansion.sources
        notes = tuple(xacro_warning(message, name) for message in expansion.messages)
        if args:
            notes += tuple(unknown_args(args, declared_args(expansion), name))
        files = (str(source), *expansion.dependencies)
    else:
        name = path or str(source)
        data = read_bytes(source)
        notes = tuple(unused_args(args or (), name))
        files = (str(source),)
    try:
        document, reader, robot = _robot(data, name, origins, None)
    except Unstreamable:  # a big file, not clean XML after all: read whole, as urdfdom does
        document, reader, robot = _robot(data, name, origins, False)
    found = notes + document.recoveries + tuple(reader.diagnostics)
    return Parsed(name, robot, found, files, data, tuple(reader.references))


def _expansion(
    source: str | Path,
    args: Mapping[str, str] | None,
    packages: Mapping[str, str | Path] | PackageFinder | None,
    workspace: Workspace | None,
) -> Expansion:
    if workspace is None:
        return expand(source, args=args, packages=packages)
    finder = workspace.packages if packages is None else packages
    key = (
        "expansion",
        os.path.abspath(source),
        tuple(sorted((args or {}).items())),
        package_key(finder),
        trusts_expressions(),
        reads_allowed(),
    )
    return workspace.memo(key, lambda: expand(source, args=args, packages=finder))


def _robot(
    data: bytes, name: str, origins: Sequence[Location] | None, stream: bool | None
) -> tuple[XmlDocument, Reader, Robot | None]:
    # As urdfdom reads it: a file it reads though strict XML does not gives xml-* warnings.
    document = read_xml(data, name, origins, stream=stream)
    reader = Reader(document.locator)
    robot = reader.robot(document.root, document.children())
    document.finish()
    return document, reader, robot


def parse(text: str | bytes, *, path: str | None = None) -> Robot:
    """Parse URDF text into a Robot.

    Raises:
        XmlSyntaxError: The text is not well-formed XML.
        RobotError: An element is malformed (``.diagnostics`` lists every finding).
    """
    if isinstance(text, str):
        # A str is decoded already: an encoding declaration in it would mislead lxml.
        data = re.sub(rb"^\s*<\?xml[^>]*\?>", b"", text.encode("utf-8"), count=1)
    else:
        data = text
    return _strict(read(data, path=path or STRING_PATH))


def load(
    path: str | Path,
    *,
    args: Mapping[str, str] | None = None,
    packages: Mapping[str, str | Path] | None = None,
) -> Robot:
    """Load a URDF file (or a xacro file, expanded with ``args`` and ``packages``) into a Robot.

    The tree's structure (undefined links, loops, ...) is checked by ``fishbot_urdf.check``.

    Raises:
        InputError: The file cannot be read.
        XmlSyntaxError: The file is not well-formed XML.
        RobotError: An element is malformed (``.diagnostics`` lists every finding).
    """
    return _strict(read(path, args=args, packages=packages))


def _strict(parsed: Parsed) -> Robot:
    errors = [d for d in parsed.diagnostics if d.is_error]
    if errors or parsed.robot is None:
        raise RobotError(errors, path=parsed.path)
    return parsed.robot
