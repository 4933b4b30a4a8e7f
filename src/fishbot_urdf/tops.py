"""The robots a file belongs to: the top files that read it, found in its package, each with
its configuration (for an editor that opens an included file, or a command given one)."""

from __future__ import annotations

import io
import os
from collections.abc import Iterator
from pathlib import Path

from lxml import etree

from .config import Config, find_config, load_config
from .errors import FishbotUrdfError
from .inputs import read_input, recording_inputs
from .lint import check_file
from .workspace import Workspace
from .xml.stream import SAFE

__all__ = [
    "MAX_CANDIDATES",
    "MAX_ENTRIES",
    "find_tops",
    "holds_robot",
    "nearest_config",
    "package_folder",
]

MAX_ENTRIES = 2000
"""How many files and folders of a package are looked at for the xacro files that may read
a file (a package with its meshes and launch files is searched so far, and no further)."""

MAX_CANDIDATES = 64
"""How many of those xacro files are read to learn what they include."""

_SKIPPED = {"build", "install", "log", "node_modules", "__pycache__"}  # never robots


def find_tops(path: str | Path, workspace: Workspace) -> tuple[str, ...]:
    """The top files of the robots ``path`` belongs to, as absolute paths, sorted.

    A file whose ``<robot>`` holds links or joints of its own is a robot: itself. Any other
    (a file of macros, opened alone) belongs to the xacro files of its package (see
    `package_folder`) whose check reads it, the outermost of them (a file that another of
    them reads is not one); a file none of them reads is a robot of its own. What each
    xacro file reads is kept in ``workspace`` until one of its files changes, so that asking
    again after an edit reads again only what changed.
    """
    name = _absolute(path)
    try:
        with workspace.reading():
            data = read_input(name)
    except FishbotUrdfError:
        data = None
    if data is not None and holds_robot(data):
        return (name,)
    readers: dict[str, frozenset[str]] = {}
    for candidate in _candidates(package_folder(name)):
        if candidate == name:
            continue
        try:
            files = _files_read(candidate, workspace)
        except FishbotUrdfError:  # gone since the folder was listed, or unreadable
            continue
        if name in files:
            readers[candidate] = files
    tops = [
        top
        for top in readers
        if not any(top in files for other, files in readers.items() if other != top)
    ]
    return tuple(sorted(tops)) or (name,)


def nearest_config(path: str | Path, workspace: Workspace) -> Config:
    """The configuration of the nearest fishbot.toml or pyproject.toml above the file
    ``path`` (see `fishbot_urdf.config.find_config`), kept in ``workspace`` until it
    changes, or the default.

    Raises:
        ConfigError: The configuration found is wrong.
    """
    found = find_config(path)
    if found is None:
        return Config()
    return workspace.memo(("config", str(found)), lambda: load_config(found))


def holds_robot(data: bytes) -> bool:
    """Whether the root element of ``data`` holds a ``<link>`` or ``<joint>`` of its own
    (not inside a macro), as far as the text can be read as XML (the rest of it may be
    being typed): read up to the first one only."""
    depth = 0
    try:
        events = etree.iterparse(io.BytesIO(data), events=("start", "end"), **_ITERPARSE)
        for event, element in events:
            if event == "end":
                depth -= 1
                if depth >= 1:
                    element.clear()  # a fragment's macros are not kept
                continue
            depth += 1
            if depth == 2 and element.tag in ("link", "joint"):  # (not in a namespace)
                return True
    except etree.LxmlError:
        return False
    return False


_ITERPARSE = {k: v for k, v in SAFE.items() if k not in ("dtd_validation", "recover")}


def package_folder(path: str | Path) -> str:
    """The folder of the nearest package.xml above the file ``path``, else its folder."""
    folder = Path(_absolute(path)).parent
    for above in (folder, *folder.parents):
        if (above / "package.xml").is_file():
            return str(above)
    return str(folder)


def _candidates(folder: str) -> Iterator[str]:
    """The xacro files in ``folder`` and below (within `MAX_ENTRIES`), at most
    `MAX_CANDIDATES`, in name order, folder by folder."""
    seen = given = 0
    for where, folders, files in os.walk(folder):
        folders[:] = sorted(f for f in folders if not f.startswith(".") and f not in _SKIPPED)
        seen += len(folders) + len(files)
        for name in sorted(files):
            if name.endswith(".xacro"):
                yield os.path.join(where, name)
                given += 1
                if given >= MAX_CANDIDATES:
                    return
        if seen >= MAX_ENTRIES:
            return


def _files_read(candidate: str, workspace: Workspace) -> frozenset[str]:
    """The files the check of ``candidate`` reads (as far as it gets, when it stops on an
    error), kept in ``workspace``."""

    def make() -> frozenset[str]:
        data = read_input(candidate)
        if b"include" not in data:  # reads nothing else: no need to expand it
            return frozenset((candidate,))
        try:
            config = nearest_config(candidate, workspace)
        except FishbotUrdfError:
            config = Config()
        with recording_inputs() as read:
            try:
                result = check_file(candidate, config=config, workspace=workspace)
            except FishbotUrdfError:
                return frozenset(map(_absolute, read))
        return frozenset(map(_absolute, result.files))

    return workspace.memo(("reads", candidate), make)


def _absolute(path: str | Path) -> str:
    return os.path.normpath(os.path.abspath(path))
