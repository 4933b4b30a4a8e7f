"""How TinyXML 1 (2.6.2, the XML parser of urdfdom 3 and so of check_urdf) reads bytes.

A model of TinyXML's own parsing functions, step for step, on bytes: what it accepts, what it
refuses, where every node starts, and the bytes it stores for names, attribute values and
text. It also notes, as it goes, what a strict XML parser would refuse (``Note``).

TinyXML reads up to the first NUL byte (urdfdom hands it a C string). Until a declaration
names an encoding it reads byte by byte; ``encoding="UTF-8"`` (or none) makes it step over
UTF-8 sequences by their lead byte, any other name makes it read byte by byte again. It never
converts bytes: a name holds the bytes written.
"""

from __future__ import annotations

import re

from ...catalog import Rule
from ...catalog.xml import XML_ATTRIBUTE, XML_COMMENT, XML_CONTROL_CHAR, XML_ENCODING
from . import _strict as strict
from ._nodes import (
    LEGACY,
    UNKNOWN,
    UTF8,
    Attribute,
    Comment,
    Document,
    Element,
    Node,
    Note,
    Other,
    Refused,
    Text,
    TooDeep,
)

# How many bytes TinyXML takes for a character starting with each byte (its utf8ByteTable:
# 1 for everything that cannot start a sequence).
_LENGTH = bytes([1] * 0xC2 + [2] * 30 + [3] * 16 + [4] * 5 + [1] * 11)
_SPACE = frozenset(b" \t\n\v\f\r")  # C's isspace() in the C locale
_ODD_SPACE = frozenset(b"\v\f")  # white space to TinyXML, not to XML
_BOM = b"\xef\xbb\xbf"
_NOT_CHARACTERS = (b"\xef\xbf\xbe", b"\xef\xbf\xbf")  # U+FFFE, U+FFFF: skipped as white space
# isalpha() of ASCII, and every byte from 127 up ("the unicode set is huge").
_ALPHA = frozenset(range(65, 91)) | frozenset(range(97, 123)) | frozenset(range(127, 256))
_NAME_START = _ALPHA | {ord("_")}
_NAME = _NAME_START | frozenset(b"0123456789-.:")
_ENTITIES = (
    (b"&amp;", b"&"),
    (b"&lt;", b"<"),
    (b"&gt;", b">"),
    (b"&quot;", b'"'),
    (b"&apos;", b"'"),
)
_HEX = frozenset(b"0123456789abcdefABCDEF")
_PLAIN_SPACE = re.compile(rb"[ \t\n\r]*")  # white space to XML too (the common run)
_MAX_DEPTH = 260  # deeper than lxml's 256: such a file is refused anyway


def read(raw: bytes) -> Document:
    """The document TinyXML reads from ``raw``; raises Refused where TinyXML reports an error."""
    nul = raw.find(b"\0")
    data = raw if nul < 0 else raw[:nul]
    return _Reader(data).document(None if nul < 0 else nul)


class _Reader:
    """TinyXML's parsing functions. Positions are byte offsets; ``None`` is its null pointer,
    ``len(data)`` the terminating NUL."""

    def __init__(self, data: bytes) -> None:
        self.data = data
        self.end = len(data)
        self.mode = UNKNOWN
        self.notes: list[Note] = []

    def at(self, i: int) -> int:
        return self.data[i] if i < self.end else 0

    def note(self, rule: Rule, offset: int, detail: str) -> None:
        self.notes.append(Note(rule, offset, detail))

    # -- TiXmlDocument::Parse --------------------------------------------------------------
    def document(self, nul: int | None) -> Document:
        data = self.data
        if not data:
            raise Refused("the document is empty", 0)
        if data.startswith(_BOM):
            self.mode = UTF8
        i = self.skip(0)
        nodes: list[Node] = []
        stop = None
        while i is not None and self.at(i):
            if self.at(i) != ord("<"):  # text at the top level: TinyXML stops reading there
                stop = i
                break
            node, i = self.node(i, 0)
            nodes.append(node)
            if self.mode == UNKNOWN and isinstance(node, Other) and node.declaration:
                label = node.encoding.lower()
                utf8 = not label or label.startswith((b"utf-8", b"utf8"))
                self.mode = UTF8 if utf8 else LEGACY
            i = None if i is None else self.skip(i)
        if not nodes:
            raise Refused("there is no XML element before the first text", stop or 0)
        return Document(data, nodes, self.mode, self.notes, stop, nul)

    # -- TiXmlBase::SkipWhiteSpace --------------------------------------------------------------
    def skip(self, i: int) -> int | None:
        if i >= self.end:
            return None
        data = self.data
        i = _PLAIN_SPACE.match(data, i).end()  # type: ignore[union-attr]  # (always matches)
        while i < self.end:
            if self.mode == UTF8 and data[i] == 0xEF:
                three = data[i : i + 3]
                if three == _BOM:
                    if i:  # (lxml reads it as a character: in a tag, part of a name)
                        self.note(XML_ENCODING, i, "bom")
                    i += 3
                    continue
                if three in _NOT_CHARACTERS:
                    self.note(XML_CONTROL_CHAR, i, "noncharacter")
                    i += 3
                    continue
            if data[i] not in _SPACE:
                break
            if data[i] in _ODD_SPACE:
                self.note(XML_CONTROL_CHAR, i, "space")
            i += 1
        return i

    def equal(self, i: int, tag: bytes, ignore_case: bool = False) -> bool:
        part = self.data[i : i + len(tag)]
        return (part.lower() if ignore_case else part) == tag

    # -- TiXmlNode::Identify and each node's Parse -----------------------------------------
    def node(self, i: int, depth: int) -> tuple[Node, int | None]:
        """The node at ``i`` (a '<'), and where reading goes on."""
        if self.starts_element(i):
            return self.element(i, depth)
        if self.equal(i, b"<?xml", ignore_case=True):
            return self.declaration(i)
        if self.equal(i, b"<!--"):
            return self.comment(i)
        if self.equal(i, b"<![CDATA["):
            close = self.data.find(b"]]>", i + 9)
            if close < 0:  # TinyXML gives up (an error inside an element, not at the top)
                return Text(b"", i), None
            strict.control(self.data, i + 9, close, self.notes)
            return Text(self.data[i + 9 : close], i), close + 3
        close = self.data.find(b">", i + 1)  # TiXmlUnknown: everything up to the first '>'
        end = self.end if close < 0 else close + 1
        return Other(i, end, False, close >= 0), end

    def starts_element(self, i: int) -> bool:
        return self.at(i + 1) in _NAME_START  # '<?' and '<!' never: neither is a letter

    def comment(self, i: int) -> tuple[Node, int]:
        close = self.data.find(b"-->", i + 4)
        end = self.end if close < 0 else close
        text = self.data[i + 4 : end]
        if b"--" in text or text.endswith(b"-"):
            self.note(XML_COMMENT, i, "dashes")
        strict.control(self.data, i + 4, end, self.notes)
        return Comment(text, i, close >= 0), end if close < 0 else close + 3

    def declaration(self, i: int) -> tuple[Node, int | None]:
        node = Other(i, self.end, True)
        p: int | None = i + 5
        while p is not None and self.at(p):
            if self.at(p) == ord(">"):
                node.end = p + 1
                return node, p + 1
            p = self.skip(p)
            assert p is not None
            if self.equal(p, b"encoding", ignore_case=True):
                found = self.attribute(p, in_declaration=True)
                if found is None:
                    return node, None
                node.encoding, p = found[0].value, found[1]
            elif self.equal(p, b"version", True) or self.equal(p, b"standalone", True):
                found = self.attribute(p, in_declaration=True)
                p = None if found is None else found[1]
            else:
                while self.at(p) and self.at(p) != ord(">") and self.at(p) not in _SPACE:
                    p += 1
        return node, None  # TinyXML stops reading here, silently

    # -- TiXmlElement::Parse and ReadValue ---------------------------------------------------
    def element(self, start: int, depth: int) -> tuple[Element, int]:
        if depth > _MAX_DEPTH:
            raise TooDeep("elements are nested too deep", start)
        p = self.skip(start + 1)
        name_end = self.name(p)
        if p is None or name_end is None or not self.at(name_end):
            raise Refused("an element name cannot be read", start)
        element = Element(self.data[p:name_end], start)
        end_tag = b"</" + element.name
        p = name_end
        while True:
            before = p
            q = self.skip(p)
            if q is None or not self.at(q):
                raise Refused("an element is not closed", start)
            p = q
            c = self.at(p)
            if c == ord("/"):
                if self.at(p + 1) != ord(">"):
                    raise Refused("'/' is not followed by '>'", p)
                return element, p + 2
            if c == ord(">"):
                end = self.content(element, p + 1, depth)
                if not self.equal(end, end_tag):
                    raise Refused(f"the end tag of {_tag(element)} is missing", end)
                after = self.skip(end + len(end_tag))
                if after is None or self.at(after) != ord(">"):
                    raise Refused("an end tag is not closed", end)
                return element, after + 1
            found = self.attribute(p)
            if found is None or not self.at(found[1]):
                raise Refused("an attribute cannot be read", p)
            attribute, p = found
            if any(a.name == attribute.name for a in element.attributes):
                raise Refused("an attribute is given twice", attribute.start)
            if before == q and element.attributes:
                self.note(XML_ATTRIBUTE, attribute.start, "unspaced")
            element.attributes.append(attribute)

    def content(self, element: Element, p: int, depth: int) -> int:
        """Read an element's content up to its end tag; returns where the end tag starts."""
        i = self.skip(p)
        while i is not None and self.at(i):
            if self.at(i) != ord("<"):
                found = self.text(i, b"<", trim=True)
                if found is None:
                    i = None
                    break
                value, after = found
                strict.text(self.data, i, after - 1, self.mode, self.notes)
                if value.strip(b" "):
                    element.children.append(Text(value, i))
                i = after - 1
            elif self.equal(i, b"</"):
                return i
            elif self.starts_element(i):  # (not through node(): two frames a level, not three)
                child, i = self.element(i, depth + 1)
                element.children.append(child)
            else:
                node, after2 = self.node(i, depth + 1)
                if isinstance(node, Other):
                    strict.inner(self.data, node, self.notes)
                element.children.append(node)
                i = after2
            i = None if i is None else self.skip(i)
        raise Refused(f"the content of {_tag(element)} is not closed", element.start)

    # -- names, attributes, text ------------------------------------------------------------------
    def name(self, p: int | None) -> int | None:
        """TiXmlBase::ReadName: where the name starting at ``p`` ends (None: no name)."""
        if p is None or self.at(p) not in _NAME_START:
            return None
        while self.at(p) in _NAME:
            p += 1
        return p

    def attribute(self, p: int, in_declaration: bool = False) -> tuple[Attribute, int] | None:
        """TiXmlAttribute::Parse; None where TinyXML gives up."""
        q = self.skip(p)
        if q is None:
            return None
        start = q
        name_end = self.name(q)
        if name_end is None or not self.at(name_end):
            return None
        name = self.data[start:name_end]
        q = self.skip(name_end)
        if q is None or self.at(q) != ord("="):
            return None
        q = self.skip(q + 1)
        if q is None:
            return None
        quote = self.at(q)
        if quote in (ord('"'), ord("'")):
            found = self.text(q + 1, bytes([quote]), trim=False)
            if found is None:
                return None
            if not in_declaration:
                strict.value(self.data, q + 1, found[1] - 1, self.mode, self.notes)
            return Attribute(name, found[0], start, True), found[1]
        value_start = q
        while self.at(q) and self.at(q) not in _SPACE and self.at(q) not in b"/>":
            if self.at(q) in b"'\"":
                return None
            q += 1
        if not in_declaration:
            self.note(XML_ATTRIBUTE, start, "unquoted")
            strict.control(self.data, value_start, q, self.notes)
        return Attribute(name, self.data[value_start:q], start, False), q

    def text(self, p: int | None, end_tag: bytes, *, trim: bool) -> tuple[bytes, int] | None:
        """TiXmlBase::ReadText (white space condensed when ``trim``); None where it fails."""
        if not trim and p is not None and len(end_tag) == 1:
            # The usual value: ASCII up to the quote, no reference. (A UTF-8 lead byte could
            # swallow the quote, and a reference is replaced: those go the long way.)
            close = self.data.find(end_tag, p)
            plain = self.data[p:close]
            if close >= 0 and plain.isascii() and b"&" not in plain:
                return plain, close + 1
        out = bytearray()
        if trim:
            p = self.skip(p) if p is not None else None
        space = False
        while p is not None and self.at(p) and not self.equal(p, end_tag):
            if trim and self.at(p) in _SPACE:
                space = True
                p += 1
                continue
            if space:
                out += b" "
                space = False
            p = self.character(p, out)
        if p is None or not self.at(p):
            return None
        return bytes(out), p + len(end_tag)

    def character(self, p: int, out: bytearray) -> int | None:
        """TiXmlBase::GetChar: append one character (a reference replaced) to ``out``."""
        data = self.data
        length = _LENGTH[data[p]] if self.mode == UTF8 else 1
        if length > 1:
            out += data[p : p + length]
            return p + length
        if data[p] != ord("&"):
            out.append(data[p])
            return p + 1
        return self.reference(p, out)

    def reference(self, p: int, out: bytearray) -> int | None:
        """TiXmlBase::GetEntity: a reference at ``p``; an unknown one loses its '&'."""
        data = self.data
        if self.at(p + 1) == ord("#") and self.at(p + 2):
            hexa = self.at(p + 2) == ord("x")
            semicolon = data.find(b";", p + (3 if hexa else 2))
            if semicolon < 0:
                return None
            code, scale, q = 0, 1, semicolon - 1
            while data[q] != (ord("x") if hexa else ord("#")):
                if data[q] not in (_HEX if hexa else b"0123456789"):
                    return None
                # an unsigned long sum of unsigned (32-bit) products, as in C
                digit = int(chr(data[q]), 16)
                code = (code + (scale * digit & 0xFFFFFFFF)) & 0xFFFFFFFFFFFFFFFF
                scale = scale * (16 if hexa else 10) & 0xFFFFFFFF
                q -= 1
            out += _utf8(code) if self.mode == UTF8 else bytes([code & 0xFF])
            return semicolon + 1
        for written, replacement in _ENTITIES:
            if data.startswith(written, p):
                out += replacement
                return p + len(written)
        return p + 1  # TinyXML drops the '&' and reads on


def _tag(element: Element) -> str:
    return f"<{element.name.decode('utf-8', 'replace')}>"


def _utf8(code: int) -> bytes:
    """TiXmlBase::ConvertUTF32ToUTF8: up to 4 bytes, nothing from 0x200000 up."""
    if code < 0x80:
        return bytes([code])
    if code >= 0x200000:
        return b""
    length = 2 if code < 0x800 else 3 if code < 0x10000 else 4
    out = bytearray(length)
    for k in range(length - 1, 0, -1):
        out[k] = (code | 0x80) & 0xBF
        code >>= 6
    out[0] = (code | (0x00, 0x00, 0xC0, 0xE0, 0xF0)[length]) & 0xFF
    return bytes(out)
