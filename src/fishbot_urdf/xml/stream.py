"""lxml's safe parse, and a big file read a part at a time: in pieces cut after the end tags
of links and joints, or an element of <robot> at a time."""

from __future__ import annotations

import io
import itertools
import re
from collections.abc import Iterator
from functools import partial
from typing import Any

from lxml import etree

from ..errors import XmlSyntaxError
from .locator import MARKUP, Alongside, Locator

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


PIECE = 4 * 2**20
"""The most bytes of a big file's robot parsed at once (see `Pieces`)."""


# The root's start tag (a self-closing root holds nothing to cut).
_ROOT_TAG = re.compile(rb"<([^\s/>]+)(?:\s+[^\s=/>]+\s*=\s*(?:\"[^\"]*\"|'[^']*'))*\s*>")
# Where a piece may end: after the end tag of an element <robot> holds.
_CUT = re.compile(rb"</(?:link|joint)>")
_JOINS = 8  # pieces joined on to one that lxml refused before the file is read otherwise


class Pieces:
    """A big file's robot read a piece at a time. The root is read first, holding nothing;
    then each piece of what it holds, cut just after the end tag of a link or joint, is
    parsed whole inside a copy of the root's start tag (lxml lets go of the interpreter while
    it parses), while a thread finds the piece's start tags and their places. Only one
    piece's tree is held at once.

    A piece that lxml refuses at its end tag was cut inside an element, and the next piece
    is joined on (a few times); one it refuses before that, or the last, raises
    Unstreamable: the file is not clean XML, and is then read whole.
    """

    __slots__ = ("_bounds", "_close", "_data", "_next", "locator")

    def __init__(self, data: bytes, bounds: list[int], close: bytes) -> None:
        self._data = data
        self._bounds = bounds  # where the root's start tag ends, each piece ends, the file ends
        self._close = close  # the root's end tag
        self._next = 0  # the next piece to parse
        self.locator: Locator

    @property
    def head_end(self) -> int:
        """Where the root's start tag ends."""
        return self._bounds[0]

    @classmethod
    def cut(cls, data: bytes) -> Pieces | None:
        """Where to cut ``data`` (None: it cannot be cut, and is to be read otherwise)."""
        first = MARKUP.search(data)
        while first is not None and not first.lastindex:  # the prolog's comments, ...
            first = MARKUP.search(data, first.end())
        head = None if first is None else _ROOT_TAG.match(data, first.start())
        if head is None or data.find(b"<!DOCTYPE", 0, head.start()) >= 0:
            return None
        close = b"</" + head[1]
        last = data.rfind(close)
        if last < head.end():
            return None
        size = min(PIECE, max(len(data) // 8, 1))
        bounds = [head.end()]
        near = max(size, 2**16)
        while last - bounds[-1] > size:
            end = _cut(data, bounds[-1] + size, near, last)
            if end is None:
                if last - bounds[-1] > size + near:
                    return None  # nowhere to cut near: read it an element at a time
                break  # the rest is the last piece
            bounds.append(end)
        bounds.append(len(data))
        return cls(data, bounds, close + b">")

    def start(self, path: str) -> etree._Element:
        """Read the root, holding nothing yet.

        Raises:
            Unstreamable: lxml refuses it.
        """
        self.locator = locator = Locator.growing(self._data, path)
        head_end = self.head_end
        locator.add(locator.stretch(0, head_end))
        return _parse_piece(self._data[:head_end] + self._close, path)

    def __iter__(self) -> Iterator[etree._Element]:
        """What <robot> holds, piece after piece (each parsed once the last is handed out).

        Raises:
            Unstreamable: lxml refuses a piece.
        """
        while self._next < len(self._bounds) - 1:
            yield from self._parse_next()

    def finish(self) -> None:
        """Parse what was not asked for, to learn whether it is XML.

        Raises:
            Unstreamable: It is not clean XML.
        """
        for _ in self:
            pass

    def _parse_next(self) -> etree._Element:
        data, bounds, index, locator = self._data, self._bounds, self._next, self.locator
        head = data[: bounds[0]]
        joined = 0
        while True:
            start, end = bounds[index], bounds[index + 1]
            piece = (
                head + data[start:] if end == len(data) else head + data[start:end] + self._close
            )
            located = Alongside(partial(locator.stretch, start, end), end - start)
            try:
                root = parse(piece, locator.path)
            except XmlSyntaxError as exc:
                # Cut inside an element (after a <joint> of <ros2_control>, say), which lxml
                # finds at the piece's end tag: try again with the next piece joined on, a
                # few times. A fault before that end is the file's own: read it otherwise.
                inside = exc.line is not None and exc.line <= piece.count(b"\n")
                if inside or end == len(data) or joined == _JOINS:
                    raise Unstreamable from exc
                del bounds[index + 1]
                joined += 1
                continue
            finally:
                located.join()  # (no thread is left running, whatever happens)
            locator.add(located.result())
            self._next = index + 1
            return root


def _parse_piece(piece: bytes, path: str) -> etree._Element:
    try:
        return parse(piece, path)
    except XmlSyntaxError as exc:
        raise Unstreamable from exc


def _cut(data: bytes, target: int, near: int, last: int) -> int | None:
    """Where a piece may end: just after the first end tag of a link or joint from ``target``
    on, at most ``near`` bytes further and before ``last`` (None if there is none). It may be
    inside another element: lxml then refuses the piece (see `Pieces`)."""
    found = _CUT.search(data, target, min(last, target + near))
    return None if found is None else found.end()
