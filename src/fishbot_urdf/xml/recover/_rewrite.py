"""TinyXML's reading of a document, written out as well-formed UTF-8 XML that lxml reads.

Only the robot element is written, with the names, attribute values and nesting TinyXML gave
it; comments and text stay, declarations and markup TinyXML skips go. Where XML cannot hold
what TinyXML read, the closest thing it can is written and a note says so: an undeclared
prefix gets a declaration of its own, an impossible name dots instead of its bad characters, a
character XML forbids U+FFFD.
"""

from __future__ import annotations

import codecs
import re
from collections.abc import Callable
from dataclasses import dataclass

from lxml import etree

from ...catalog import Rule
from ...catalog.xml import XML_DEFAULT_NAMESPACE, XML_ENCODING, XML_MARKUP, XML_UNDECLARED_PREFIX
from ._nodes import LEGACY, UTF8, Comment, Document, Element, Note, Other, Text

# The namespace an undeclared prefix is given (one per prefix).
UNDECLARED = "urn:fishbot-urdf:undeclared-prefix:"

_START = (
    "A-Z_a-z\xc0-\xd6\xd8-\xf6\xf8-\u02ff\u0370-\u037d\u037f-\u1fff\u200c-\u200d"
    "\u2070-\u218f\u2c00-\u2fef\u3001-\ud7ff\uf900-\ufdcf\ufdf0-\ufffd\U00010000-\U000effff"
)
_NCNAME = re.compile(f"[{_START}][{_START}\\-.0-9\xb7\u0300-\u036f\u203f-\u2040]*")
_NOT_NAME = re.compile(f"[^{_START}\\-.0-9\xb7\u0300-\u036f\u203f-\u2040]")
# Characters XML 1.0 cannot hold, even as references.
_ILLEGAL = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")
_ATTRIBUTE_ESCAPES = {"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;"}
_ATTRIBUTE_ESCAPES |= {"\t": "&#9;", "\n": "&#10;", "\r": "&#13;"}  # kept, as urdfdom keeps them
_TEXT_ESCAPES = {"&": "&amp;", "<": "&lt;", ">": "&gt;", "\r": "&#13;"}
_ESCAPE_ATTRIBUTE = re.compile('[&<>"\t\n\r]')
_ESCAPE_TEXT = re.compile("[&<>\r]")
_FALLBACK = {0xDC00 + b: b for b in range(0x80, 0x100)}  # surrogateescape -> ISO-8859-1
_WIDE = re.compile(rb"[\x80-\xff]")


@dataclass(frozen=True, slots=True)
class Rewritten:
    """The robot element as lxml is to read it.

    Attributes:
        data: Well-formed UTF-8 XML.
        starts: The byte offset, in the original file, of each element of ``data`` in order.
        tags: Qualified element names (``prefix:local``) of ``data`` whose start tag in the
            original file is written otherwise (``<`` and the name as bytes there).
    """

    data: bytes
    starts: tuple[int, ...]
    tags: dict[str, bytes]


def rewrite(document: Document, root: Element) -> Rewritten:
    """Write ``root`` out, adding notes to ``document.notes`` for what XML cannot hold."""
    writer = _Writer(document)
    writer.element(root, {})
    return Rewritten(b"".join(writer.out), tuple(writer.starts), writer.tags)


class _Writer:
    def __init__(self, document: Document) -> None:
        self.notes = document.notes
        self.decode = _decoder(document)
        self.out: list[bytes] = []
        self.starts: list[int] = []
        self.tags: dict[str, bytes] = {}
        self.plain: set[str] = set()  # names known to be valid without a prefix

    def note(self, rule: Rule, offset: int, detail: str) -> None:
        self.notes.append(Note(rule, offset, detail))

    def element(self, element: Element, scope: dict[str, str]) -> None:
        self.starts.append(element.start)
        scope = dict(scope)
        declared: list[tuple[str, str]] = []
        plain: list[tuple[str, str, int]] = []
        for attribute in element.attributes:
            name = self.decode(attribute.name)
            value = self.decode(attribute.value.split(b"\0", 1)[0])  # urdfdom's C string
            if name == "xmlns":
                if value:
                    self.note(XML_DEFAULT_NAMESPACE, attribute.start, value)
            elif name.startswith("xmlns:"):
                prefix = name[6:]
                if not _NCNAME.fullmatch(prefix) or prefix in ("xml", "xmlns"):
                    self.note(XML_MARKUP, attribute.start, f"name:{name}")
                elif not value:
                    self.note(XML_UNDECLARED_PREFIX, attribute.start, f"empty:{prefix}")
                else:
                    scope[prefix] = value
                    declared.append((prefix, value))
            else:
                plain.append((name, value, attribute.start))
        own = {prefix for prefix, _ in declared}
        written_name = self.name(self.decode(element.name), element.start, scope, own, declared)
        key_bytes = b"<" + element.name
        if written_name.encode("utf-8") != element.name:
            self.tags.setdefault(written_name, key_bytes)
        parts = [b"<", written_name.encode("utf-8")]
        attributes: list[tuple[str, str]] = []
        seen: set[str] = set()
        for name, value, start in plain:
            written = self.name(name, start, scope, own, declared, attribute=True)
            if written not in seen:
                seen.add(written)
                attributes.append((written, value))
        for prefix, uri in declared:
            parts.append(f' xmlns:{prefix}="{_escape_attribute(uri)}"'.encode())
        for name, value in attributes:
            parts.append(f' {name}="{_escape_attribute(value)}"'.encode())
        self.out.append(b"".join(parts))
        if not element.children:
            self.out.append(b"/>")
            return
        self.out.append(b">")
        for child in element.children:
            if isinstance(child, Element):
                self.element(child, scope)
            elif isinstance(child, Text):
                text = _ILLEGAL.sub("\ufffd", self.decode(child.value.split(b"\0", 1)[0]))
                self.out.append(_ESCAPE_TEXT.sub(lambda m: _TEXT_ESCAPES[m[0]], text).encode())
            elif isinstance(child, Comment):
                self.out.append(b"<!--" + _comment(self.decode(child.value)) + b"-->")
            else:
                assert isinstance(child, Other)  # declarations and markup TinyXML skips
        self.out.append(b"</" + written_name.encode("utf-8") + b">")

    def name(
        self,
        name: str,
        start: int,
        scope: dict[str, str],
        own: set[str],
        declared: list[tuple[str, str]],
        *,
        attribute: bool = False,
    ) -> str:
        """``name`` as XML with namespaces can hold it, declaring a prefix where needed."""
        prefix, colon, local = name.partition(":")
        if not colon:
            if name in self.plain or _NCNAME.fullmatch(name):
                self.plain.add(name)
                return name
        elif _NCNAME.fullmatch(prefix) and _NCNAME.fullmatch(local) and prefix != "xmlns":
            if prefix == "xml" or prefix in scope:
                return name
            self.note(XML_UNDECLARED_PREFIX, start, prefix)
            if prefix not in own:
                uri = UNDECLARED + prefix
                scope[prefix] = uri
                own.add(prefix)
                declared.append((prefix, uri))
            return name
        written = _NOT_NAME.sub(".", name.replace(":", "."))
        if not _NCNAME.fullmatch(written):
            written = "_" + written
        self.note(XML_MARKUP, start, f"name:{name}")
        return written


def _decoder(document: Document) -> Callable[[bytes], str]:
    """How to turn TinyXML's bytes into text, noting how the file is encoded."""
    data = document.data
    label = next(
        (n.encoding for n in document.nodes if isinstance(n, Other) and n.declaration), b""
    ).decode("latin-1")
    try:
        data.decode("utf-8")
        bad = -1
    except UnicodeDecodeError as error:
        bad = error.start
    first_wide = _WIDE.search(data)
    wide = -1 if first_wide is None else first_wide.start()
    if label and not _lxml_knows(label):
        start = next(n.start for n in document.nodes if isinstance(n, Other) and n.declaration)
        document.notes.append(Note(XML_ENCODING, start, f"label:{label}"))
    if document.mode == LEGACY and wide >= 0:
        codec = _single_byte(label)
        if bad < 0 and codec is not None:
            document.notes.append(Note(XML_ENCODING, wide, f"mislabelled:{label}"))
        elif bad >= 0 and codec is not None:
            document.notes.append(Note(XML_ENCODING, wide, f"declared:{label}"))
            return lambda value: value.decode(codec)
    if bad >= 0:
        kind = "utf-8" if document.mode == UTF8 else "bytes"
        document.notes.append(Note(XML_ENCODING, bad, f"invalid:{kind}:{data[bad]:02X}"))
    return _utf8_or_latin1


def _utf8_or_latin1(value: bytes) -> str:
    """UTF-8, with any byte that is not read as ISO-8859-1 (what such files mostly are)."""
    try:
        return value.decode("utf-8")
    except UnicodeDecodeError:
        return value.decode("utf-8", "surrogateescape").translate(_FALLBACK)


def _single_byte(label: str) -> str | None:
    """The Python codec for an ASCII-compatible encoding name, else None (unknown, UTF-16)."""
    try:
        info = codecs.lookup(label)
    except LookupError:
        return None
    if info.name.startswith(("utf-16", "utf-32", "utf_16", "utf_32", "utf-8", "utf_8")):
        return None
    try:
        return info.name if "<robot/>".encode(info.name) == b"<robot/>" else None
    except UnicodeError:  # pragma: no cover - codecs that cannot encode ASCII
        return None


def _lxml_knows(label: str) -> bool:
    """True when libxml2 reads a file declaring encoding ``label`` (ASCII bytes)."""
    if not re.fullmatch(r"[A-Za-z][\w.-]*", label):
        return False
    probe = f'<?xml version="1.0" encoding="{label}"?><a/>'.encode("ascii")
    try:
        etree.fromstring(probe, etree.XMLParser(resolve_entities=False, no_network=True))
    except (etree.XMLSyntaxError, ValueError, LookupError):
        return False
    return True


def _escape_attribute(value: str) -> str:
    value = _ILLEGAL.sub("\ufffd", value)
    return _ESCAPE_ATTRIBUTE.sub(lambda m: _ATTRIBUTE_ESCAPES[m[0]], value)


def _comment(text: str) -> bytes:
    """Comment text XML allows: no '--', no '-' at the end, no forbidden characters."""
    text = _ILLEGAL.sub("", text)
    while "--" in text:
        text = text.replace("--", "- -")
    if text.endswith("-"):
        text += " "
    return text.encode("utf-8")
