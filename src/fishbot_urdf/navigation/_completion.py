"""What may be written at a place: read from the text before it, which a file being
edited leaves unfinished."""

from __future__ import annotations

import re

from ..catalog import all_rules
from ..extensions import TAGS, Target, plugin_target
from ..model import JointType
from ._names import XACRO_TAGS, Macro
from ._scan import Document, Tag
from ._schema import ATTRIBUTES, CHILDREN, DESCRIPTIONS
from ._table import Table
from .answers import Completion

__all__ = ["completions"]

_IGNORE = re.compile(r"fishbot:\s*ignore\[[^\]]*$")
_OPEN_VALUE = re.compile(r"([^\s=/<>\"']+)\s*=\s*([\"'])([^\"']*)$")
_ATTRIBUTE_NAMES = re.compile(r"([^\s=/<>\"']+)\s*=")


def completions(table: Table, path: str, line: int, column: int) -> list[Completion]:
    doc = table.document(path)
    if doc is None:
        return []
    offset = doc.offset(line, column)
    text = doc.text
    comment = text.rfind("<!--", 0, offset)
    if comment >= 0 and text.rfind("-->", comment, offset) < 0:
        if _IGNORE.search(text, comment, offset):
            return [Completion(r.id, "rule", r.summary) for r in all_rules()]
        return []
    lt = text.rfind("<", 0, offset)
    if lt >= 0 and text.find(">", lt, offset) < 0:
        return _in_tag(table, doc, lt, offset)
    outer = _enclosing(doc, offset)
    written = text[text.rfind(">", 0, offset) + 1 : offset]
    found = _substitution(table, doc, written, outer)
    if found is not None:
        return found
    target = plugin_target(outer.name) if outer is not None else None
    if target is Target.JOINT:
        return _joints(table)
    if target is Target.LINK:
        return _links(table)
    return []


def _in_tag(table: Table, doc: Document, lt: int, offset: int) -> list[Completion]:
    head = doc.text[lt + 1 : offset]
    outer = _enclosing(doc, lt)
    if not re.search(r"\s", head):
        if head.startswith("/"):
            return []
        if head.startswith("xacro:"):
            return _macros(table) + [
                Completion(name, "element", "xacro") for name in sorted(XACRO_TAGS)
            ]
        context = _urdf_context(doc, outer)
        return [
            Completion(name, "element", DESCRIPTIONS.get(name, ""))
            for name in CHILDREN.get(context, ())
        ]
    tag = re.match(r"[^\s/>]+", head)
    name = tag[0] if tag else ""
    value = _OPEN_VALUE.search(head)
    if value is not None:
        found = _substitution(table, doc, value[3], outer)
        if found is not None:
            return found
        return _values(table, doc, name, value[1], outer)
    ends = [i for i in (doc.text.find(">", offset), doc.text.find("<", offset)) if i >= 0]
    given = set(_ATTRIBUTE_NAMES.findall(doc.text, lt, min(ends, default=len(doc.text))))
    if name.startswith("xacro:"):
        macro = table.macros().get(name[len("xacro:") :])
        if macro is None:
            return []
        return [
            Completion(
                p.name, "parameter", f"default {p.default}" if p.default is not None else "required"
            )
            for p in macro.params.values()
            if p.name not in given and not p.block
        ]
    return [Completion(a, "attribute") for a in ATTRIBUTES.get(name, ()) if a not in given]


def _values(
    table: Table, doc: Document, tag: str, attribute: str, outer: Tag | None
) -> list[Completion]:
    context = _urdf_context(doc, outer)
    if tag in ("parent", "child") and attribute == "link":
        return _links(table)
    if tag == "gazebo" and attribute == "reference":
        return _links(table) + _joints(table)
    if (tag == "mimic" and attribute == "joint") or (
        tag == "joint" and attribute == "name" and context in TAGS
    ):
        return _joints(table)
    if tag == "joint" and attribute == "type":
        return [Completion(t.value, "value") for t in JointType]
    return []


def _substitution(
    table: Table, doc: Document, written: str, outer: Tag | None
) -> list[Completion] | None:
    """The names a ``${`` or ``$(arg`` left open takes."""
    opened = written.rfind("${")
    if opened >= 0 and written.find("}", opened) < 0:
        macro = _macro_at(table, doc, outer)
        found = []
        if macro is not None:
            about = f"parameter of macro {macro.name}"
            found = [Completion(p.name, "parameter", about) for p in macro.params.values()]
        properties = table.properties()
        for name, (_, tag) in sorted(properties.items()):
            value = tag.get("value")
            found.append(Completion(name, "property", value.value if value is not None else ""))
        return found
    arg = written.rfind("$(arg")
    if arg >= 0 and written.find(")", arg) < 0:
        return [
            Completion(name, "arg", tag.get("default").value if tag.get("default") else "")  # type: ignore[union-attr]
            for name, tag in sorted(table.args().items())
        ]
    return None


def _macro_at(table: Table, doc: Document, outer: Tag | None) -> Macro | None:
    names = table.files.get(doc.path)
    if names is None or outer is None:
        return None
    if outer.name == "xacro:macro":
        attribute = outer.get("name")
        return names.macros.get(attribute.value) if attribute else None
    return names.macro_of(outer)


def _enclosing(doc: Document, offset: int) -> Tag | None:
    """The innermost element open at ``offset``."""
    inner = None
    for tag in doc.tags:
        if tag.start >= offset:
            break
        if tag.head_end <= offset < tag.end or (
            tag.end >= len(doc.text) and tag.head_end <= offset
        ):
            inner = tag
    return inner


def _urdf_context(doc: Document, outer: Tag | None) -> str:
    """The URDF element that holds a place, past xacro's own elements (a macro's body is
    written for the robot)."""
    tag = outer
    while tag is not None and tag.xacro:
        tag = doc.tags[tag.parent] if tag.parent is not None else None
    if tag is None:
        return "robot" if outer is not None else ""
    return tag.name


def _links(table: Table) -> list[Completion]:
    robot = table.analysis.robot if table.analysis else None
    names = [link.name for link in robot.links] if robot else _literal(table, "link")
    return [Completion(name, "link") for name in names]


def _joints(table: Table) -> list[Completion]:
    robot = table.analysis.robot if table.analysis else None
    if robot is not None:
        return [
            Completion(j.name, "joint", f"{j.type.value}: {j.parent} → {j.child}")
            for j in robot.joints
        ]
    return [Completion(name, "joint") for name in _literal(table, "joint")]


def _literal(table: Table, kind: str) -> list[str]:
    return sorted(
        {
            key[1]
            for key, entries in table.by_key.items()
            if key[0] == kind and any(e.definition for e in entries)
        }
    )


def _macros(table: Table) -> list[Completion]:
    found = []
    for name, macro in sorted(table.macros().items()):
        params = " ".join(p.name for p in macro.params.values())
        found.append(Completion(name, "macro", params))
    return found
