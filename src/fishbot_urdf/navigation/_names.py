"""What one file says about names, read from its scan: the macros, properties and
arguments it defines, every ``${...}`` and ``$(arg ...)`` use, its includes, and where it
writes a link, joint or material name (literally or as an expression)."""

from __future__ import annotations

import keyword
import os
import re
from dataclasses import dataclass, field

from ..errors import FishbotUrdfError
from ..extensions import Target, plugin_target
from ..packages import PackageFinder
from ._scan import Attribute, Document, Tag

__all__ = ["Entry", "FileNames", "Key", "Macro", "Named", "Param", "names_of"]

Key = tuple[str, str, str]
"""What a name names: (kind, name, scope); the scope is the macro for a parameter."""

# Elements of xacro itself: every other ``xacro:`` element calls a macro.
XACRO_TAGS = frozenset(
    {
        "macro",
        "property",
        "arg",
        "include",
        "if",
        "unless",
        "insert_block",
        "call",
        "element",
        "attribute",
        "eval",
    }
)

_SUBSTITUTION = re.compile(r"\$\{([^}]*)\}?|\$\((arg|find)\s+([^)\s]*)\s*\)?")
_STRING = re.compile(r"'[^']*'?|\"[^\"]*\"?")
_IDENTIFIER = re.compile(r"(?<![\w.])([A-Za-z_]\w*)")
_PARAM = re.compile(r"(\*{0,2})([A-Za-z_][\w]*)(?::=(\^\|?)?('[^']*'|\"[^\"]*\"|\S*))?")


@dataclass(frozen=True, slots=True)
class Entry:
    """A name written at a place: what it names, whether it defines it there, and whether
    the place holds exactly the name (so that renaming can rewrite it)."""

    key: Key
    path: str
    start: int
    end: int
    definition: bool
    literal: bool = True
    via: bool = False  # handed to a macro as ${param}: renaming rewrites the call instead


@dataclass(frozen=True, slots=True)
class Param:
    name: str
    default: str | None
    start: int
    end: int
    block: bool = False


@dataclass(slots=True, eq=False)
class Macro:
    name: str
    tag: Tag
    params: dict[str, Param]
    path: str


@dataclass(frozen=True, slots=True)
class Named:
    """Where a link, joint or material name is written: ``kind`` is ``link``, ``joint``,
    ``link or joint`` or ``material``; ``value`` as written (maybe an expression)."""

    kind: str
    definition: bool
    tag: Tag
    value: str
    start: int
    end: int

    @property
    def literal(self) -> bool:
        return "$" not in self.value and "&" not in self.value


@dataclass(slots=True, eq=False)
class FileNames:
    document: Document
    entries: list[Entry] = field(default_factory=list)
    macros: dict[str, Macro] = field(default_factory=dict)
    properties: dict[Key, Tag] = field(default_factory=dict)
    args: dict[str, Tag] = field(default_factory=dict)
    includes: list[tuple[Tag, Attribute, str | None]] = field(default_factory=list)
    named: list[Named] = field(default_factory=list)

    def macro_of(self, tag: Tag) -> Macro | None:
        """The macro whose body holds ``tag``."""
        if tag.macro is None:
            return None
        outer = self.document.tags[tag.macro]
        name = outer.get("name")
        macro = self.macros.get(name.value) if name else None
        return macro if macro is not None and macro.tag is outer else None


def names_of(document: Document, packages: PackageFinder | None) -> FileNames:
    """Everything ``document`` defines and uses by name."""
    found = FileNames(document)
    for tag in document.tags:  # definitions first: the uses look up the scopes
        if tag.name == "xacro:macro" and (name := tag.get("name")):
            found.macros[name.value] = Macro(name.value, tag, _params(tag), document.path)
    for tag in document.tags:
        _read_tag(found, tag, packages)
    for text in document.texts:
        owner = document.tags[text.parent] if text.parent is not None else None
        _uses(found, text.start, document.text[text.start : text.end], owner)
        if owner is not None:
            _plugin_names(found, owner, text.start, text.end)
    return found


def _params(tag: Tag) -> dict[str, Param]:
    params = tag.get("params")
    if params is None:
        return {}
    found = {}
    for match in _PARAM.finditer(params.value):
        default = match[4]
        if default and default[0] in "'\"":
            default = default[1:-1]
        found[match[2]] = Param(
            match[2],
            default,
            params.start + match.start(2),
            params.start + match.end(2),
            bool(match[1]),
        )
    return found


def _scope(found: FileNames, tag: Tag) -> str:
    macro = found.macro_of(tag)
    return macro.name if macro is not None else ""


def _read_tag(found: FileNames, tag: Tag, packages: PackageFinder | None) -> None:
    path, local = found.document.path, tag.local
    name = tag.get("name")
    if tag.xacro and local not in XACRO_TAGS:
        key = ("macro", local, "")
        start = tag.name_start + len("xacro:")
        found.entries.append(Entry(key, path, start, start + len(local), False))
        if tag.end_name_start is not None:
            start = tag.end_name_start + len("xacro:")
            found.entries.append(Entry(key, path, start, start + len(local), False))
        for attribute in tag.attributes:
            end = attribute.name_start + len(attribute.name)
            given = ("param", attribute.name, local)
            found.entries.append(Entry(given, path, attribute.name_start, end, False))
    elif tag.name == "xacro:macro" and name is not None:
        found.entries.append(Entry(("macro", name.value, ""), path, name.start, name.end, True))
        macro = found.macros.get(name.value)
        for param in macro.params.values() if macro else ():
            key = ("param", param.name, name.value)
            found.entries.append(Entry(key, path, param.start, param.end, True))
    elif tag.name in ("xacro:property", "xacro:arg") and name is not None:
        if tag.local == "property":
            key = ("property", name.value, _scope(found, tag))
            found.properties.setdefault(key, tag)
        else:
            key = ("arg", name.value, "")
            found.args.setdefault(name.value, tag)
        found.entries.append(Entry(key, path, name.start, name.end, True))
    elif tag.name == "xacro:include" and (filename := tag.get("filename")):
        target = _included(filename.value, path, packages)
        found.includes.append((tag, filename, target))
        if target is not None:
            key = ("file", target, "")
            found.entries.append(Entry(key, path, filename.start, filename.end, False))
    for attribute in tag.attributes:
        if tag.name == "xacro:macro" and attribute.name == "params":
            continue
        _uses(found, attribute.start, attribute.value, tag)
    _named(found, tag)


def _uses(found: FileNames, base: int, value: str, tag: Tag | None) -> None:
    """The properties, parameters and arguments ``value`` (written at ``base``) uses."""
    if "$" not in value:
        return
    macro = found.macro_of(tag) if tag is not None else None
    path = found.document.path
    for match in _SUBSTITUTION.finditer(value):
        if match[2] == "arg" and match[3]:
            start = base + match.start(3)
            key = ("arg", match[3], "")
            found.entries.append(Entry(key, path, start, start + len(match[3]), False))
        elif match.start(1) >= 0 and not (match.start() and value[match.start() - 1] == "$"):
            inner = match.start(1)
            code = _STRING.sub(lambda m: " " * len(m[0]), match[1])
            for word in _IDENTIFIER.finditer(code):
                ident = word[1]
                if keyword.iskeyword(ident):
                    continue
                start = base + inner + word.start(1)
                key = _resolve(found, ident, macro)
                found.entries.append(Entry(key, path, start, start + len(ident), False))


def _resolve(found: FileNames, ident: str, macro: Macro | None) -> Key:
    """What ``ident`` in an expression names: the macro's parameter, a property of the
    macro's own, or a property of the file (or of another file: the scope is the same)."""
    if macro is not None:
        if ident in macro.params:
            return ("param", ident, macro.name)
        if ("property", ident, macro.name) in found.properties:
            return ("property", ident, macro.name)
    return ("property", ident, "")


def _included(filename: str, near: str, packages: PackageFinder | None) -> str | None:
    """The file an include names, with ``$(find ...)`` resolved; None when it is built by
    an expression or names a package no one knows."""
    text = filename
    for match in list(_SUBSTITUTION.finditer(filename))[::-1]:
        if match[2] != "find" or packages is None:
            return None
        try:
            folder = str(packages.find(match[3], near=near))
        except FishbotUrdfError:
            return None
        text = text[: match.start()] + folder + text[match.end() :]
    return os.path.normpath(os.path.join(os.path.dirname(near), text))


def _named(found: FileNames, tag: Tag) -> None:
    """Where ``tag`` writes a link, joint or material name."""
    doc = found.document
    extension = tag.extension
    parent = doc.tags[tag.parent].name if tag.parent is not None else None

    def add(kind: str, attribute_name: str, definition: bool) -> None:
        attribute = tag.get(attribute_name)
        if attribute is not None:
            found.named.append(
                Named(kind, definition, tag, attribute.value, attribute.start, attribute.end)
            )

    if extension is None:
        if tag.name in ("link", "joint") and parent != tag.name:
            add(tag.name, "name", True)
        elif tag.name in ("parent", "child") and parent == "joint":
            add("link", "link", False)
        elif tag.name == "mimic" and parent == "joint":
            add("joint", "joint", False)
        elif tag.name == "material" and parent not in ("gazebo",):
            defines = bool(tag.children) or parent in (None, "robot", "xacro:macro")
            add("material", "name", defines)
        elif tag.name == "gazebo":
            add("link or joint", "reference", False)
    elif tag.name == "joint" and parent in ("transmission", "ros2_control"):
        add("joint", "name", False)


def _plugin_names(found: FileNames, tag: Tag, start: int, end: int) -> None:
    """The joint or link names the text of a Gazebo plugin's element gives."""
    target = plugin_target(tag.name)
    if target is None or not tag.plugin:
        return
    text = found.document.text
    parts = [(start, end)]
    if target is Target.JOINT:
        parts, at = [], start
        for piece in text[start:end].split(","):
            parts.append((at, at + len(piece)))
            at += len(piece) + 1
    for begin, stop in parts:
        value = text[begin:stop]
        begin += len(value) - len(value.lstrip())
        stop -= len(value) - len(value.rstrip())
        if target is Target.LINK and text.startswith("/", begin):
            begin += 1
        if begin < stop:
            kind = "joint" if target is Target.JOINT else "link"
            found.named.append(Named(kind, False, tag, text[begin:stop], begin, stop))
