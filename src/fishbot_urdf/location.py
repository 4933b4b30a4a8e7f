"""Where something is written: a file, a line and a column."""

from __future__ import annotations

from typing import NamedTuple


class Location(NamedTuple):
    """Where an element starts in its source file (1-based line and column).

    A small immutable value like a vector, so a NamedTuple rather than a dataclass: a big
    file has hundreds of thousands of them, and tuples are made three times faster.
    """

    path: str
    line: int
    column: int
