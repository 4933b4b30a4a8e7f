"""The text of a robot's source files as an editor sees it: lines and columns, the start tag
written at a place, the span of an attribute's value in it.

A finding starts where its element is written (``<joint`` of ``<joint name=...>``); its range
ends where that start tag ends, or, for a finding about one value, where that value ends
(see :func:`with_ranges`). Fixes (`fishbot_urdf.fixes`) edit the same spans. Lines and
columns are 1-based and count characters; an end is just past the range.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace

from .diagnostics import Diagnostic
from .errors import FishbotUrdfError

__all__ = ["Attribute", "SourceText", "Texts", "with_ranges"]

Position = tuple[int, int]  # line, column

# A start tag from its "<": the name, then attributes whose quoted values may hold ">".
_START_TAG = re.compile(r"<[^\s/>!?][^\s/>]*(?:\"[^\"]*\"|'[^']*'|[^>\"'])*?/?>", re.DOTALL)
_ATTRIBUTE = re.compile(r"([^\s=/>\"']+)\s*=\s*(\"([^\"]*)\"|'([^']*)')")
_WORD = re.compile(r"[^\s]+")


@dataclass(frozen=True, slots=True)
class Attribute:
    """An attribute as written in a start tag: its name, and its value's span (quotes
    left out) and text."""

    name: str
    value: str
    start: int  # offset of the value's first character
    end: int  # offset just past its last


class SourceText:
    """One file's text, with positions <-> offsets."""

    __slots__ = ("_starts", "path", "text")

    def __init__(self, path: str, text: str) -> None:
        self.path = path
        self.text = text
        self._starts = [0] + [m.end() for m in re.finditer("\n", text)]

    @classmethod
    def decode(cls, path: str, data: bytes) -> SourceText:
        """The text of ``data`` (UTF-8; a byte that is not, read as U+FFFD, as the reader
        counts columns), a leading byte-order mark kept as one character."""
        return cls(path, data.decode("utf-8", "replace"))

    @property
    def newline(self) -> str:
        """The file's line break: CRLF if its first line ends so, else LF."""
        first = self.text.find("\n")
        return "\r\n" if first > 0 and self.text[first - 1] == "\r" else "\n"

    def offset(self, line: int, column: int) -> int | None:
        """The offset of a position, or None when the text has no such place."""
        if not 1 <= line <= len(self._starts) or column < 1:
            return None
        begin = self._starts[line - 1]
        end = self._starts[line] if line < len(self._starts) else len(self.text)
        at = begin + column - 1
        return at if at <= end else None

    def position(self, offset: int) -> Position:
        """The (line, column) of an offset."""
        index = bisect.bisect_right(self._starts, offset) - 1
        return index + 1, offset - self._starts[index] + 1

    def line_text(self, line: int) -> str:
        """The text of a line, without its line break ('' past the end)."""
        if not 1 <= line <= len(self._starts):
            return ""
        begin = self._starts[line - 1]
        end = self._starts[line] if line < len(self._starts) else len(self.text)
        return self.text[begin:end].rstrip("\r\n")

    def start_tag(self, line: int, column: int) -> tuple[int, int] | None:
        """The span (offsets) of the start tag written at a position (its ``<``, or one of its
        attributes), if one is there."""
        at = self.offset(line, column)
        if at is None:
            return None
        begin = at if self.text.startswith("<", at) else self.text.rfind("<", 0, at)
        if begin < 0:
            return None
        found = _START_TAG.match(self.text, begin)
        if found is None or found.end() <= at:
            return None
        return found.start(), found.end()

    def attributes(self, line: int, column: int) -> list[Attribute]:
        """The attributes of the start tag written at a position (none if none is there)."""
        tag = self.start_tag(line, column)
        if tag is None:
            return []
        start, end = tag
        name = _WORD.match(self.text, start)
        begin = start if name is None else name.end()
        found = []
        for match in _ATTRIBUTE.finditer(self.text, begin, end):
            group = 3 if match.group(3) is not None else 4
            found.append(Attribute(match.group(1), match.group(group), *match.span(group)))
        return found

    def end_of(self, line: int, column: int) -> Position | None:
        """Where the range of a finding at a position ends: the end of the start tag written
        there (of the attribute, for a position on one), else of the word there; None when
        the text has no such place."""
        tag = self.start_tag(line, column)
        if tag is not None:
            at = self.offset(line, column)
            for attribute in self.attributes(line, column):
                if at is not None and at < attribute.start and tag[0] != at:
                    return self.position(attribute.end + 1)  # the closing quote
            return self.position(tag[1])
        at = self.offset(line, column)
        if at is None:
            return None
        word = _WORD.match(self.text, at)
        if word is None:  # white space to the line's end: the line's end
            return line, len(self.line_text(line)) + 1
        return self.position(word.end())


class Texts:
    """Source texts by the names findings give files, each read and decoded once, through
    ``read`` (a workspace's, so unsaved texts count); a file that cannot be read is None."""

    def __init__(self, read: Callable[[str], bytes]) -> None:
        self._read = read
        self._known: dict[str, SourceText | None] = {}

    def add(self, path: str, data: bytes) -> None:
        """Know ``path``'s text as ``data`` (a URDF read from standard input)."""
        self._known[path] = SourceText.decode(path, data)

    def get(self, path: str) -> SourceText | None:
        """The text of ``path``, or None when it cannot be read."""
        if path not in self._known:
            try:
                data = None if path.startswith("<") else self._read(path)
            except FishbotUrdfError:
                data = None
            self._known[path] = None if data is None else SourceText.decode(path, data)
        return self._known[path]


def with_ranges(findings: Iterable[Diagnostic], texts: Texts) -> list[Diagnostic]:
    """``findings``, each with the end of its range where its text shows one (see
    :meth:`SourceText.end_of`)."""
    ranged = []
    for finding in findings:
        if finding.end_line is None and finding.line is not None and finding.column is not None:
            source = texts.get(finding.path)
            end = None if source is None else source.end_of(finding.line, finding.column)
            if end is not None:
                finding = replace(finding, end_line=end[0], end_column=end[1])
        ranged.append(finding)
    return ranged
