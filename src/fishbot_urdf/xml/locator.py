"""Where each element of an XML file starts: its line and column (lxml gives the line where
a start tag ends, and no column), found by one scan of the file's bytes."""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from ..location import Location

if TYPE_CHECKING:
    from lxml import etree


def located(data: bytes, path: str, origins: Sequence[Location] | None) -> Locator:
    """A `Locator` with every location made."""
    locator = Locator(data, path, origins)
    locator.locations()
    return locator


# Every start tag, in document order; comments, CDATA, processing instructions and the DOCTYPE
# are matched too so that a "<tag" inside them is not taken for an element. One that is never
# closed runs to the end of the file (which is then no XML): were it not matched at all, the
# search for its end would be made again from each of the next ones, and a file of many
# unclosed comments would take time growing with its size squared.
MARKUP = re.compile(
    rb"<(?:!--(?:.*?-->|.*)|!\[CDATA\[(?:.*?\]\]>|.*)|\?(?:.*?\?>|.*)"
    rb"|!DOCTYPE(?:(?:[^\[>]|\[.*?\])*>|.*)|([^/!?]))",
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


# Every start tag of a stretch that holds no comment, CDATA, processing instruction or
# DOCTYPE: a quarter quicker than MARKUP, which looks at each '<' for those too.
_START_TAG = re.compile(rb"<[^/!?]")


def _start_tags(data: bytes, start: int = 0, end: int | None = None) -> list[int]:
    """The offset of every start tag in ``data[start:end]`` (which cuts no markup)."""
    stop = len(data) if end is None else end
    # '!' and '?' are rare in a URDF (and found at once), '<' is not. The '?' of an XML
    # declaration at the start are passed over.
    after = _DECLARATION.match(data, start)
    if (
        data.find(b"!", start, stop) < 0
        and data.find(b"?", after.end() if after else start, stop) < 0
    ):
        return [m.start() for m in _START_TAG.finditer(data, start, stop)]
    return [m.start() for m in MARKUP.finditer(data, start, stop) if m.lastindex]


_DECLARATION = re.compile(rb"<\?xml[^?<>]*\?>")


def _has_raw_whitespace(data: bytes) -> bool:
    """Whether an attribute value in ``data`` holds a raw tab or line break."""
    # First on the bytes the pattern looks at (the dropped ones are spaces, which it lets
    # stand between '=' and the quote, and bytes it takes anywhere inside a value), then,
    # only if that matches, on the file itself.
    kept = data.translate(None, _NOT_IN_PATTERN)
    # Nearly always every quote left there is one of an '=""' or "=''" (a value holding
    # none of those bytes): then no value holds a tab or line break, and the pattern, a
    # third of the time of the rest, need not run.
    rest = kept.replace(b'=""', b"").replace(b"=''", b"")
    if (b'"' not in rest and b"'" not in rest) or _RAW_WHITESPACE.search(kept) is None:
        return False
    return _RAW_WHITESPACE.search(data) is not None


def _width(data: bytes, start: int, end: int, ascii_only: bool) -> int:
    """How many characters the bytes from ``start`` to ``end`` hold."""
    if ascii_only:
        return end - start
    return len(data[start:end].decode("utf-8", "replace"))


def _locations(data: bytes, path: str, starts: Sequence[int], ascii_only: bool) -> list[Location]:
    """1-based line and column (in characters) of every offset of ``starts`` (increasing),
    in one pass: each stretch of ``data`` between two offsets is looked at once, so a long
    one-line file stays linear."""
    new = tuple.__new__  # a Location without the NamedTuple's Python-level __new__
    count, rfind = data.count, data.rfind
    found: list[Location] = []
    line, line_start, previous, chars = 1, 0, 0, 0
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
    return found


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

    def rewind(self) -> None:
        """Start again from the top of the document."""
        self._index = 0  # next entry of _starts to hand out
        self._last = -1  # the entry of the last element found (-1: none)

    def locations(self) -> Sequence[Location]:
        """The location of every start tag, in one pass (made on first use)."""
        if self._locations is None:
            self._locations = _locations(self._data, self.path, self._starts, self._ascii)
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
