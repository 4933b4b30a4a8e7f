"""Safe XML reading and exact source positions (line and column) for elements and attributes."""

from __future__ import annotations

import re
from pathlib import Path

from lxml import etree

from .diagnostics import Diagnostic, Severity
from .errors import InputError, XmlSyntaxError
from .model import Location

STRING_PATH = "<string>"

# No entity expansion, no DTD loading, no network, libxml2's default size/depth guards on.
_PARSER_OPTIONS = {
    "resolve_entities": False,
    "load_dtd": False,
    "no_network": True,
    "dtd_validation": False,
    "huge_tree": False,
    "remove_comments": False,
    "recover": False,
}

def read_bytes(path: str | Path) -> bytes:
    """Read a whole file, turning every OS error into an InputError that names the file."""
    try:
        return Path(path).read_bytes()
    except FileNotFoundError as exc:
        raise InputError("no such file", path=str(path)) from exc
    except IsADirectoryError as exc:
        raise InputError("is a directory, not a file", path=str(path)) from exc
    except PermissionError as exc:
        raise InputError("permission denied", path=str(path)) from exc
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", path=str(path)) from exc


def parse_xml(data: bytes, path: str = STRING_PATH) -> etree._Element:
    """Parse bytes into an lxml element tree, refusing entities and DTDs.

    Raises:
        XmlSyntaxError: The text is not well-formed XML, or declares entities.
    """
    if not data.strip():
        raise XmlSyntaxError("the file is empty (a URDF starts with <robot name=\"...\">)", path=path)
    if not data.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"<") and not data.startswith(
        (b"\xff\xfe", b"\xfe\xff")  # UTF-16 byte order marks
    ):
        raise XmlSyntaxError("this is not an XML file: it does not start with '<'", path=path,
                             line=1, column=1)
    doctype = data.find(b"<!DOCTYPE")
    entity = data.find(b"<!ENTITY", doctype) if doctype >= 0 else -1
    if entity >= 0:
        raise XmlSyntaxError(
            "XML entity declarations are not allowed (URDF never needs them; they are "
            "refused so that nothing outside the file is read and nothing expands without end)",
            path=path,
            line=data.count(b"\n", 0, entity) + 1,
            column=len(data[data.rfind(b"\n", 0, entity) + 1 : entity].decode("utf-8", "replace"))
            + 1,
        )
    parser = etree.XMLParser(**_PARSER_OPTIONS)  # type: ignore[call-overload]
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


class Locator:
    """Finds where elements start in the raw bytes, in document order, in linear time.

    lxml reports the line where a start tag *ends*, and no column, so the locator scans the
    bytes itself: each call looks for ``<tag`` after the previous match, skipping comments.
    Callers must ask for elements in document order (parents before children).
    """

    __slots__ = ("_column_at_cursor", "_cursor", "_data", "_last", "_line", "path")

    def __init__(self, data: bytes, path: str) -> None:
        self._data = data
        self.path = path
        self._cursor = 0  # byte offset just after the last element found
        self._line = 1  # line number at _cursor
        self._column_at_cursor = 1  # 1-based character column at _cursor
        self._last: tuple[Location, int] | None = None  # the last element found, and its offset

    @staticmethod
    def _chars(data: bytes) -> int:
        return len(data) if data.isascii() else len(data.decode("utf-8", "replace"))

    def _advance(self, offset: int) -> tuple[int, int]:
        """Line and column of ``offset`` (>= cursor), scanning only the bytes in between."""
        data = self._data
        newlines = data.count(b"\n", self._cursor, offset)
        if newlines:
            line_start = data.rfind(b"\n", self._cursor, offset) + 1
            return self._line + newlines, self._chars(data[line_start:offset]) + 1
        return self._line, self._column_at_cursor + self._chars(data[self._cursor : offset])

    def _find(self, tag: bytes) -> int:
        data = self._data
        needle = b"<" + tag
        pos = self._cursor if self._last is None else self._cursor + 1
        while True:
            found = data.find(needle, pos)
            if found < 0:
                return -1
            comment = data.find(b"<!--", pos, found)
            if comment >= 0:
                end = data.find(b"-->", comment + 4)
                pos = len(data) if end < 0 else end + 3
                continue
            after = data[found + len(needle) : found + len(needle) + 1]
            if after and after not in b" \t\r\n/>":
                pos = found + 1
                continue
            return found

    def locate(self, element: etree._Element) -> Location:
        """The location of ``element``'s start tag; advances the cursor past it."""
        tag = element.tag
        found = self._find(tag.encode("utf-8")) if isinstance(tag, str) else -1
        if found < 0:
            return Location(self.path, element.sourceline or 1, 1)
        line, column = self._advance(found)
        location = Location(self.path, line, column)
        self._line, self._column_at_cursor, self._cursor = line, column, found
        self._last = (location, found)
        return location

    def attribute(self, location: Location, name: str) -> Location:
        """The location of attribute ``name`` in the start tag found at ``location``.

        Exact for the element located last (attributes are read before children are located);
        otherwise the element's own location.
        """
        if self._last is None or self._last[0] is not location:
            return location
        data = self._data
        tag_start = self._last[1]
        tag_end = data.find(b">", tag_start)
        pattern = re.compile(rb"\s" + re.escape(name.encode("utf-8")) + rb"\s*=")
        match = pattern.search(data, tag_start, tag_end if tag_end >= 0 else len(data))
        if match is None:
            return location
        line, column = self._advance(match.start() + 1)
        return Location(self.path, line, column)


def diagnostic(
    rule: str,
    message: str,
    location: Location | None,
    *,
    hint: str | None = None,
    severity: Severity = Severity.ERROR,
    path: str = STRING_PATH,
) -> Diagnostic:
    """Build a Diagnostic at ``location`` (or at the whole file ``path``)."""
    if location is None:
        return Diagnostic(rule, severity, message, path, None, None, hint)
    return Diagnostic(rule, severity, message, location.path, location.line, location.column, hint)
