"""lxml's safe parse, and a big file read a part at a time: an element of <robot> at a
time."""

from __future__ import annotations

import io
import itertools
import re
from collections.abc import Iterator
from typing import Any

from lxml import etree

from ..errors import XmlSyntaxError

# No entity expansion, no DTD loading, no network, libxml2's size and depth guards on.
SAFE: dict[str, Any] = {
    "resolve_entities": False,
    "load_dtd": False,
    "no_network": True,
    "dtd_validation": False,
    "huge_tree": False,
    "recover": False,
}
# For the reader: it reads no white space between elements (an element URDF does not
# define is kept without it) and looks no element up by xml:id, and a tree without either is
# built and walked in three quarters of the time. (`parse_xml` keeps both, for writing.)
READING: dict[str, Any] = {**SAFE, "remove_blank_text": True, "collect_ids": False}


def parse(data: bytes, path: str, options: dict[str, Any] = READING) -> etree._Element:
    """``data`` parsed by lxml with ``options`` (`SAFE` or `READING`).

    Raises:
        XmlSyntaxError: lxml refuses it (its message, and where).
    """
    parser = etree.XMLParser(**options)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as exc:
        line, column = exc.position if exc.position else (None, None)
        message = (exc.msg or str(exc)).strip()
        # libxml2 appends ", line N, column M" to some messages; the location says that already.
        message = re.sub(r",? line \d+, column \d+$", "", message)
        if message.startswith("Excessive depth in document"):
            message = "elements are nested more than 256 deep (no URDF needs that)"
        raise XmlSyntaxError(
            f"XML syntax error: {message}",
            path=path,
            line=line or None,
            column=column or None,
        ) from exc
    except ValueError as exc:  # e.g. a unicode string with an encoding declaration
        raise XmlSyntaxError(f"XML syntax error: {exc}", path=path) from exc
    return root


STREAM_FROM = 16 * 2**20
"""Files at least this big (bytes) are read a part at a time (see
`fishbot_urdf.xml.source.read_xml`): the tree lxml builds takes about 13 times the file's
size."""


class Unstreamable(Exception):
    """A file read a part at a time turned out not to be clean XML past its start: read it
    whole (`fishbot_urdf.xml.source.read_xml` with ``stream=False``) to learn what urdfdom
    makes of it."""


_CHECK_EVERY = 1024  # elements handed out between two looks at a stream's error log


class ElementStream:
    """The elements directly inside the root, each handed out once lxml has read it whole,
    and dropped from the tree (with the comments before it) when the next one is asked for."""

    __slots__ = ("_events", "_parser", "root")

    def __init__(self, data: bytes) -> None:
        """Raises Unstreamable when lxml refuses the start of ``data``."""
        self._parser = etree.iterparse(io.BytesIO(data), events=("end",), **READING)
        try:
            event = next(self._parser)
        except (etree.XMLSyntaxError, StopIteration) as exc:
            raise Unstreamable from exc
        root = event[1]  # the first element read whole: the root itself, or inside it
        while (parent := root.getparent()) is not None:
            root = parent
        self.root: etree._Element = root
        self._events = itertools.chain([event], self._parser)

    def __iter__(self) -> Iterator[etree._Element]:
        """Raises Unstreamable when lxml refuses the file further on."""
        root = self.root
        try:
            unchecked = 0
            for _, element in self._events:
                if element.getparent() is not root:
                    continue
                before = root.index(element)  # those handed out, and comments between them
                if before:
                    del root[:before]
                unchecked += 1
                if unchecked == _CHECK_EVERY:
                    self._check()
                    unchecked = 0
                yield element
        except etree.XMLSyntaxError as exc:
            raise Unstreamable from exc

    def finish(self) -> None:
        """Read the rest of the file (what was not asked for), to learn whether it is XML.

        Raises:
            Unstreamable: It is not clean XML.
        """
        for _ in self:
            pass
        self._check()

    def _check(self) -> None:
        # What a whole read refuses and a stream only logs (an undeclared namespace prefix),
        # looked for every _CHECK_EVERY elements so that a faulty stream stops early (lxml
        # raises at the end too). Not at each: every look copies the log (0.14 s in all for
        # the 200,000 elements of the 100,000-link tree's robot).
        if self._parser.error_log.filter_from_errors():
            raise Unstreamable
