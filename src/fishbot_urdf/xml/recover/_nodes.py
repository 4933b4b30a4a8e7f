"""What TinyXML reads: nodes with the bytes it stores and where they start in the file."""

from __future__ import annotations

from dataclasses import dataclass, field

from ...catalog import Rule

# How TinyXML reads characters: UTF-8 sequences by their lead byte, or byte by byte (another
# encoding declared: LEGACY; none declared yet: UNKNOWN).
UTF8, LEGACY, UNKNOWN = "utf-8", "legacy", "unknown"


class Refused(Exception):
    """TinyXML (or urdfdom after it) refuses the document; ``offset`` is where, if known."""

    def __init__(self, reason: str, offset: int | None = None) -> None:
        super().__init__(reason)
        self.reason = reason
        self.offset = offset


class TooDeep(Refused):
    """Nested deeper than lxml allows: refused for that, whatever TinyXML does."""


@dataclass(slots=True)
class Note:
    """Something a strict XML parser refuses (or reads otherwise) at byte ``offset``: the
    rule it breaks, and what of it (``kind`` or ``kind:argument``, by rule)."""

    rule: Rule
    offset: int
    detail: str


@dataclass(slots=True)
class Attribute:
    name: bytes
    value: bytes  # as TinyXML stores it: references replaced, nothing else changed
    start: int
    quoted: bool


@dataclass(slots=True)
class Element:
    name: bytes
    start: int
    attributes: list[Attribute] = field(default_factory=list)
    children: list[Node] = field(default_factory=list)


@dataclass(slots=True)
class Text:
    value: bytes
    start: int


@dataclass(slots=True)
class Comment:
    value: bytes
    start: int
    closed: bool


@dataclass(slots=True)
class Other:
    """A declaration or anything else TinyXML keeps without reading (DOCTYPE, PI, junk)."""

    start: int
    end: int
    declaration: bool
    closed: bool = True
    encoding: bytes = b""


Node = Element | Text | Comment | Other


@dataclass(slots=True)
class Document:
    data: bytes  # the bytes TinyXML saw (up to the first NUL)
    nodes: list[Node]
    mode: str  # UTF8, LEGACY or UNKNOWN: how the top level finished
    notes: list[Note]
    stop: int | None  # where TinyXML stopped reading the top level early (text there)
    nul: int | None  # where the first NUL byte cut the file
