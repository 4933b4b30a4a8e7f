"""Safe XML reading, as urdfdom reads a file: whole, or a part at a time for a big file
(`fishbot_urdf.xml.stream`), with every element's place (`fishbot_urdf.xml.locator`)."""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from ..diagnostics import Diagnostic, Kind, Subject
from ..errors import XmlSyntaxError
from ..inputs import read_input
from ..location import Location
from . import recover
from .locator import Locator, located
from .stream import (
    SAFE,
    STREAM_FROM,
    ElementStream,
    Unstreamable,
    parse,
)

STRING_PATH = "<string>"


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
    return parse(data, path, SAFE)


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
    _stream: ElementStream | None = None

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
    try:
        root = parse(data, path)
    except XmlSyntaxError as error:
        strict = error
    # (where the root's start tag ends: a DOCTYPE comes before)
    if strict is None and not recover.needed(data, _line_end(data, root.sourceline)):
        return XmlDocument(root, located(data, path, origins), ())
    try:
        recovered = recover.recover(data)
        root = parse(recovered.data, path)
    except (recover.Refused, XmlSyntaxError) as refusal:
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
    # The strict parser's error, through its cause's traceback, holds this frame and its
    # callers' (and what they made: the robot, its analysis) until the cycle collector
    # runs, which the command line keeps from running: let go of it now.
    del strict
    locator = Locator(data, path, starts=recovered.starts, tags=recovered.tags)

    findings = []
    for recovery in recovered.recoveries:
        line, column = _line_column(data, recovery.offset)
        findings.append(
            recovery.rule.report(
                recovery.message,
                Location(path, line, column),
                path=path,
                subject=Subject(Kind.FILE, path),
                hint=recovery.hint,
            )
        )
    return XmlDocument(root, locator, tuple(findings))


def _streamed(data: bytes, path: str, origins: Sequence[Location] | None) -> XmlDocument | None:
    """``data`` read an element at a time; None if it is to be read whole (it is not clean
    XML, or urdfdom reads it otherwise)."""
    try:
        stream = ElementStream(data)
    except Unstreamable:
        return None  # for urdfdom's reading, or the strict parser's message
    if recover.needed(data, _line_end(data, stream.root.sourceline)):
        return None
    return XmlDocument(stream.root, Locator(data, path, origins), (), stream)


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
