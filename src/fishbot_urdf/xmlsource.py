"""Safe XML reading and exact source positions (line and column) for elements and attributes."""

from __future__ import annotations

import io
import itertools
import re
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any, Generic, NamedTuple, TypeVar

from lxml import etree

from . import xmlrecover
from .diagnostics import Diagnostic, Kind, Subject
from .errors import XmlSyntaxError
from .inputs import read_input
from .location import Location

STRING_PATH = "<string>"
_T = TypeVar("_T")


def read_bytes(path: str | Path) -> bytes:
    """Read a whole regular file within the size limit (see :mod:`fishbot_urdf.inputs`)."""
    return read_input(path)


def parse_xml(data: bytes, path: str = STRING_PATH) -> etree._Element:
    """Parse bytes into an lxml element tree, refusing entities and DTDs.

    Strict: a file urdfdom reads though XML does not (see `read_xml`) is refused too.

    Raises:
        XmlSyntaxError: The text is not well-formed XML, or declares entities.
    """
    _check_start(data, path)
    return _parse(data, path, _SAFE)


STREAM_FROM = 16 * 2**20
"""Files at least this big (bytes) are read as a stream (see `read_xml`): the tree lxml
builds takes about 13 times the file's size."""


class Unstreamable(Exception):
    """A file read as a stream turned out not to be clean XML past its start: read it whole
    (`read_xml` with ``stream=False``) to learn what urdfdom makes of it."""


_CHECK_EVERY = 1024  # elements handed out between two looks at a stream's error log


class _Stream:
    """The elements directly inside the root, each handed out once lxml has read it whole,
    and dropped from the tree (with the comments before it) when the next one is asked for."""

    __slots__ = ("_events", "_parser", "root")

    def __init__(self, data: bytes) -> None:
        """Raises Unstreamable when lxml refuses the start of ``data``."""
        self._parser = etree.iterparse(io.BytesIO(data), events=("end",), **_READING)
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


@dataclass(frozen=True, slots=True)
class XmlDocument:
    """A file read as XML the way urdfdom reads it.

    Attributes:
        root: The root element (``<robot>`` unless the file has none).
        locator: Source positions of its elements, in the file as written.
        recoveries: One warning for each rule (``xml-*``) applied to read a file that urdfdom
            reads and strict XML parsers refuse (or read otherwise); empty for clean XML.
    """

    root: etree._Element
    locator: Locator
    recoveries: tuple[Diagnostic, ...]
    _stream: _Stream | _Pieces | None = None

    def children(self) -> Iterator[etree._Element]:
        """What the root holds (comments and processing instructions too, unless streamed),
        in order; a streamed file's elements are dropped from ``root`` once passed.

        Raises:
            Unstreamable: A streamed file is not clean XML further on.
        """
        return iter(self.root) if self._stream is None else iter(self._stream)

    def finish(self) -> None:
        """Make sure the whole file was read (a streamed file may not have been).

        Raises:
            Unstreamable: A streamed file is not clean XML further on.
        """
        if self._stream is not None:
            self._stream.finish()


def read_xml(
    data: bytes,
    path: str = STRING_PATH,
    origins: Sequence[Location] | None = None,
    *,
    stream: bool | None = None,
) -> XmlDocument:
    """Read bytes as urdfdom (check_urdf, robot_state_publisher) reads them.

    Clean XML is read as it is. A file urdfdom reads although strict XML parsers refuse it (a
    misplaced declaration, an undeclared prefix, a stray '&', ...) or read it otherwise is
    read as urdfdom's TinyXML reads it, and each rule applied gives one warning saying what a
    strict tool does with the file; nothing is ever read from outside the file.

    ``stream`` (default: for files of `STREAM_FROM` bytes and more) reads clean XML as the
    document's `XmlDocument.children` are asked for, so that the whole tree is never held; a
    caller that gets `Unstreamable` from them reads the file again with ``stream=False``.

    Raises:
        XmlSyntaxError: urdfdom refuses the file too (the strict parser's message when it
            has one), or the file declares entities.
    """
    _check_start(data, path)
    if len(data) >= STREAM_FROM if stream is None else stream:
        streamed = _streamed(data, path, origins)
        if streamed is not None:
            return streamed
    strict: XmlSyntaxError | None = None
    located = _Alongside(partial(_located, data, path, origins), len(data))
    try:
        root = _parse(data, path)
    except XmlSyntaxError as error:
        strict = error
    finally:
        located.join()  # (no thread is left running, whatever happens)
    # (where the root's start tag ends: a DOCTYPE comes before)
    if strict is None and not xmlrecover.needed(data, _line_end(data, root.sourceline)):
        return XmlDocument(root, located.result(), ())
    try:
        recovered = xmlrecover.recover(data)
        root = _parse(recovered.data, path)
    except (xmlrecover.Refused, XmlSyntaxError) as refusal:
        if strict is not None:
            raise strict from refusal
        if isinstance(refusal, XmlSyntaxError):  # pragma: no cover - a rewrite lxml refuses
            raise
        line, column = _line_column(data, refusal.offset or 0)
        raise XmlSyntaxError(
            f"urdfdom cannot read this file: {refusal.reason}",
            path=path,
            line=line if refusal.offset is not None else None,
            column=column if refusal.offset is not None else None,
        ) from refusal
    locator = Locator(data, path, starts=recovered.starts, tags=recovered.tags)
    from .rules.xml import BY_ID

    findings = []
    for recovery in recovered.recoveries:
        line, column = _line_column(data, recovery.offset)
        findings.append(
            BY_ID[recovery.rule].report(
                recovery.message,
                Location(path, line, column),
                path=path,
                subject=Subject(Kind.FILE, path),
                hint=recovery.hint,
            )
        )
    return XmlDocument(root, locator, tuple(findings))


def _streamed(data: bytes, path: str, origins: Sequence[Location] | None) -> XmlDocument | None:
    """``data`` read a piece or an element at a time; None if it is to be read whole (it is
    not clean XML, or urdfdom reads it otherwise)."""
    pieces = _Pieces.cut(data) if origins is None else None
    if pieces is not None:
        if xmlrecover.needed(data, pieces.head_end):
            return None
        try:
            return XmlDocument(pieces.start(path), pieces.locator, (), pieces)
        except Unstreamable:
            return None
    try:
        stream = _Stream(data)
    except Unstreamable:
        return None  # for urdfdom's reading, or the strict parser's message
    if xmlrecover.needed(data, _line_end(data, stream.root.sourceline)):
        return None
    return XmlDocument(stream.root, Locator(data, path, origins), (), stream)


PIECE = 4 * 2**20
"""The most bytes of a big file's robot parsed at once (see `_Pieces`)."""

# The root's start tag (a self-closing root holds nothing to cut).
_ROOT_TAG = re.compile(rb"<([^\s/>]+)(?:\s+[^\s=/>]+\s*=\s*(?:\"[^\"]*\"|'[^']*'))*\s*>")
# Where a piece may end: after the end tag of an element <robot> holds.
_CUT = re.compile(rb"</(?:link|joint)>")
_JOINS = 8  # pieces joined on to one that lxml refused before the file is read otherwise


class _Pieces:
    """A big file's robot read a piece at a time. The root is read first, holding nothing;
    then each piece of what it holds, cut just after the end tag of a link or joint, is
    parsed whole inside a copy of the root's start tag (lxml lets go of the interpreter while
    it parses), while a thread finds the piece's start tags and their places. Only one
    piece's tree is held at once.

    A piece that lxml refuses (the file is not clean XML, or was cut where it should not
    have been) raises Unstreamable: the file is then read whole.
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
    def cut(cls, data: bytes) -> _Pieces | None:
        """Where to cut ``data`` (None: it cannot be cut, and is to be read otherwise)."""
        first = _MARKUP.search(data)
        while first is not None and not first.lastindex:  # the prolog's comments, ...
            first = _MARKUP.search(data, first.end())
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
            located = _Alongside(partial(locator.stretch, start, end), end - start)
            try:
                root = _parse(piece, locator.path)
            except XmlSyntaxError as exc:
                # Cut inside an element (after a <joint> of <ros2_control>, say), or a fault:
                # try again with the next piece joined on, a few times; then read the file
                # otherwise.
                if end == len(data) or joined == _JOINS:
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
        return _parse(piece, path)
    except XmlSyntaxError as exc:
        raise Unstreamable from exc


def _cut(data: bytes, target: int, near: int, last: int) -> int | None:
    """Where a piece may end: just after the first end tag of a link or joint from ``target``
    on, at most ``near`` bytes further and before ``last`` (None if there is none). It may be
    inside another element: lxml then refuses the piece (see `_Pieces`)."""
    found = _CUT.search(data, target, min(last, target + near))
    return None if found is None else found.end()


LOCATE_ALONGSIDE_FROM = 512 * 2**10
"""Files at least this big (bytes) are scanned for their elements' places while lxml parses
them, in a thread of their own: lxml lets go of the interpreter while it parses. (Below, the
thread's start and the interpreter's hand-over cost about what it saves: a 600 KB robot reads
in 0.92 of the time, real robots of 60 to 200 KB in 1.05.)"""


class _Alongside(Generic[_T]):
    """Work on a file's places done in a thread of its own while lxml parses the file (lxml
    lets go of the interpreter while it parses), when the file is big enough for the thread
    to pay; done in the caller when it is not, or when it failed in the thread."""

    __slots__ = ("_done", "_thread", "_work")

    def __init__(self, work: Callable[[], _T], size: int) -> None:
        self._work = work
        self._done: list[_T] = []
        self._thread = None
        if size >= LOCATE_ALONGSIDE_FROM:
            import threading

            self._thread = threading.Thread(target=self._run, name="fishbot-locate", daemon=True)
            self._thread.start()

    def _run(self) -> None:
        try:
            done = self._work()
        except Exception:  # done again in the caller, which then raises
            return
        self._done.append(done)

    def join(self) -> None:
        """Wait for the thread, if there is one."""
        if self._thread is not None:
            self._thread.join()

    def result(self) -> _T:
        """What the work gave, once joined (done here if there was no thread, or it failed)."""
        return self._done[0] if self._done else self._work()


def _located(data: bytes, path: str, origins: Sequence[Location] | None) -> Locator:
    """A `Locator` with every location made."""
    locator = Locator(data, path, origins)
    locator.locations()
    return locator


_OPENS = re.compile(rb"[\xef\xbb\xbf \t\r\n\v\f]*<")  # what may come before the first '<'


def _check_start(data: bytes, path: str) -> None:
    if not data or data.isspace():  # (neither copies the file, as strip() would)
        raise XmlSyntaxError('the file is empty (a URDF starts with <robot name="...">)', path=path)
    if not _OPENS.match(data) and not data.startswith(
        (b"\xff\xfe", b"\xfe\xff")  # UTF-16 byte order marks
    ):
        raise XmlSyntaxError(
            "this is not an XML file: it does not start with '<'", path=path, line=1, column=1
        )
    doctype = data.find(b"<!DOCTYPE")
    entity = data.find(b"<!ENTITY", doctype) if doctype >= 0 else -1
    if entity >= 0:
        line, column = _line_column(data, entity)
        raise XmlSyntaxError(
            "XML entity declarations are not allowed (URDF never needs them; they are "
            "refused so that nothing outside the file is read and nothing expands without end)",
            path=path,
            line=line,
            column=column,
        )
    if data.startswith((b"\xff\xfe", b"\xfe\xff", b"\0")) or b"\0" in data[1:4]:
        raise XmlSyntaxError(
            "the file is UTF-16 or UTF-32: urdfdom reads it only up to its first NUL byte and "
            "finds no <robot> (save it as UTF-8)",
            path=path,
            line=1,
            column=1,
        )


def _line_end(data: bytes, line: object) -> int | None:
    """Byte offset of the end of 1-based ``line`` (None: unknown)."""
    if not isinstance(line, int):
        return None
    end = -1
    for _ in range(line):
        end = data.find(b"\n", end + 1)
        if end < 0:
            return None
    return end


def _line_column(data: bytes, offset: int) -> tuple[int, int]:
    """1-based line and column (in characters) of byte ``offset``, as the Locator counts."""
    start = data.rfind(b"\n", 0, offset) + 1
    return data.count(b"\n", 0, offset) + 1, len(data[start:offset].decode("utf-8", "replace")) + 1


# No entity expansion, no DTD loading, no network, libxml2's size and depth guards on.
_SAFE: dict[str, Any] = {
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
_READING: dict[str, Any] = {**_SAFE, "remove_blank_text": True, "collect_ids": False}


def _parse(data: bytes, path: str, options: dict[str, Any] = _READING) -> etree._Element:
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


# Every start tag, in document order; comments, CDATA, processing instructions and the DOCTYPE
# are matched too so that a "<tag" inside them is not taken for an element.
_MARKUP = re.compile(
    rb"<(?:!--.*?-->|!\[CDATA\[.*?\]\]>|\?.*?\?>|!DOCTYPE(?:[^\[>]|\[.*?\])*>|([^/!?]))",
    re.DOTALL,
)
_AFTER_TAG = frozenset(b" \t\r\n/>")
# An attribute value holding a raw tab or line break. XML turns them into spaces, but
# urdfdom's XML parser keeps them, and then refuses a vector like "0 0<TAB>1".
# The run before the first tab or line break holds none, so each try scans a value once.
_RAW_WHITESPACE = re.compile(
    rb"=[ \t\r\n]*(?:\"[^\"<\t\n\r]*[\t\n\r][^\"<]*\"|'[^'<\t\n\r]*[\t\n\r][^'<]*')"
)
# Every byte but those the pattern tells apart from the rest: with them dropped, what is left
# is a fifth of a URDF, and the pattern still matches it wherever it matches the file.
_NOT_IN_PATTERN = bytes(b for b in range(256) if b not in b"=\"'<\t\n\r")


def _start_tags(data: bytes, start: int = 0, end: int | None = None) -> list[int]:
    """The offset of every start tag in ``data[start:end]`` (which cuts no markup)."""
    scan = _MARKUP.finditer(data, start) if end is None else _MARKUP.finditer(data, start, end)
    return [m.start() for m in scan if m.lastindex]


def _has_raw_whitespace(data: bytes) -> bool:
    """Whether an attribute value in ``data`` holds a raw tab or line break."""
    # First on the bytes the pattern looks at (the dropped ones are spaces, which it lets
    # stand between '=' and the quote, and bytes it takes anywhere inside a value), then,
    # only if that matches, on the file itself.
    if _RAW_WHITESPACE.search(data.translate(None, _NOT_IN_PATTERN)) is None:
        return False
    return _RAW_WHITESPACE.search(data) is not None


def _width(data: bytes, start: int, end: int, ascii_only: bool) -> int:
    """How many characters the bytes from ``start`` to ``end`` hold."""
    if ascii_only:
        return end - start
    return len(data[start:end].decode("utf-8", "replace"))


_TOP = (1, 0, 0, 0)  # where counting starts: line 1 from offset 0, no character counted


def _locations(
    data: bytes,
    path: str,
    starts: Sequence[int],
    ascii_only: bool,
    counted: tuple[int, int, int, int] = _TOP,
) -> tuple[list[Location], tuple[int, int, int, int]]:
    """1-based line and column (in characters) of every offset of ``starts`` (increasing),
    in one pass: each stretch of ``data`` between two offsets is looked at once, so a long
    one-line file stays linear. ``counted`` carries the count on from where an earlier call
    ended (its line, where that starts, its last offset, the characters counted on the
    line), for a file located a stretch at a time; the count at the end is returned too."""
    new = tuple.__new__  # a Location without the NamedTuple's Python-level __new__
    count, rfind = data.count, data.rfind
    found: list[Location] = []
    line, line_start, previous, chars = counted
    for offset in starts:
        newlines = count(b"\n", previous, offset)
        if newlines:
            line += newlines
            line_start = rfind(b"\n", previous, offset) + 1
            previous, chars = line_start, 0
        if ascii_only:
            column = offset - line_start + 1
        else:  # characters, carried along the line
            chars += _width(data, previous, offset, ascii_only)
            column = chars + 1
        previous = offset
        found.append(new(Location, (path, line, column)))
    return found, (line, line_start, previous, chars)


class Stretch(NamedTuple):
    """A stretch of a file as a growing `Locator` scanned it."""

    starts: list[int]  # the offset of each start tag
    places: list[Location]  # the place of each
    counted: tuple[int, int, int, int]  # the line count where the stretch ends (_locations)


class Locator:
    """Exact line and column of every element's start tag, in linear time.

    lxml reports the line where a start tag *ends*, and no column, so one regular-expression
    pass over the bytes lists where every start tag begins, in document order, and one more
    turns those offsets into lines and columns. Callers visit elements in document order and
    ``skip`` the subtrees they do not read. Where the scan is exact (everywhere but in a
    document with a DOCTYPE, or one rewritten for urdfdom's reading) the next start tag is
    the element's; elsewhere each ``locate`` compares the tag name, so an element the scan
    took wrongly only costs a short scan.
    """

    __slots__ = (
        "_ascii",
        "_counted",
        "_data",
        "_exact",
        "_index",
        "_last",
        "_locations",
        "_origins",
        "_plain",
        "_starts",
        "_tags",
        "path",
        "raw_whitespace",
    )

    def __init__(
        self,
        data: bytes,
        path: str,
        origins: Sequence[Location] | None = None,
        *,
        starts: Sequence[int] | None = None,
        tags: Mapping[str, bytes] | None = None,
    ) -> None:
        """``starts`` gives the offset of every element instead of the scan (for a document
        lxml read after a rewrite); ``tags`` the start-tag bytes of elements whose name, as
        ``prefix:local``, is written otherwise in ``data``."""
        self._data = data
        self._ascii = data.isascii()
        self.path = path
        self._counted = _TOP  # where the places found so far end (see `growing`)
        if starts is not None:
            self._starts = list(starts)
        else:
            self._starts = _start_tags(data)
        # Outside a DOCTYPE's declarations the scan finds exactly the start tags lxml reads
        # (comments, CDATA sections and processing instructions are matched whole), so the
        # next start tag is the element's: no name needs to be compared.
        self._exact = starts is None and (
            not self._starts or data.find(b"<!DOCTYPE", 0, self._starts[0]) < 0
        )
        # Where each element was written when ``data`` was generated (an expanded xacro file):
        # reported instead of the element's place in ``data``.
        self._origins = (
            origins if origins is not None and len(origins) == len(self._starts) else None
        )
        self._locations: Sequence[Location] | None = self._origins
        self._tags: dict[str, bytes] = dict(tags or {})
        self._plain: dict[object, bytes] = {}  # "<name" of each tag in no namespace
        self.raw_whitespace = _has_raw_whitespace(data)
        self.rewind()

    @classmethod
    def growing(cls, data: bytes, path: str) -> Locator:
        """A locator of ``data`` (with no DOCTYPE) that knows no start tag yet: each stretch of
        the file is scanned (`stretch`) and its places added (`add`), in order, before its
        elements are located."""
        locator = cls(data, path, starts=())
        locator._exact = data.find(b"<!DOCTYPE") < 0
        locator._locations = []
        return locator

    def stretch(self, start: int, end: int) -> Stretch:
        """The start tags of ``data[start:end]``, the stretch after those added, and their
        places. Nothing is added: this may run in a thread while the stretch is parsed."""
        found = _start_tags(self._data, start, end)
        return Stretch(found, *_locations(self._data, self.path, found, self._ascii, self._counted))

    def add(self, stretch: Stretch) -> None:
        """Add the places of a stretch found by `stretch` (a locator made by `growing`)."""
        places = self._locations
        assert isinstance(places, list), "not a growing locator"
        self._starts.extend(stretch.starts)
        places.extend(stretch.places)
        self._counted = stretch.counted

    def rewind(self) -> None:
        """Start again from the top of the document."""
        self._index = 0  # next entry of _starts to hand out
        self._last = -1  # the entry of the last element found (-1: none)

    def locations(self) -> Sequence[Location]:
        """The location of every start tag, in one pass (made on first use)."""
        if self._locations is None:
            self._locations = _locations(self._data, self.path, self._starts, self._ascii)[0]
        return self._locations

    def locate(self, element: etree._Element) -> Location:
        """The location of ``element``'s start tag: the next start tag where the scan is
        exact, else the next one of its name."""
        index = self._index
        if self._exact:
            if index < len(self._starts):
                self._index, self._last = index + 1, index
                return (self._locations or self.locations())[index]
            return self._fallback(element)
        # Most often the next start tag is the element's: one look, no loop.
        name = self._plain.get(element.tag)
        if name is not None and index < len(self._starts):
            offset = self._starts[index]
            data = self._data
            if data.startswith(name, offset) and data[offset + len(name)] in _AFTER_TAG:
                self._index, self._last = index + 1, index
                return (self._locations or self.locations())[index]
        return self._search(element)

    def _search(self, element: etree._Element) -> Location:
        tag = element.tag
        if not isinstance(tag, str):
            return self._fallback(element)
        plain = tag[0] != "{"
        if not plain:  # in a namespace: written prefix:local (or local) in the file
            local = tag[tag.index("}") + 1 :]
            tag = f"{element.prefix}:{local}" if element.prefix else local
        name = self._tags.get(tag)
        if name is None:
            name = self._tags[tag] = b"<" + tag.encode("utf-8")
        if plain:  # the written name is the tag
            self._plain[tag] = name
        data, starts, size = self._data, self._starts, len(name)
        locations = self._locations or self.locations()
        for index in range(self._index, len(starts)):
            offset = starts[index]
            if data.startswith(name, offset) and data[offset + size] in _AFTER_TAG:
                self._index, self._last = index + 1, index
                return locations[index]
        return self._fallback(element)

    def _fallback(self, element: etree._Element) -> Location:
        # Only reached if the scan and lxml disagree: lxml's line is close enough then.
        line = element.sourceline
        return Location(self.path, line if isinstance(line, int) else 1, 1)

    def skip(self, element: etree._Element) -> None:
        """Pass over ``element`` and everything inside it without locating them."""
        self.locate(element)
        self.skip_children(element)

    def skip_children(self, element: etree._Element) -> None:
        """Pass over everything inside ``element`` (already located)."""
        self._index += sum(1 for node in element.iterdescendants() if isinstance(node.tag, str))

    def _attribute_match(self, location: Location, name: str) -> re.Match[bytes] | None:
        last = self._last
        if last < 0 or (self._locations or self.locations())[last] is not location:
            return None
        data = self._data
        tag_start = self._starts[last]
        tag_end = data.find(b">", tag_start)
        pattern = re.compile(
            rb"\s" + re.escape(name.encode("utf-8")) + rb"\s*=\s*(?:\"([^\"]*)\"|'([^']*)')"
        )
        return pattern.search(data, tag_start, tag_end if tag_end >= 0 else len(data))

    def raw_attribute(self, location: Location, name: str) -> str | None:
        """Attribute ``name`` of the element at ``location`` as written, white space and all
        (character references are not expanded). None when it cannot be found."""
        match = self._attribute_match(location, name)
        if match is None:
            return None
        raw = match.group(1) if match.group(1) is not None else match.group(2)
        return raw.decode("utf-8", "replace")

    def attribute(self, location: Location, name: str) -> Location:
        """The location of attribute ``name`` in the start tag found at ``location``.

        Exact for the element located last (attributes are read before children are located);
        otherwise the element's own location.
        """
        match = self._attribute_match(location, name)
        if match is None or self._origins is not None:
            return location
        data, tag, offset = self._data, self._starts[self._last], match.start() + 1
        newlines = data.count(b"\n", tag, offset)
        if not newlines:  # on the tag's line: count on from the tag's column
            return Location(
                self.path, location.line, location.column + _width(data, tag, offset, self._ascii)
            )
        line_start = data.rfind(b"\n", tag, offset) + 1
        return Location(
            self.path, location.line + newlines, _width(data, line_start, offset, self._ascii) + 1
        )
