"""Read what urdfdom reads: the XML that check_urdf accepts and lxml refuses, recovered.

check_urdf (urdfdom 3, TinyXML 2.6.2) accepts files no strict XML parser does. Each such
file is read here as TinyXML reads it (``_tinyxml``), written out as well-formed XML
(``_rewrite``) and given one warning per rule below; everything TinyXML refuses stays refused.
Measured with check_urdf 3.0.1, lxml 6.1 (libxml2 2.14), xacro 2.1.1 (expat) and yourdfpy
0.0.60 (lxml, then lxml's recover mode): ok reads it as urdfdom does, no refuses it, ``~``
reads something else without an error, crash raises an exception, - not measured.

===========================================  ===  ====  =====  ========  =====================
case                                         cu   lxml  xacro  yourdfpy  rule
===========================================  ===  ====  =====  ========  =====================
``<?xml version="0.0"?>`` (2.0, "abc")       ok   no    ok     ok        xml-declaration
declaration without version, unquoted, junk  ok   no    no     ok        xml-declaration
declaration after a blank line, a comment    ok   no    no     ok        xml-declaration
  or a BOM and a newline; twice; inside
undeclared prefix ``<drake:x>``, ``d:a=``    ok   no    no     ok        xml-undeclared-prefix
``xmlns="..."`` on ``<robot>``               ok   ~     ok     ~         xml-default-namespace
ISO-8859-1 declared, non-ASCII bytes         ok*  ok    no     ok        xml-encoding
ISO-8859-1 bytes undeclared, bad UTF-8       ok*  no    no     ok        xml-encoding
declared ISO-8859-1, file is UTF-8           ok   ~     ok     ~         xml-encoding
name lxml does not know ("latin-1")          ok   no    ok     ok        xml-encoding
UTF-16 declared, the file 8-bit              ok   no    ok     crash     xml-encoding
``&#228;`` and no UTF-8 declaration          ok*  ~     -      -         xml-encoding
stray ``&``, ``&foo;``, ``&amp`` (no ``;``)  ok   no    no     ~         xml-escape
``<`` in a value, ``]]>`` in text            ok   no    no     ok        xml-escape
``&#0;``, ``&#1;``, ``&#x110000;``           ok   no    no     crash     xml-escape
``&foo;`` after a DOCTYPE                    ok   ~     ~      ~         xml-escape
unquoted ``a=b``; ``a="1"b="2"``             ok   no    no     crash     xml-attribute
``--`` inside a comment, ``--->``            ok   no    no     ~         xml-comment
control character, form feed as a space      ok   no    no     crash     xml-control-char
``<1a/>``, ``<!x>``, ``<a:b:c/>``, DOCTYPE   ok   no    no     ok        xml-markup
  inside an element
text, an element, a second ``<robot>`` or    ok   no    no     ok        xml-outside-root
  a NUL byte after the root (an element
  before it: yourdfpy crashes)
UTF-16 file with a BOM (without: xacro ok)   no   ok    no     ok        (refused)
DOCTYPE with an internal subset              no   ok    ok     ok        (refused)
duplicate attribute, mismatched end tag      no   no    no     ok        (refused)
undeclared prefix on ``<robot>``             no   no    no     crash     (refused)
===========================================  ===  ====  =====  ========  =====================

``ok*``: check_urdf prints the raw bytes, which are not UTF-8 (here: the UTF-8 of what they
mean). urdfdom drops the ``&`` of ``&foo;`` (reading ``foo;``); a byte that starts a UTF-8
sequence after a UTF-8 declaration swallows the bytes after it (a closing quote: refused).
urdfdom 4 (TinyXML2, ROS 2 Jazzy) differs, from its source: it refuses unquoted values and a
declaration after anything but another one, and keeps ``&foo;`` as written.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ._messages import Recovery
    from ._nodes import Refused, TooDeep
    from ._rewrite import UNDECLARED

# The reader and its tables (name patterns over all of Unicode take milliseconds to
# compile) load when a file first needs them: most files never do.
_LAZY = {
    "Recovery": "._messages",
    "Refused": "._nodes",
    "TooDeep": "._nodes",
    "UNDECLARED": "._rewrite",
}


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(module, __name__), name)


__all__ = [
    "UNDECLARED",
    "Recovered",
    "Recovery",
    "Refused",
    "TooDeep",
    "needed",
    "recover",
]


@dataclass(frozen=True, slots=True)
class Recovered:
    """A file as urdfdom reads it, as well-formed XML.

    Attributes:
        data: The robot element as UTF-8 XML.
        starts: Byte offset in the original file of each element of ``data``, in order.
        tags: Element names of ``data`` (``prefix:local``) written otherwise in the file,
            with the bytes that start them there (``<`` and the name).
        recoveries: One per rule applied, in the order of the file.
    """

    data: bytes
    starts: tuple[int, ...]
    tags: Mapping[str, bytes]
    recoveries: tuple[Recovery, ...]


def recover(data: bytes) -> Recovered:
    """Read ``data`` as urdfdom (TinyXML) does.

    Raises:
        Refused: urdfdom refuses the file (TooDeep: nested deeper than lxml reads).
    """
    # the reader loads with its first use (~40 ms of Unicode name patterns to compile)
    from ._messages import summary
    from ._rewrite import rewrite
    from ._strict import root
    from ._tinyxml import read

    document = read(data)
    robot = root(document)
    rewritten = rewrite(document, robot)
    return Recovered(
        rewritten.data, rewritten.starts, rewritten.tags, summary(document.notes, data)
    )


_BOM = b"\xef\xbb\xbf"
_DECLARATION_START = re.compile(rb"[ \t\r\n]*<\?xml([ \t\r\n][^>]*)?>")
_ENCODING = re.compile(rb"encoding[ \t\r\n]*=[ \t\r\n]*[\"']?([^\"'?\s]*)", re.IGNORECASE)
_ANY_DECLARATION = re.compile(rb"<\?xml[ \t\r\n][^>]*encoding", re.IGNORECASE)
_PI = re.compile(rb"<\?.*?\?>", re.DOTALL)
_CHARREF = re.compile(rb"&#(?:x([0-9a-fA-F]+)|([0-9]+));")
_DEFAULT_NAMESPACE = re.compile(rb"xmlns[ \t\r\n]*=[ \t\r\n]*(?:\"[^\"]|'[^'])")


def needed(data: bytes, prolog: int | None = None) -> bool:
    """True when lxml may read well-formed ``data`` otherwise than urdfdom: a NUL byte (UTF-16
    too), a DOCTYPE, a byte-order mark after the start (white space to urdfdom), a default
    namespace, a processing instruction holding '>', bytes that are not ASCII in a file urdfdom
    reads byte by byte, or a reference above 127 there.

    ``prolog``: where the root element's start tag ends, if known (a DOCTYPE comes before).
    """
    # (Each look at the whole file first for what it needs, with the quickest search there is:
    # at 64 MB a pattern's search takes 30 ms, a byte string's a few.)
    if b"\0" in data or data.find(b"<!DOCTYPE", 0, prolog) >= 0:
        return True
    wide = not data.isascii()
    if wide and data.find(_BOM, 1) >= 0:  # (a byte-order mark is not ASCII)
        return True
    if b"xmlns" in data and _DEFAULT_NAMESPACE.search(data):
        return True
    if _instruction_holding_gt(data):
        return True
    if data.startswith(_BOM):
        return False  # UTF-8 to urdfdom as to lxml
    first = _DECLARATION_START.match(data)
    label = None if first is None else _ENCODING.search(first[0])
    if first is not None and (label is None or label[1].lower().startswith((b"utf-8", b"utf8"))):
        return False  # UTF-8 to urdfdom as to lxml
    if first is not None:  # another encoding: urdfdom reads byte by byte
        return wide or _high_reference(data)
    # No declaration first: byte by byte until one (which may name an encoding) comes.
    return _high_reference(data) or (wide and _ANY_DECLARATION.search(data) is not None)


def _instruction_holding_gt(data: bytes) -> bool:
    """Whether a processing instruction in ``data`` holds '>' (as `_PI` finds them, left to
    right). Each '<?' is found from its '?', which is rare in a URDF, where '<' is not."""
    at = data.find(b"?", 1)
    while at >= 0:
        if data[at - 1] != 0x3C:  # no '<' before it
            at = data.find(b"?", at + 1)
            continue
        found = _PI.match(data, at - 1)
        if found is None:  # no "?>" after it, so none after those that follow either
            return False
        if b">" in found[0][2:-2]:
            return True
        at = data.find(b"?", found.end() + 1)
    return False


def _high_reference(data: bytes) -> bool:
    return b"&#" in data and any(
        int(m[1], 16) > 127 if m[1] else int(m[2]) > 127 for m in _CHARREF.finditer(data)
    )
