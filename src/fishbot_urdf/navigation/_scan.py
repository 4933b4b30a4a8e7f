"""A lenient scan of an XML file's text: its tags, their attributes with the places of their
values, its texts and comments, all as character offsets; a file being edited, not
well-formed, is scanned as far as it reads."""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass, field

from ..extensions import TAGS
from ..xml.locator import MARKUP
from .answers import Span

__all__ = ["Attribute", "Document", "Tag", "Text", "scan"]

# The markup the project's locator tells apart (comments, CDATA, processing instructions,
# the DOCTYPE, start tags), as a pattern over characters.
_MARKUP = re.compile(MARKUP.pattern.decode("ascii"), MARKUP.flags)
_NAME = re.compile(r"[^\s/>=<\"']+")
_ATTRIBUTE = re.compile(r"\s*([^\s/>=<\"']+)\s*=\s*(?:\"([^\"<]*)\"|'([^'<]*)')")
_CLOSE = re.compile(r"\s*(/?)>")
_END_TAG = re.compile(r"</\s*([^\s>]*)\s*>?")


@dataclass(frozen=True, slots=True)
class Attribute:
    """An attribute: its name and value as written (entities left as they are), and where
    the name starts and the value (inside its quotes) starts and ends."""

    name: str
    value: str
    name_start: int
    start: int
    end: int


@dataclass(slots=True, eq=False)
class Tag:
    """An element, from its start tag: the name, where the name is written, the attributes,
    the element that holds it (an index into `Document.tags`), and where it ends (after its
    end tag, or its start tag's ``/>``; the end of what was read for an element left open)."""

    name: str
    start: int
    name_start: int
    head_end: int
    attributes: tuple[Attribute, ...]
    parent: int | None
    index: int
    end: int = -1
    end_name_start: int | None = None  # where the name of its end tag is written
    children: list[int] = field(default_factory=list)
    # What holds it, known from its parent's when it is read (no walk up a deep file):
    macro: int | None = None  # the innermost <xacro:macro>
    extension: str | None = None  # the outermost <gazebo>, <transmission>, <ros2_control>
    plugin: bool = False  # inside a <plugin>

    def get(self, name: str) -> Attribute | None:
        for attribute in self.attributes:
            if attribute.name == name:
                return attribute
        return None

    @property
    def local(self) -> str:
        """The name without its prefix (``macro`` for ``xacro:macro``)."""
        return self.name.rpartition(":")[2]

    @property
    def xacro(self) -> bool:
        return self.name.startswith("xacro:")


@dataclass(frozen=True, slots=True)
class Text:
    """A run of character data between markup, with the element holding it."""

    start: int
    end: int
    parent: int | None


@dataclass(slots=True, eq=False)
class Document:
    """A file's text as scanned."""

    path: str
    text: str
    tags: list[Tag]
    texts: list[Text]
    comments: list[tuple[int, int]]
    _lines: list[int]
    _starts: list[int] = field(default_factory=list)
    _runs: dict[int | None, list[Text]] = field(default_factory=dict)

    def position(self, offset: int) -> tuple[int, int]:
        """1-based line and column (in characters) of ``offset``."""
        row = bisect.bisect_right(self._lines, offset) - 1
        return row + 1, offset - self._lines[row] + 1

    def offset(self, line: int, column: int) -> int:
        """The offset of 1-based ``line`` and ``column`` (clamped into the text)."""
        if line < 1:
            return 0
        if line > len(self._lines):
            return len(self.text)
        start = self._lines[line - 1]
        stop = self._lines[line] - 1 if line < len(self._lines) else len(self.text)
        return min(start + max(column, 1) - 1, stop)

    def span(self, start: int, end: int) -> Span:
        line, column = self.position(start)
        end_line, end_column = self.position(end)
        return Span(self.path, line, column, end_line, end_column)

    def tag_at(self, line: int, column: int) -> Tag | None:
        """The element whose start tag holds ``line``:``column`` (where a reader located it)."""
        offset = self.offset(line, column)
        if len(self._starts) != len(self.tags):
            self._starts = [tag.start for tag in self.tags]
        found = bisect.bisect_right(self._starts, offset) - 1
        if found >= 0 and offset < max(self.tags[found].head_end, self.tags[found].start + 1):
            return self.tags[found]
        return None

    def ancestors(self, tag: Tag) -> list[Tag]:
        found = []
        parent = tag.parent
        while parent is not None:
            found.append(self.tags[parent])
            parent = self.tags[parent].parent
        return found

    def inner_text(self, tag: Tag) -> Text | None:
        """The one run of text an element holds, when it holds no element."""
        if tag.children:
            return None
        if not self._runs and self.texts:  # made whole, then set: safe between threads
            runs_of: dict[int | None, list[Text]] = {}
            for text in self.texts:
                runs_of.setdefault(text.parent, []).append(text)
            self._runs = runs_of
        runs = self._runs.get(tag.index, ())
        return runs[0] if len(runs) == 1 else None


def scan(path: str, text: str) -> Document:
    """Every tag, text and comment of ``text``, in document order; never fails."""
    lines = [0] + [m.end() for m in re.finditer("\n", text)]
    tags: list[Tag] = []
    texts: list[Text] = []
    comments: list[tuple[int, int]] = []
    open_: list[int] = []
    position = 0

    def text_to(stop: int) -> None:
        if stop > position and text[position:stop].strip():
            texts.append(Text(position, stop, open_[-1] if open_ else None))

    while True:
        lt = text.find("<", position)
        if lt < 0:
            text_to(len(text))
            break
        text_to(lt)
        if text.startswith("</", lt):
            match = _END_TAG.match(text, lt)
            assert match is not None
            name = match[1]
            for depth in range(len(open_) - 1, -1, -1):
                if tags[open_[depth]].name == name:
                    for left in open_[depth + 1 :]:
                        tags[left].end = lt
                    tags[open_[depth]].end = match.end()
                    tags[open_[depth]].end_name_start = match.start(1)
                    del open_[depth:]
                    break
            position = max(match.end(), lt + 2)
            continue
        markup = _MARKUP.match(text, lt)
        if markup is not None and not markup.lastindex:  # comment, CDATA, PI, DOCTYPE
            if text.startswith("<!--", lt):
                comments.append((lt + 4, markup.end()))
            position = markup.end()
            continue
        name_match = _NAME.match(text, lt + 1)
        if name_match is None:
            position = lt + 1
            continue
        attributes = []
        at = name_match.end()
        while (found := _ATTRIBUTE.match(text, at)) is not None:
            quote = 2 if found.group(2) is not None else 3
            attributes.append(
                Attribute(
                    found[1], found[quote], found.start(1), found.start(quote), found.end(quote)
                )
            )
            at = found.end()
        close = _CLOSE.match(text, at)
        head_end = close.end() if close else at
        tag = Tag(
            name_match[0],
            lt,
            lt + 1,
            head_end,
            tuple(attributes),
            open_[-1] if open_ else None,
            len(tags),
        )
        if tag.parent is not None:
            outer = tags[tag.parent]
            outer.children.append(tag.index)
            tag.macro = outer.index if outer.name == "xacro:macro" else outer.macro
            tag.extension = outer.extension or (outer.name if outer.name in TAGS else None)
            tag.plugin = outer.plugin or outer.name == "plugin"
        tags.append(tag)
        if close is not None and close[1]:
            tag.end = head_end
        else:
            open_.append(tag.index)
        position = max(head_end, lt + 1)
    for left in open_:
        tags[left].end = len(text)
    return Document(path, text, tags, texts, comments, lines)
