"""What a strict XML parser refuses in what TinyXML reads: notes for the recovery rules."""

from __future__ import annotations

import re

from ...catalog.xml import (
    XML_CONTROL_CHAR,
    XML_DECLARATION,
    XML_ENCODING,
    XML_ESCAPE,
    XML_MARKUP,
    XML_OUTSIDE_ROOT,
)
from ._nodes import UNKNOWN, UTF8, Comment, Document, Element, Note, Other, Refused, Text

# What a strict parser accepts where TinyXML found a reference (no DTD: five names only).
_REFERENCE = re.compile(rb"&(?:(amp|lt|gt|quot|apos)|#([0-9]+)|#x([0-9a-fA-F]+));")
_CONTROL = re.compile(rb"[\x01-\x08\x0b\x0c\x0e-\x1f]|\xef\xbf[\xbe\xbf]")
_BOM = b"\xef\xbb\xbf"
# A processing instruction as XML allows it (its target not "xml" in any case).
_PI = re.compile(rb"<\?(?![Xx][Mm][Ll][\s?])[A-Za-z_\x80-\xff][^\s?]*(?:\s.*?)?\?>", re.DOTALL)
_XML_TARGET = re.compile(rb"<\?[Xx][Mm][Ll][\s?]")
_S = rb"[ \t\r\n]"
# The XML declaration as libxml2 accepts it (any 1.x version).
_DECLARATION = re.compile(
    rb"<\?xml" + _S + rb"+version" + _S + rb"*=" + _S + rb"*(?:\"1\.[0-9]+\"|'1\.[0-9]+')"
    rb"(?:"
    + _S
    + rb"+encoding"
    + _S
    + rb"*="
    + _S
    + rb"*(?:\"[A-Za-z][\w.-]*\"|'[A-Za-z][\w.-]*'))?"
    rb"(?:"
    + _S
    + rb"+standalone"
    + _S
    + rb"*="
    + _S
    + rb"*(?:\"(?:yes|no)\"|'(?:yes|no)'))?"
    + _S
    + rb"*\?>"
)
_LITERAL = rb"(?:\"[^\"]*\"|'[^']*')"
# A DOCTYPE as XML allows it, without declarations (those are refused before this).
_DOCTYPE = re.compile(
    rb"<!DOCTYPE" + _S + rb"+[A-Za-z_:][\w.:-]*"
    rb"(?:"
    + _S
    + rb"+(?:SYSTEM"
    + _S
    + rb"+"
    + _LITERAL
    + rb"|PUBLIC"
    + _S
    + rb"+"
    + _LITERAL
    + _S
    + rb"+"
    + _LITERAL
    + rb"))?"
    + _S
    + rb"*(?:\["
    + _S
    + rb"*\]"
    + _S
    + rb"*)?>"
)


def root(document: Document) -> Element:
    """The element urdfdom reads, its first top-level <robot>; notes what else the top level
    holds that a strict parser refuses. Raises Refused when there is no such element."""
    found = next((n for n in document.nodes if isinstance(n, Element) and n.name == b"robot"), None)
    if found is None:
        if document.stop is not None:
            last = document.nodes[-1]
            doctype = isinstance(last, Other) and document.data.startswith(b"<!DOCTYPE", last.start)
            raise Refused(
                (
                    "its DOCTYPE ends at the first '>', inside the [...] part, and "
                    if doctype
                    else ""
                )
                + "it stops reading at this text outside any element, before any <robot>",
                document.stop,
            )
        raise Refused("there is no top-level <robot> element")
    notes, data = document.notes, document.data
    first = 3 if data.startswith(_BOM) else 0
    doctype = False
    for index, node in enumerate(document.nodes):
        after = node.start > found.start
        if isinstance(node, Element):
            if node is not found:
                notes.append(Note(XML_OUTSIDE_ROOT, node.start, "element"))
        elif isinstance(node, Comment):
            if not node.closed:
                notes.append(Note(XML_OUTSIDE_ROOT, node.start, "comment"))
        elif isinstance(node, Text):  # CDATA, which XML allows inside an element only
            notes.append(Note(XML_OUTSIDE_ROOT, node.start, "markup"))
        elif isinstance(node, Other):
            written = data[node.start : node.end]
            if node.declaration and _XML_TARGET.match(written):
                if index or node.start != first:
                    notes.append(Note(XML_DECLARATION, node.start, "misplaced"))
                elif not _DECLARATION.fullmatch(written):
                    notes.append(Note(XML_DECLARATION, node.start, "malformed"))
            elif written.startswith(b"<!DOCTYPE") and not after and not doctype:
                doctype = True
                if not _DOCTYPE.fullmatch(written):
                    notes.append(Note(XML_MARKUP, node.start, "doctype"))
            elif not _PI.fullmatch(written):
                rule = XML_OUTSIDE_ROOT if after else XML_MARKUP
                notes.append(Note(rule, node.start, "markup"))
    if document.stop is not None:
        notes.append(Note(XML_OUTSIDE_ROOT, document.stop, "text"))
    if document.nul is not None:
        notes.append(Note(XML_OUTSIDE_ROOT, document.nul, "nul"))
    return found


def control(data: bytes, start: int, end: int, notes: list[Note]) -> None:
    """Note the first character XML forbids in ``data[start:end]``."""
    found = _CONTROL.search(data, start, end)
    if found:
        kind = "noncharacter" if found[0][0] == 0xEF else "control"
        notes.append(Note(XML_CONTROL_CHAR, found.start(), kind))


def value(data: bytes, start: int, end: int, mode: str, notes: list[Note]) -> None:
    """Note what a strict parser refuses in a quoted attribute value."""
    lt = data.find(b"<", start, end)
    if lt >= 0:
        notes.append(Note(XML_ESCAPE, lt, "lt"))
    references(data, start, end, mode, notes)
    control(data, start, end, notes)


def text(data: bytes, start: int, end: int, mode: str, notes: list[Note]) -> None:
    """Note what a strict parser refuses in text."""
    brackets = data.find(b"]]>", start, end)
    if brackets >= 0:
        notes.append(Note(XML_ESCAPE, brackets, "brackets"))
    references(data, start, end, mode, notes)
    control(data, start, end, notes)


def references(data: bytes, start: int, end: int, mode: str, notes: list[Note]) -> None:
    """Note each '&' that starts no reference XML reads as TinyXML does."""
    amp = data.find(b"&", start, end)
    while amp >= 0:
        found = _REFERENCE.match(data, amp, end)
        if found is None:
            notes.append(Note(XML_ESCAPE, amp, "amp"))
        elif not found[1]:
            code = int(found[2]) if found[2] else int(found[3], 16)
            if not _is_char(code):
                notes.append(Note(XML_ESCAPE, amp, "charref"))
            elif mode != UTF8 and code > (127 if mode == UNKNOWN else 255):
                notes.append(Note(XML_ENCODING, amp, "charref"))  # urdfdom keeps one byte
        amp = data.find(b"&", amp + 1, end)


def inner(data: bytes, node: Other, notes: list[Note]) -> None:
    """Note markup inside an element that TinyXML skips and a strict parser refuses."""
    written = data[node.start : node.end]
    if node.declaration and _XML_TARGET.match(written):
        notes.append(Note(XML_DECLARATION, node.start, "inside"))
    elif not _PI.fullmatch(written):
        notes.append(Note(XML_MARKUP, node.start, "markup"))


def _is_char(code: int) -> bool:
    """True for a character XML 1.0 allows."""
    return (
        code in (0x9, 0xA, 0xD)
        or 0x20 <= code <= 0xD7FF
        or 0xE000 <= code <= 0xFFFD
        or 0x10000 <= code <= 0x10FFFF
    )
