"""Xacro -> URDF without ROS, with the PyPI ``xacro`` package as the engine.

This package is the only place that imports xacro. xacro keeps its state in module globals
(the file and macro stacks, the list of files read, the substitution arguments, the symbol
table) and prints its warnings, so every expansion runs xacro's code in a copy of its own
(:mod:`._instance`), its evaluator chosen when the copy is made and never swapped, its
hooks in place for good, and its messages captured instead of printed. Expansions on
several threads run side by side, each on its own copy. The hooks:

- ``$(find pkg)`` resolves through :func:`fishbot_urdf.packages.find_package`;
- every element remembers the file, line and column it was written at (kept through the
  clones a macro call makes), so errors and findings point at the xacro source, with the
  chain of macro calls that led there;
- ``$(dirname)`` works (xacro 2.1.1 never tells it the current file);
- ``<xacro:attribute>`` with a number value is written out (xacro 2.1.1 crashes on it);
- unless expressions run as Python, files are read only inside the robot's tree, the folders
  of the packages ``$(find)`` resolves, and the folders allowed (``allow_read``, or
  :func:`allowing_reads`): see ``_scope``.
"""

from __future__ import annotations

import os
import re
import stat
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar, cast

from ..errors import ArgumentError, InputError
from ..inputs import (
    allowing_reads,
    is_input_file,
    read_input,
    reads_allowed,
    trusting_expressions,
    trusts_expressions,
)
from ..packages import PackageFinder
from ._result import Expansion, ExpansionLimitError, MacroDefinition, XacroError
from ._scope import ReadOutsideError, ReadScope, robot_tree

if TYPE_CHECKING:
    from ._engine import Run
    from ._macros import Argument as Argument
    from ._macros import MacroTable as MacroTable

__all__ = [
    "Expansion",
    "ExpansionLimitError",
    "MacroDefinition",
    "ReadOutsideError",
    "XacroError",
    "allowing_reads",
    "declared_args",
    "expand",
    "parse_args",
    "probe_macros",
    "robot_tree",
    "trusting_expressions",
    "unexpanded",
]

T = TypeVar("T")


def parse_args(items: list[str] | tuple[str, ...]) -> dict[str, str]:
    """``["name:=value", ...]`` -> ``{"name": "value"}``, read as the xacro command reads them:
    spaces around name and value are dropped, and an empty value (``name:=``) or a ROS
    private parameter (``_name:=value``) is ignored.

    Raises:
        ArgumentError: An item has no ``:=``, more than one, or no name.
    """
    args: dict[str, str] = {}
    for item in items:
        pieces = [piece.strip() for piece in item.split(":=")]
        if len(pieces) != 2 or not pieces[0]:
            raise ArgumentError(f"'{item}' is not an argument: write name:=value", name=item)
        name, value = pieces
        if value and not (len(name) > 1 and name[0] == "_" and name[1] != "_"):
            args[name] = value
    return args


def expand(
    path: str | Path,
    args: Mapping[str, str] | None = None,
    packages: Mapping[str, str | Path] | PackageFinder | None = None,
    *,
    trust_expressions: bool | None = None,
    allow_read: str | os.PathLike[str] | Iterable[str | os.PathLike[str]] = (),
) -> Expansion:
    """Expand a xacro file to URDF.

    Args:
        path: The xacro file. Its name appears in the banner as given, as xacro does.
        args: Values for ``<xacro:arg>``, like ``name:=value`` on xacro's command line.
        packages: Package folders for ``$(find NAME)``, searched first (see
            :mod:`fishbot_urdf.packages` for the rest of the search), or a finder that
            keeps its answers (a workspace's).
        trust_expressions: Evaluate expressions with Python's ``eval``, as ROS's xacro
            does, running the file's code (default: as :func:`trusting_expressions` says,
            else no). It also lifts the limit on what may be read.
        allow_read: A folder, or folders, the expansion may read files in, besides the robot's tree
            (see :func:`robot_tree`), the folders of the packages ``$(find)`` resolves and
            those of :func:`allowing_reads`. A relative folder is taken from the current
            folder.

    Raises:
        InputError: The file cannot be read, or is not a regular file (a FIFO, a device),
            or is bigger than the size limit (see :mod:`fishbot_urdf.inputs`).
        PackageNotFoundError: ``$(find NAME)`` names a package no place knows.
        ReadOutsideError: Expressions do not run as Python, and the file reads a file
            (or an include pattern looks in a folder) outside the folders above, links
            resolved.
        XacroError: xacro refuses the input (the message says where and why).
    """
    return _run(path, args, packages, trust_expressions, allow_read).expand()


def probe_macros(
    path: str | Path,
    probe: Callable[[MacroTable], T],
    args: Mapping[str, str] | None = None,
    packages: Mapping[str, str | Path] | None = None,
    *,
    trust_expressions: bool | None = None,
    allow_read: str | os.PathLike[str] | Iterable[str | os.PathLike[str]] = (),
) -> T:
    """Expand a xacro file as :func:`expand` does, then hand its top-level macros to
    ``probe``, which may call them (:meth:`MacroTable.call`) as the file's top level would,
    within the same limits; what ``probe`` gives.

    Raises:
        The errors of :func:`expand`.
    """
    run = _run(path, args, packages, trust_expressions, allow_read, probe)
    run.expand()
    return cast("T", run.probed)


def _run(
    path: str | Path,
    args: Mapping[str, str] | None,
    packages: Mapping[str, str | Path] | PackageFinder | None,
    trust_expressions: bool | None,
    allow_read: str | os.PathLike[str] | Iterable[str | os.PathLike[str]],
    probe: Callable[[MacroTable], Any] | None = None,
) -> Run:
    name = str(path)
    try:
        # An editor's unsaved text of the file may be all there is of it.
        folder = not is_input_file(name) and stat.S_ISDIR(os.stat(name).st_mode)
    except (FileNotFoundError, NotADirectoryError) as exc:
        raise InputError(f"{name} does not exist", path=name) from exc
    except OSError as exc:  # a name too long, a loop of links, ...
        raise InputError(f"cannot read: {exc.strerror or exc}", path=name) from exc
    if folder:
        raise InputError(f"{name} is a folder", path=name)
    from ._engine import Run  # xacro, minidom and the interpreter load here: ~15 ms

    trust = trusts_expressions() if trust_expressions is None else trust_expressions
    if trust:
        reads = ReadScope.anywhere()
    else:
        given = [allow_read] if isinstance(allow_read, str | os.PathLike) else allow_read
        reads = ReadScope.of(name, (*reads_allowed(), *given))
    found = packages if isinstance(packages, PackageFinder) else dict(packages or {})
    return Run(name, dict(args or {}), found, trust=trust, reads=reads, probe=probe)


# How a xacro file declares or reads an argument: <xacro:arg name="..."> (any prefix),
# $(arg name), and xacro.arg('name') in an expression.
_ARG_NAMES = re.compile(
    rb"<[\w.-]+:arg\b[^>]*?\sname\s*=\s*([\"'])(.*?)\1"
    rb"|\$\(arg\s+([^)\s]+)\s*\)"
    rb"|xacro\.arg\(\s*([\"'])(.*?)\4"
)


def declared_args(expansion: Expansion) -> frozenset[str]:
    """Every argument name the expanded files declare with ``<xacro:arg>`` or read with
    ``$(arg ...)``: the names a ``name:=value`` may give. Files that cannot be read again
    declare nothing."""
    names: set[str] = set()
    for file in (expansion.path, *expansion.dependencies):
        try:
            data = read_input(file)
        except (InputError, OSError):
            continue
        for match in _ARG_NAMES.finditer(data):
            found = match.group(2) or match.group(3) or match.group(5)
            if found:
                names.add(found.decode("utf-8", "replace"))
    return frozenset(names)


# A substitution xacro makes: $(arg x), $(find pkg), $(eval ...), ${expression}.
_SUBSTITUTION = re.compile(r"\$\([a-z]+\b[^)]*\)?|\$\{[^}]*\}?")

EXPAND_HINT = (
    "run xacro or `fishbot expand` on the .xacro file it came from, or give that file instead"
)
"""What to do about a xacro substitution left in a URDF file."""


def unexpanded(text: str) -> str | None:
    """The first xacro substitution in ``text`` (``$(arg x)``, ``$(find pkg)``, ``${x}``), as
    written, if it holds one: in a URDF file, a substitution xacro never made (the file was
    written from a .xacro file without running xacro on it)."""
    found = _SUBSTITUTION.search(text)
    return None if found is None else found.group()
