"""The outline of one file: the links, joints, materials, macros, properties, arguments
and includes it defines, read from its text alone."""

from __future__ import annotations

from ..workspace import Workspace
from ._names import FileNames, names_of
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
    for tag in names.document.tags:
        symbol = _symbol(names, tag)
        if symbol is not None:
            found[tag.index] = symbol
    return _nest(names, found)


def _symbol(names: FileNames, tag: Tag) -> Symbol | None:
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
    for named in names.named:
        if named.tag is tag and named.definition:
            detail = ""
            if named.kind == "joint" and (kind := tag.get("type")):
                detail = kind.value
            return Symbol(
                named.value, _KINDS[named.kind], whole, doc.span(named.start, named.end), detail
            )
    return None


def _nest(names: FileNames, found: dict[int, Symbol]) -> list[Symbol]:
    """The symbols with each one's children those inside it (a robot's, a macro's)."""
    children: dict[int | None, list[int]] = {}
    for index in found:
        holder = next(
            (
                a.index
                for a in names.document.ancestors(names.document.tags[index])
                if a.index in found
            ),
            None,
        )
        children.setdefault(holder, []).append(index)

    def made(index: int) -> Symbol:
        symbol = found[index]
        inner = tuple(made(i) for i in children.get(index, ()))
        if not inner:
            return symbol
        return Symbol(symbol.name, symbol.kind, symbol.span, symbol.selection, symbol.detail, inner)

    return [made(index) for index in children.get(None, ())]
