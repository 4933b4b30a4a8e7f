"""The outline of one file: the links, joints, materials, macros, properties, arguments
and includes it defines, read from its text alone."""

from __future__ import annotations

from ..workspace import Workspace
from ._names import FileNames, Named, names_of
from ._scan import Tag, scan
from ._table import normal
from .answers import Symbol

__all__ = ["symbols"]

_KINDS = {"link": "link", "joint": "joint", "material": "material"}


def symbols(workspace: Workspace, path: str) -> list[Symbol]:
    """What the file ``path`` (read through ``workspace``) defines, in file order, a
    macro's links, joints and properties as its children.

    Raises:
        InputError: The file cannot be read.
    """
    key = normal(path)
    text = workspace.read(key).decode("utf-8", "replace")
    names = names_of(scan(key, text), workspace.packages)
    found: dict[int, Symbol] = {}
    defining = {named.tag.index: named for named in names.named if named.definition}
    for tag in names.document.tags:
        symbol = _symbol(names, tag, defining.get(tag.index))
        if symbol is not None:
            found[tag.index] = symbol
    return _nest(names, found)


def _symbol(names: FileNames, tag: Tag, named: Named | None) -> Symbol | None:
    doc = names.document
    whole = doc.span(tag.start, max(tag.end, tag.head_end))
    if tag.name == "xacro:macro" and (name := tag.get("name")):
        macro = names.macros.get(name.value)
        params = " ".join(
            p.name + (f":={p.default}" if p.default is not None else "")
            for p in (macro.params.values() if macro else ())
        )
        return Symbol(name.value, "macro", whole, doc.span(name.start, name.end), params)
    if tag.name in ("xacro:property", "xacro:arg") and (name := tag.get("name")):
        value = tag.get("value") or tag.get("default")
        detail = value.value if value is not None else ""
        return Symbol(name.value, tag.local, whole, doc.span(name.start, name.end), detail)
    if tag.name == "xacro:include" and (filename := tag.get("filename")):
        span = doc.span(filename.start, filename.end)
        return Symbol(filename.value, "include", whole, span)
    if tag.name == "robot" and (name := tag.get("name")):
        return Symbol(name.value, "robot", whole, doc.span(name.start, name.end))
    if named is not None:
        detail = ""
        if named.kind == "joint" and (kind := tag.get("type")):
            detail = kind.value
        selection = doc.span(named.start, named.end)
        return Symbol(named.value, _KINDS[named.kind], whole, selection, detail)
    return None


def _nest(names: FileNames, found: dict[int, Symbol]) -> list[Symbol]:
    """The symbols with each one's children those inside it (a robot's, a macro's)."""
    tags = names.document.tags
    holder: list[int | None] = [None] * len(tags)  # the innermost symbol holding each tag
    children: dict[int | None, list[int]] = {}
    for tag in tags:
        parent = tag.parent
        holder[tag.index] = (
            None if parent is None else (parent if parent in found else holder[parent])
        )
        if tag.index in found:
            children.setdefault(holder[tag.index], []).append(tag.index)
    made: dict[int, Symbol] = {}
    for index in sorted(found, reverse=True):  # a symbol's children come after it
        symbol = found[index]
        inner = tuple(made[i] for i in children.get(index, ()))
        if inner:
            symbol = Symbol(
                symbol.name, symbol.kind, symbol.span, symbol.selection, symbol.detail, inner
            )
        made[index] = symbol
    return [made[index] for index in children.get(None, ())]
