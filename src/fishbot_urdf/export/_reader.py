"""The document sdformat's URDF converter builds, and what sdformat's reader makes of it
when `ign sdf -p` prints it: attributes and elements it knows kept in their order, those
it requires and does not find added with their default text, unknown ones copied after
them, comments dropped (from SDFormat 1.9's description, sdf_1.9.json)."""

from __future__ import annotations

import math
import struct
from collections.abc import Callable, Iterator, Mapping
from typing import Any, Protocol

from ..analysis import sdformat
from ..analysis.sdformat import Description, describe, refusal
from ..errors import ConversionError
from ..location import Location

__all__ = ["Element", "Node", "copy", "printed", "read", "single"]


class Element:
    """An element of the converter's document: a tag, attributes in order, a text (None
    for none) and child elements. The converter edits its document as it goes (settings
    replace earlier ones, blobs are moved and re-posed), so this one can be edited."""

    __slots__ = ("attributes", "children", "tag", "text", "where")

    def __init__(
        self,
        tag: str,
        text: str | None = None,
        attributes: list[tuple[str, str]] | None = None,
        children: list[Element] | None = None,
    ) -> None:
        self.tag = tag
        self.text = text
        self.attributes = attributes or []
        self.children = children or []
        self.where: Location | None = None  # where the robot's text writes it, if it does

    def get(self, name: str) -> str | None:
        return next((value for key, value in self.attributes if key == name), None)

    def find(self, tag: str) -> Element | None:
        """The first child named ``tag``."""
        return next((child for child in self.children if child.tag == tag), None)

    def append(self, child: Element) -> Element:
        self.children.append(child)
        return child

    def remove(self, child: Element) -> None:
        self.children = [c for c in self.children if c is not child]

    def put(self, tag: str, text: str, where: Location | None = None) -> Element:
        """A ``<tag>text</tag>`` appended in place of the first one there was (the
        converter's AddKeyValue); ``where`` the setting it is written from."""
        old = self.find(tag)
        if old is not None:
            self.remove(old)
        put = self.append(Element(tag, text))
        put.where = where
        return put

    def clone(self) -> Element:
        cloned = Element(
            self.tag, self.text, list(self.attributes), [c.clone() for c in self.children]
        )
        cloned.where = self.where
        return cloned


class Node(Protocol):
    """What is read of an element of the robot's text (an lxml element)."""

    tag: object
    text: str | None
    attrib: Mapping[Any, Any]
    nsmap: Mapping[str | None, str]

    def __iter__(self) -> Iterator[Node]: ...


def copy(node: Node, place: Callable[[Node], Location | None] | None = None) -> Element:
    """An element of the robot's text as the converter's XML parser holds it: comments
    dropped, a text kept only when it is not all white space and comes before any child
    (each placed by ``place``, when given)."""
    children = [copy(child, place) for child in node if isinstance(child.tag, str)]
    text = node.text if node.text is not None and node.text.strip() else None
    prefixes = {uri: prefix for prefix, uri in node.nsmap.items() if prefix}
    attributes = [(_written(str(k), prefixes), str(v)) for k, v in node.attrib.items()]
    copied = Element(_written(str(node.tag), prefixes), text, attributes, children)
    copied.where = place(node) if place is not None else None
    return copied


def _written(name: str, prefixes: dict[str, str]) -> str:
    """A name as written (``xacro:q``), not as the namespace-aware reader holds it."""
    if not name.startswith("{"):
        return name
    uri, local = name[1:].split("}", 1)
    return f"{prefixes[uri]}:{local}" if uri in prefixes else local


def _attr(value: str) -> str:
    """An attribute's value in single quotes, as sdformat writes one."""
    return "'" + _escape(value).replace("'", "&apos;") + "'"


def read(element: Element, description: Description | None = None) -> Element:
    """``element`` as sdformat's reader keeps it (``description`` its element's; the
    model's when not given)."""
    description = description or describe("model.sdf") or {}
    known = {d["name"]: d for d in reversed(sdformat.children(description))}
    attributes = []
    for name, required, default in description.get("attributes", ()):
        value = element.get(name)
        if value is not None or required == "1":
            attributes.append((name, default if value is None else value.strip()))
    text = None
    if "default" in description:
        if element.text is None:
            text = _reprinted(description, element.where)
        else:
            text = element.text.strip()
            _check(description, text, element.where)
    if description.get("copy"):
        return Element(element.tag, text, attributes, [_copied(c) for c in element.children])
    children = [read(c, known[c.tag]) for c in element.children if c.tag in known]
    present = {c.tag for c in children}
    children += [
        _default(d)
        for d in sdformat.children(description)
        if d["required"] == "1" and d["name"] not in present
    ]
    children += [_copied(c) for c in element.children if c.tag not in known]
    return Element(element.tag, text, attributes, children)


def _copied(element: Element) -> Element:
    """An element the reader copies as it is (unknown, or in a plugin), but for its
    attributes' values, which it trims."""
    attributes = [(name, value.strip()) for name, value in element.attributes]
    return Element(element.tag, element.text, attributes, [_copied(c) for c in element.children])


def _check(description: Description, text: str, where: Location | None) -> None:
    """Refuse a value the reader refuses for its element's type (see `refusal`).

    Raises:
        ConversionError: The reader refuses ``text``.
    """
    why = refusal(description, text)
    if why is not None:
        raise ConversionError(
            f"<{description['name']}> {text!r} {why}: sdformat's reader refuses it",
            target="sdf",
            **_at(where),
        )


def _at(where: Location | None) -> dict[str, Any]:
    """A ConversionError's place: where the value at fault is written, when known."""
    if where is None:
        return {}
    return {"path": where.path, "line": where.line, "column": where.column}


def _reprinted(description: Description, where: Location | None = None) -> str:
    """The text the reader prints for a typed element it finds empty: its default value, as
    its type prints it (a number with 17 significant digits, a bool as 1 or 0).

    Raises:
        ConversionError: The element is required (the reader refuses it empty).
    """
    kind, default = description["type"], description["default"]
    if description["required"] == "1":
        raise ConversionError(
            f"<{description['name']}> is empty, and sdformat's reader refuses a required "
            "element without a value",
            target="sdf",
            **_at(where),
        )
    if kind in ("double", "vector3", "vector2d"):
        return " ".join(f"{float(v):.17g}" for v in default.split())
    if kind in ("float", "color"):
        return " ".join(f"{single(float(v)):.9g}" for v in default.split())
    if kind in ("int", "unsigned int"):
        return str(int(default))
    if kind == "bool":
        return "1" if default.lower() in ("true", "1") else "0"
    return str(default)


def single(value: float) -> float:
    """``value`` as a C float holds it (beyond its range, an infinity)."""
    try:
        held: float = struct.unpack("f", struct.pack("f", value))[0]
    except OverflowError:
        return math.copysign(math.inf, value)
    return held


def _default(description: Description) -> Element:
    """The element the reader adds where a required one is missing."""
    attributes = [(n, d) for n, r, d in description.get("attributes", ()) if r == "1"]
    children = [_default(d) for d in sdformat.children(description) if d["required"] == "1"]
    return Element(description["name"], description.get("default"), attributes, children)


def printed(element: Element, indent: str = "") -> list[str]:
    """The lines sdformat prints for ``element``, attributes in single quotes. (It escapes
    nothing, so that a ``&`` in a text makes what it prints no XML; here it is escaped.)"""
    head = indent + "<" + element.tag + "".join(f" {k}={_attr(v)}" for k, v in element.attributes)
    if element.children:
        lines = [head + ">"]
        for child in element.children:
            lines += printed(child, indent + "  ")
        return [*lines, f"{indent}</{element.tag}>"]
    if element.text is not None:
        return [f"{head}>{_escape(element.text)}</{element.tag}>"]
    return [head + "/>"]


def _escape(text: str) -> str:
    """``text`` with ``&``, ``<`` and ``>`` written as XML entities. (Not xml.sax.saxutils':
    importing it loads urllib, a sixth of the command's start.)"""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
