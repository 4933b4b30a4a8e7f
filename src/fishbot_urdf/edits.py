"""The changes that mend a finding, as edits of the text of its files."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["Edit", "Fix"]


@dataclass(frozen=True, slots=True)
class Edit:
    """Text to put in the place of a range of a file (an insertion: an empty range).

    Lines and columns are 1-based, columns in characters; ``end_line``/``end_column`` are
    just past the range.
    """

    path: str
    line: int
    column: int
    end_line: int
    end_column: int
    text: str

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return {
            "path": self.path,
            "line": self.line,
            "column": self.column,
            "end_line": self.end_line,
            "end_column": self.end_column,
            "text": self.text,
        }


@dataclass(frozen=True, slots=True)
class Fix:
    """A change that mends a finding, as edits of its files.

    Attributes:
        title: What it does, for a person choosing it (``replace 'base_lnk' with
            'base_link'``).
        edits: The edits, none overlapping another.
        safe: Whether ``fishbot check --fix`` applies it: it changes only what the finding
            is about and keeps the author's intent (a guess is applied only with
            ``--unsafe-fixes``).
        silences: It silences the finding (a suppression comment) rather than mending it:
            offered to an editor, never applied by ``--fix``.
    """

    title: str
    edits: tuple[Edit, ...]
    safe: bool = True
    silences: bool = False

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return {
            "title": self.title,
            "safe": self.safe,
            "silences": self.silences,
            "edits": [e.to_dict() for e in self.edits],
        }
