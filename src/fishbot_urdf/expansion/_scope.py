"""Where an expansion may read: the robot's tree, the packages it finds, the folders allowed.

A xacro file names the files it reads (includes, include patterns, YAML files), and a file
from a stranger can name ``~/.ssh/id_rsa`` as easily as ``wheel.urdf.xacro``; the error
that reading it gives (not XML, not YAML) would then show its lines. An expansion that does
not run expressions as Python reads only inside:

- the robot's tree (:func:`robot_tree`) of the file expanded, as named and with its links
  resolved;
- the folder of each package ``$(find)`` resolves during the expansion (and, when its
  ``package.xml`` is a link, as colcon's ``--symlink-install`` makes it, the folder that
  file really is in);
- the folders allowed by the caller (:func:`fishbot_urdf.inputs.allowing_reads`, or
  ``expand(..., allow_read=...)``).

Paths are compared with their links resolved: a link inside the tree that points out of it
leads outside.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass, replace
from pathlib import Path

from ..catalog.xacro import XACRO_READ_OUTSIDE
from ..location import Location
from ..packages import upward_folders
from ._result import XacroError

__all__ = ["READ_HINT", "ReadOutsideError", "ReadScope", "robot_tree"]

READ_HINT = (
    "if the robot should read it, allow a folder that holds it with allow_read=[DIR] "
    "or allow-read in [tool.fishbot]"
)
"""What to do about a read refused, in the library's words (the CLI names its option)."""


class ReadOutsideError(XacroError):
    """An expansion names a file, or an include pattern a folder, outside the folders it
    may read (see :mod:`fishbot_urdf.expansion`). The message names the file and the
    robot's tree, never anything the file holds.

    Attributes:
        file: The file (or folder) as the expansion names it.
        real: The same, with its links resolved.
        tree: The robot's tree, links resolved.
        pattern: The include pattern that reaches the folder ``file``, or None.
    """

    rule = XACRO_READ_OUTSIDE.id

    def __init__(
        self,
        file: str,
        real: str,
        tree: str,
        *,
        pattern: str | None = None,
        where: Location | None = None,
        calls: tuple[tuple[str, Location | None], ...] = (),
    ) -> None:
        self.file, self.real, self.tree, self.pattern = file, real, tree, pattern
        # Absolute, as the tree is: the two are compared at a glance.
        shown = os.path.abspath(file)
        if os.path.normcase(shown) != os.path.normcase(real):
            shown += f", which is {real}"
        if pattern is None:
            message = f"cannot read {shown}: it is outside the robot's tree {tree}"
        else:
            message = f"include pattern {pattern} looks in {shown}, outside the robot's tree {tree}"
        super().__init__(message, rule=XACRO_READ_OUTSIDE, hint=READ_HINT, where=where, calls=calls)

    def located(
        self, where: Location | None, calls: tuple[tuple[str, Location | None], ...]
    ) -> ReadOutsideError:
        """The same error, at the element that names the file."""
        return ReadOutsideError(
            self.file, self.real, self.tree, pattern=self.pattern, where=where, calls=calls
        )


def robot_tree(robot: str | Path) -> str:
    """The robot's tree: the nearest folder at or above the robot file's own that holds a
    ``.git`` (a folder, or the file a git worktree or submodule has); else the nearest that
    holds a ``package.xml``; else the robot file's own folder. Links are not resolved."""
    folder = os.path.dirname(os.path.abspath(robot))
    for marker, there in ((".git", os.path.lexists), ("package.xml", os.path.isfile)):
        for above in upward_folders(folder):
            if there(os.path.join(above, marker)):
                return above
    return folder


@dataclass(frozen=True, slots=True)
class ReadScope:
    """The folders one expansion may read in, links resolved.

    Attributes:
        tree: The robot's tree (the first of ``roots``), or None: anywhere (an expansion
            that runs expressions as Python reads as ROS's xacro does).
        roots: Every folder reads may reach.
    """

    tree: str | None
    roots: tuple[str, ...] = ()

    @classmethod
    def anywhere(cls) -> ReadScope:
        """No restriction."""
        return cls(None)

    @classmethod
    def of(cls, robot: str | Path, allowed: Iterable[str | os.PathLike[str]] = ()) -> ReadScope:
        """The robot file's tree (found from the file as named, and from the file its links
        lead to), and the folders ``allowed``."""
        named = os.path.realpath(robot_tree(robot))
        real = os.path.realpath(robot_tree(os.path.realpath(robot)))
        folders = (named, real, *(os.path.realpath(folder) for folder in allowed))
        return cls(named, tuple(dict.fromkeys(folders)))

    def including(self, package: str | os.PathLike[str]) -> ReadScope:
        """This scope and the folder of a package ``$(find)`` resolved."""
        if self.tree is None:
            return self
        folders = [os.path.realpath(package)]
        manifest = os.path.join(package, "package.xml")
        if os.path.islink(manifest):  # colcon --symlink-install links each file it installs
            folders.append(os.path.dirname(os.path.realpath(manifest)))
        added = tuple(f for f in dict.fromkeys(folders) if f not in self.roots)
        return replace(self, roots=self.roots + added) if added else self

    def check(self, path: str) -> None:
        """Refuse to read the file ``path`` outside the roots.

        Raises:
            ReadOutsideError: It is outside, links resolved.
        """
        if self.tree is None:
            return
        real = os.path.realpath(path)
        if not self._holds(real):
            raise ReadOutsideError(path, real, self.tree)

    def check_pattern(self, folder: str, pattern: str) -> None:
        """Refuse to look in ``folder`` for the include pattern ``pattern`` outside the
        roots (before its names or whether it exists are known).

        Raises:
            ReadOutsideError: It is outside, links resolved.
        """
        if self.tree is None:
            return
        real = os.path.realpath(folder or os.curdir)
        if not self._holds(real):
            raise ReadOutsideError(folder or os.curdir, real, self.tree, pattern=pattern)

    def _holds(self, real: str) -> bool:
        path = os.path.normcase(real)
        for root in self.roots:
            top = os.path.normcase(root)
            if path == top or path.startswith(top.rstrip(os.sep) + os.sep):
                return True
        return False
