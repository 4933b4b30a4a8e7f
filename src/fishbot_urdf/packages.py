"""ROS package names -> folders, without ROS: for ``$(find pkg)`` and ``package://pkg/...``.

Places are searched in this order, and the first that knows the package wins:

1. ``packages``: names given explicitly (``--package NAME=PATH`` on the command line).
2. The folders around the file being read, walking up to the nearest ``package.xml`` whose
   ``<name>`` is the package.
3. The folders listed in ``ROS_PACKAGE_PATH``, in order, each searched for a ``package.xml``
   of that name (the shallowest one wins in a folder; packages are not searched inside).
4. ``share/NAME`` under each prefix of ``AMENT_PREFIX_PATH`` (an installed ROS 2 package).
5. The ``src/`` folder of the colcon workspace around the file, searched like 3.
6. ``ament_index_python``, when it can be imported (a sourced ROS 2 install).

A folder or link that cannot be looked at (a loop of links, no permission) is passed over as
if it were not there. Inside :func:`fishbot_urdf.inputs.recording_inputs`, every
``package.xml`` read on the way is noted, and so is the manifest of the package found (found
by its place, as under AMENT_PREFIX_PATH, or named with ``packages``, it is not read): a
caller can tell which files a robot's reading depended on.
"""

from __future__ import annotations

import os
import sys
from collections import deque
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from xml.parsers import expat

from .catalog.setup import PACKAGE_NOT_FOUND
from .errors import FishbotUrdfError, InputError
from .inputs import deadline, note_inputs, read_input, recording_inputs

__all__ = [
    "PackageFinder",
    "PackageNotFoundError",
    "find_package",
    "gazebo_model_path",
    "package_name",
    "resolve_package_uri",
    "ros_version",
    "upward_folders",
]

_IGNORE_MARKERS = ("COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE")
_SKIP_DIRS = frozenset(("build", "install", "log", "node_modules", "__pycache__"))


class PackageNotFoundError(FishbotUrdfError):
    """No place knows the package.

    ``searched`` lists every place looked at, in order (the first is the packages given by
    name, ``given``)."""

    rule = PACKAGE_NOT_FOUND.id

    def __init__(
        self,
        package: str,
        searched: tuple[str, ...],
        *,
        given: tuple[str, ...] = (),
        path: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        self.package = package
        self.searched = searched
        self.given = given
        places = "; ".join(searched) if searched else "nowhere"
        super().__init__(
            f"package '{package}' not found (searched: {places})",
            path=path,
            line=line,
            column=column,
        )


def package_name(package_xml: str | Path) -> str | None:
    """The ``<name>`` of a package.xml, or None if it has none or cannot be read (a FIFO, a
    device or a file over the size limit is not read; a file that is not well-formed XML,
    which ROS's tools refuse too, has no name, and so has one that declares entities)."""
    try:
        data = read_input(package_xml)
    except InputError:
        return None
    return _name_in(data)


def ros_version(package_xml: str | Path) -> int | None:
    """The ROS a package.xml builds with: 2 for ament (``ament_cmake``, ``ament_python``), 1
    for catkin, by its ``<buildtool_depend>`` and ``<export><build_type>``; None when it names
    neither or cannot be read (as for `package_name`)."""
    try:
        data = read_input(package_xml)
    except InputError:
        return None
    tools: list[str] = []
    parts: list[str] = []
    inside = False

    def start(tag: str, attributes: object) -> None:
        nonlocal inside
        inside = tag.rpartition(" ")[2] in ("buildtool_depend", "build_type")
        parts.clear()

    def end(tag: str) -> None:
        nonlocal inside
        if inside:
            tools.append("".join(parts).strip())
        inside = False

    def text(chunk: str) -> None:
        if inside:
            parts.append(chunk)

    if not _walk(data, start, end, text):
        return None
    if any(tool.startswith("ament") for tool in tools):
        return 2
    return 1 if "catkin" in tools else None


def gazebo_model_path(package_xml: str | Path) -> str | None:
    """The ``gazebo_model_path`` a package.xml exports (``<export><gazebo_ros
    gazebo_model_path="${prefix}/.."/>``), which gazebo_ros puts on GAZEBO_MODEL_PATH; None
    when it exports none or cannot be read (as for `package_name`)."""
    try:
        data = read_input(package_xml)
    except InputError:
        return None
    found: list[str] = []
    path: list[str] = []

    def start(tag: str, attributes: dict[str, str]) -> None:
        path.append(tag.rpartition(" ")[2])
        if path[-3:] == ["package", "export", "gazebo_ros"] and len(path) == 3:
            value = attributes.get("gazebo_model_path")
            if value is not None:
                found.append(value)

    def end(tag: str) -> None:
        path.pop()

    if not _walk(data, start, end):
        return None
    return found[0] if found else None


def _walk(
    data: bytes,
    start: Callable[[str, dict[str, str]], None],
    end: Callable[[str], None],
    text: Callable[[str], None] | None = None,
    other: Callable[..., None] | None = None,
) -> bool:
    """Run a package.xml's bytes through expat with these handlers (tags as ``namespace
    name``; ``other`` for comments and processing instructions); False when it is no
    well-formed XML or declares entities."""

    def refuse(*_: object) -> None:
        raise _NotRead

    parser = expat.ParserCreate(namespace_separator=" ")
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    parser.StartElementHandler = start
    parser.EndElementHandler = end
    if text is not None:
        parser.CharacterDataHandler = text
    if other is not None:
        parser.CommentHandler = other
        parser.ProcessingInstructionHandler = other
    parser.EntityDeclHandler = refuse
    try:
        parser.Parse(data, True)
    except (expat.ExpatError, _NotRead, ValueError):
        return False
    return True


class _NotRead(Exception):
    pass


def _name_in(data: bytes) -> str | None:
    # With expat, which xacro loads anyway (lxml would cost `fishbot expand` a sixth of its
    # start-up): no DTD is loaded, no external entity is read, and a file that declares an
    # entity is refused as the URDF reader refuses it. The name is the text of the root's
    # first <name> up to anything inside it, as lxml's ``.text`` gives it.

    depth, state, root_ok = 0, _BEFORE, False
    parts: list[str] = []

    def start(tag: str, attributes: object) -> None:
        nonlocal depth, state, root_ok
        depth += 1
        local = tag.rpartition(" ")[2]
        if depth == 1:
            root_ok = local == "package"
        elif state == _IN:
            state = _AFTER
        elif depth == 2 and local == "name" and state == _BEFORE:
            state = _IN

    def end(tag: str) -> None:
        nonlocal depth, state
        if depth == 2 and state == _IN:
            state = _AFTER
        depth -= 1

    def text(chunk: str) -> None:
        if state == _IN:
            parts.append(chunk)

    def other(*_: object) -> None:  # a comment or processing instruction ends the text
        nonlocal state
        if state == _IN:
            state = _AFTER

    if not _walk(data, start, end, text, other):
        return None
    if not root_ok or state == _BEFORE:
        return None
    return "".join(parts).strip() or None


_BEFORE, _IN, _AFTER = 0, 1, 2  # where the reading of package.xml is, against <name>


def find_package(
    name: str,
    *,
    near: str | Path | None = None,
    packages: Mapping[str, str | Path] | None = None,
    environ: Mapping[str, str] | None = None,
) -> Path:
    """The folder of ROS package ``name`` (its share folder when installed).

    Args:
        name: The package name, as in ``$(find name)``.
        near: The file being read: its folders and its workspace are searched.
        packages: Explicit ``name -> folder`` entries, searched first.
        environ: The environment to read ROS_PACKAGE_PATH and AMENT_PREFIX_PATH from
            (default ``os.environ``).

    Raises:
        PackageNotFoundError: No place knows the package.
    """
    env = os.environ if environ is None else environ
    searched: list[str] = []
    for found in _candidates(name, near, packages or {}, env, searched):
        return found
    raise PackageNotFoundError(name, tuple(searched), given=tuple(sorted(packages or {})))


class PackageFinder:
    """Finds packages as `find_package` does, and keeps each answer.

    Each answer (a folder, or that the package is not found) is kept by package name and
    the folder of the file that names it: for one run over many files, which name the same
    packages from the same folders.

    A package added or moved after it was looked up is not seen: make a new finder for a
    new run. Safe to share between threads (two may look the same package up at once).
    """

    __slots__ = ("_found", "environ", "packages")

    def __init__(
        self,
        packages: Mapping[str, str | Path] | None = None,
        environ: Mapping[str, str] | None = None,
    ) -> None:
        """``packages`` and ``environ`` are those of `find_package`."""
        self.packages: Mapping[str, str | Path] = dict(packages or {})
        self.environ = environ
        # Each answer, with the manifests it depends on (see `recording_inputs`).
        self._found: dict[
            tuple[str, str | None], tuple[Path | PackageNotFoundError, tuple[str, ...]]
        ] = {}

    def find(self, name: str, *, near: str | Path | None = None) -> Path:
        """`find_package` of ``name`` from the file ``near``, looked up once.

        Raises:
            PackageNotFoundError: No place knows the package.
        """
        # The folder find_package starts from: the file's own, links resolved.
        key = (name, None if near is None else os.path.dirname(os.path.realpath(near)))
        known = self._found.get(key)
        if known is None:
            found: Path | PackageNotFoundError
            with recording_inputs() as read:
                try:
                    found = find_package(
                        name, near=near, packages=self.packages, environ=self.environ
                    )
                except PackageNotFoundError as exc:
                    # (kept without its traceback, whose frames would keep what the first
                    # caller's frames hold, a robot and its analysis, as long as the finder)
                    found = exc.with_traceback(None)
            self._found[key] = (found, tuple(read))
        else:
            found, manifests = known
            note_inputs(manifests)
        if isinstance(found, PackageNotFoundError):
            raise PackageNotFoundError(found.package, found.searched, given=found.given)
        return found


def resolve_package_uri(
    uri: str,
    *,
    near: str | Path | None = None,
    packages: Mapping[str, str | Path] | None = None,
) -> Path:
    """The file a ``package://pkg/path`` or ``file://`` URI names.

    Other text is a plain path, relative to ``near``'s folder.

    Raises:
        PackageNotFoundError: The package is not found.
    """
    if uri.startswith("package://"):
        package, _, rest = uri[len("package://") :].partition("/")
        return find_package(package, near=near, packages=packages) / rest
    if uri.startswith("file://"):
        return Path(uri[len("file://") :])
    path = Path(uri)
    if not path.is_absolute() and near is not None:
        return Path(near).parent / path
    return path


def _candidates(
    name: str,
    near: str | Path | None,
    packages: Mapping[str, str | Path],
    env: Mapping[str, str],
    searched: list[str],
) -> Iterator[Path]:
    if name in packages:
        yield _by_place(Path(os.path.abspath(packages[name])))
    given = ", ".join(sorted(packages))
    searched.append(f"the packages given ({given or 'none'})")

    # (os.path rather than pathlib: this runs for every package a robot names)
    start = os.path.dirname(os.path.realpath(near)) if near is not None else None
    if start is not None:
        for folder in upward_folders(start):
            manifest = os.path.join(folder, "package.xml")
            if os.path.isfile(manifest) and package_name(manifest) == name:
                yield Path(folder)
        searched.append(f"the folders above {start}")

    for entry in _path_list(env.get("ROS_PACKAGE_PATH", "")):
        found = _crawl(Path(os.path.abspath(entry)), name)
        if found is not None:
            yield found
    searched.append("ROS_PACKAGE_PATH" + _shown(env.get("ROS_PACKAGE_PATH", "")))

    for entry in _path_list(env.get("AMENT_PREFIX_PATH", "")):
        prefix = Path(os.path.abspath(entry))
        share = prefix / "share" / name
        marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / name
        if os.path.isfile(marker) or os.path.isfile(share / "package.xml"):
            yield _by_place(share)
    searched.append("AMENT_PREFIX_PATH" + _shown(env.get("AMENT_PREFIX_PATH", "")))

    if start is not None:
        workspace = _workspace_src(start)
        if workspace is not None:
            found = _crawl(workspace, name)
            if found is not None:
                yield found
            searched.append(f"the workspace {workspace}")

    share_directory = _ament_lookup()
    if share_directory is None:
        searched.append("ament_index_python (not installed)")
    else:
        try:
            yield _by_place(Path(os.path.abspath(share_directory(name))))
        except Exception:  # its PackageNotFoundError, or a broken install
            searched.append("ament_index_python")


def _by_place(folder: Path) -> Path:
    """A package found by its place, whose manifest was not read: noted all the same (see
    `fishbot_urdf.inputs.recording_inputs`), as what the answer stands on."""
    manifest = folder / "package.xml"
    if os.path.isfile(manifest):
        note_inputs((str(manifest),))
    return folder


_AMENT = "ament_index_python.packages"
_ament_missing_from: list[tuple[str, ...]] = []  # the import path it was last not found on


def _ament_lookup() -> Callable[[str], str] | None:
    """ament_index_python's package lookup, if it can be imported. Python remembers no import
    that failed: each is a search of every import folder (34 us, for each package a robot
    names), so the failure is remembered here until the import path changes."""
    unloaded = _AMENT not in sys.modules
    if unloaded and _ament_missing_from and _ament_missing_from[0] == tuple(sys.path):
        return None
    try:
        from ament_index_python.packages import (  # type: ignore[import-not-found]
            get_package_share_directory,
        )
    except ImportError:
        if unloaded:
            _ament_missing_from[:] = [tuple(sys.path)]
        return None
    return get_package_share_directory  # type: ignore[no-any-return]


def upward_folders(folder: str) -> Iterator[str]:
    """``folder`` and each folder above it, up to the root."""
    while True:
        yield folder
        parent = os.path.dirname(folder)
        if parent == folder:
            return
        folder = parent


def _path_list(value: str) -> list[str]:
    return [entry for entry in value.split(os.pathsep) if entry]


def _shown(value: str) -> str:
    return f" ({value})" if value else " (not set)"


def _workspace_src(start: str) -> Path | None:
    """The ``src`` folder of the nearest colcon workspace holding ``start``."""
    for folder in upward_folders(start):
        if os.path.basename(folder) == "src" and os.path.dirname(folder) != folder:
            return Path(folder)
        src = os.path.join(folder, "src")
        if os.path.isdir(src) and any(
            os.path.isdir(os.path.join(folder, marker)) for marker in ("build", "install", "log")
        ):
            return Path(src)
    return None


def _crawl(top: Path, name: str) -> Path | None:
    """The shallowest package called ``name`` under ``top`` (breadth first, names sorted).

    Linked folders are followed (a workspace often links its packages into ``src/``), each
    real folder once.
    """
    queue = deque([top])
    seen: set[str] = set()
    limit = deadline()
    while queue:
        limit.check(f"searching {top} for package {name!r}")
        folder = queue.popleft()
        real = os.path.realpath(folder)
        if real in seen:
            continue
        seen.add(real)
        try:
            entries = sorted(os.scandir(folder), key=lambda e: e.name)
        except OSError:
            continue
        names = {entry.name for entry in entries}
        if "package.xml" in names:
            if package_name(folder / "package.xml") == name:
                return folder
            continue  # packages do not nest
        if any(marker in names for marker in _IGNORE_MARKERS):
            continue
        for entry in entries:
            if not entry.name.startswith(".") and entry.name not in _SKIP_DIRS and _is_dir(entry):
                queue.append(Path(entry.path))
    return None


def _is_dir(entry: os.DirEntry[str]) -> bool:
    """Whether ``entry`` is a folder (or links to one); a link that cannot be followed (a
    loop, no permission) is none."""
    try:
        return entry.is_dir()
    except OSError:
        return False
