"""Every name one robot's files write, with its place, built once: the files' own facts
joined to the robot's analysis, which tells which link a name a macro builds is and
follows a name handed to a macro to the call that gives it."""

from __future__ import annotations

import bisect
import os
from collections import defaultdict
from dataclasses import dataclass, field

from ..analysis import Analysis
from ..errors import FishbotUrdfError
from ..location import Location, calls_of
from ..workspace import Workspace
from ._names import Entry, FileNames, Key, Macro, names_of
from ._scan import Document, Tag, scan
from .answers import Span

__all__ = ["Table", "build", "normal"]


def normal(path: str) -> str:
    return os.path.normpath(os.path.abspath(path))


@dataclass(slots=True, eq=False)
class Table:
    """The names of a robot's files (or of one file alone, with no analysis)."""

    files: dict[str, FileNames]
    analysis: Analysis | None
    by_key: dict[Key, list[Entry]] = field(default_factory=lambda: defaultdict(list))
    by_path: dict[str, list[Entry]] = field(default_factory=lambda: defaultdict(list))
    _starts: dict[str, list[int]] = field(default_factory=dict)
    _added: set[tuple[Key, str, int]] = field(default_factory=set)

    def add(self, entry: Entry) -> None:
        """Note ``entry``, unless its name is already noted at its place."""
        place = (entry.key, entry.path, entry.start)
        if place in self._added:
            return
        self._added.add(place)
        self.by_key[entry.key].append(entry)
        self.by_path[entry.path].append(entry)

    def finish(self) -> None:
        for path, entries in self.by_path.items():
            entries.sort(key=lambda e: (e.start, -e.end))
            self._starts[path] = [e.start for e in entries]

    def document(self, path: str) -> Document | None:
        names = self.files.get(normal(path))
        return names.document if names is not None else None

    def at(self, path: str, line: int, column: int) -> list[Entry]:
        """The entries written at the place (the innermost, when one holds another; a
        name a macro builds is written in one place for each link it makes)."""
        path = normal(path)
        doc = self.document(path)
        if doc is None:
            return []
        offset = doc.offset(line, column)
        entries = self.by_path.get(path, [])
        stop = bisect.bisect_right(self._starts.get(path, []), offset)
        holding = [e for e in entries[:stop] if e.start <= offset <= e.end]
        if not holding:
            return []
        width = min(e.end - e.start for e in holding)
        return [e for e in holding if e.end - e.start == width]

    def span(self, entry: Entry) -> Span:
        return self.files[entry.path].document.span(entry.start, entry.end)

    def macros(self) -> dict[str, Macro]:
        found: dict[str, Macro] = {}
        for names in self.files.values():
            for name, macro in names.macros.items():
                found.setdefault(name, macro)
        return found

    def properties(self) -> dict[str, tuple[FileNames, Tag]]:
        """The properties every file defines outside macros, by name."""
        found: dict[str, tuple[FileNames, Tag]] = {}
        for names in self.files.values():
            for (_, name, scope), tag in names.properties.items():
                if not scope:
                    found.setdefault(name, (names, tag))
        return found

    def args(self) -> dict[str, Tag]:
        found: dict[str, Tag] = {}
        for names in self.files.values():
            for name, tag in names.args.items():
                found.setdefault(name, tag)
        return found


def build(workspace: Workspace, paths: list[str], analysis: Analysis | None) -> Table:
    """The table of the files ``paths`` (those that can be read), with the robot's analysis."""
    files: dict[str, FileNames] = {}
    for path in paths:
        key = normal(path)
        if key in files:
            continue
        try:
            data = workspace.read(key)
        except FishbotUrdfError:
            continue
        document = scan(key, data.decode("utf-8", "replace"))
        files[key] = names_of(document, workspace.packages)
    table = Table(files, analysis)
    links = {link.name for link in analysis.robot.links} if analysis else set()
    joints = {joint.name for joint in analysis.robot.joints} if analysis else set()
    for names in files.values():
        for entry in names.entries:
            table.add(entry)
        for named in names.named:
            if not named.literal:
                continue
            kind = named.kind
            if kind == "link or joint":
                kind = "joint" if named.value in joints and named.value not in links else "link"
            entry = Entry(
                (kind, named.value, ""),
                names.document.path,
                named.start,
                named.end,
                named.definition,
            )
            table.add(entry)
    if analysis is not None:
        _join(table, analysis)
    table.finish()
    return table


def _join(table: Table, analysis: Analysis) -> None:
    """The names macros build or are handed, placed from where the reader found each
    element (and the calls that made it)."""
    robot = analysis.robot
    for link in robot.links:
        _place(table, ("link", link.name, ""), link.source, "name", definition=True)
    for joint in robot.joints:
        key = ("joint", joint.name, "")
        _place(table, key, joint.source, "name", definition=True)
        found = _tag(table, joint.source)
        if found is None:
            continue
        names, tag = found
        for child in tag.children:
            end = names.document.tags[child]
            if end.name in ("parent", "child") and (attribute := end.get("link")):
                name = joint.parent if end.name == "parent" else joint.child
                _trace(
                    table,
                    ("link", name, ""),
                    names,
                    end,
                    attribute.value,
                    attribute.start,
                    attribute.end,
                    calls_of(joint.source),
                    False,
                )
    link_names = {link.name for link in robot.links}
    for reference in analysis.references:
        kind = "link" if reference.name in link_names else "joint"
        key = (kind, reference.name, "")
        found = _tag(table, reference.source)
        if found is None:
            continue
        names, tag = found
        attribute = tag.get("reference" if tag.name == "gazebo" else "name")
        if tag.name in ("gazebo", "joint") and attribute is not None:
            _trace(
                table,
                key,
                names,
                tag,
                attribute.value,
                attribute.start,
                attribute.end,
                calls_of(reference.source),
                False,
            )
        elif (text := names.document.inner_text(tag)) is not None:
            value = names.document.text[text.start : text.end]
            start = text.start + len(value) - len(value.lstrip())
            value = value.strip()
            _trace(
                table,
                key,
                names,
                tag,
                value,
                start,
                start + len(value),
                calls_of(reference.source),
                False,
            )


def _tag(table: Table, where: Location | None) -> tuple[FileNames, Tag] | None:
    if where is None:
        return None
    names = table.files.get(normal(where.path))
    if names is None:
        return None
    tag = names.document.tag_at(where.line, where.column)
    return None if tag is None else (names, tag)


def _place(
    table: Table, key: Key, where: Location | None, attribute_name: str, *, definition: bool
) -> None:
    found = _tag(table, where)
    if found is None:
        return
    names, tag = found
    attribute = tag.get(attribute_name)
    if attribute is not None:
        _trace(
            table,
            key,
            names,
            tag,
            attribute.value,
            attribute.start,
            attribute.end,
            calls_of(where),
            definition,
        )


def _trace(
    table: Table,
    key: Key,
    names: FileNames,
    tag: Tag,
    value: str,
    start: int,
    end: int,
    calls: tuple[tuple[str, Location], ...],
    definition: bool,
) -> None:
    """Add the place of a name written as ``value``; one that is a macro's parameter
    (``${param}``) is followed to the call that gives it."""
    first = (names, start, end)
    if "$" in value:
        for _, site in calls:
            macro = names.macro_of(tag)
            param = value[2:-1].strip() if value.startswith("${") and value.endswith("}") else ""
            if macro is None or param not in macro.params:
                break
            found = _tag(table, site)
            given = found[1].get(param) if found else None
            if found is None or given is None:
                break
            names, tag = found
            value, start, end = given.value, given.start, given.end
            if "$" not in value:
                break
    literal = "$" not in value and "&" not in value and value == key[1]
    table.add(Entry(key, names.document.path, start, end, definition, literal))
    if first[0] is not names or first[1] != start:  # followed to a call: the body's place too
        table.add(Entry(key, first[0].document.path, first[1], first[2], False, False, via=True))
