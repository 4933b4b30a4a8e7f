"""Diagnostics: one finding about a robot description, and how findings are rendered."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from enum import Enum
from typing import Any


class Severity(str, Enum):
    """How bad a finding is: errors make a robot invalid, warnings do not (unless --strict)."""

    ERROR = "error"
    WARNING = "warning"
    NOTE = "note"


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """One finding, located in a source file.

    Attributes:
        rule: Stable rule id, e.g. ``undefined-link``.
        severity: ERROR, WARNING or NOTE.
        message: What is wrong, naming the element (``joint 'wheel_joint': ...``).
        path: File the finding is in ('<string>' for text parsed from memory).
        line: 1-based line, or None when the finding is about the whole file.
        column: 1-based column (in characters), or None.
        hint: What is allowed or what to do; rendered in parentheses.
    """

    rule: str
    severity: Severity
    message: str
    path: str = "<string>"
    line: int | None = None
    column: int | None = None
    hint: str | None = None

    @property
    def is_error(self) -> bool:
        """True for ERROR findings."""
        return self.severity is Severity.ERROR

    def format(self) -> str:
        """Render as one GCC-style line: ``path:line:col: error: message (hint) [rule]``."""
        where = self.path
        if self.line is not None:
            where += f":{self.line}"
            if self.column is not None:
                where += f":{self.column}"
        text = f"{where}: {self.severity.value}: {self.message}"
        if self.hint:
            text += f" ({self.hint})"
        return f"{text} [{self.rule}]"

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return {
            "rule": self.rule,
            "severity": self.severity.value,
            "message": self.message,
            "path": self.path,
            "line": self.line,
            "column": self.column,
            "hint": self.hint,
        }


def closest(name: str, candidates: Iterable[str]) -> str | None:
    """The candidate that looks most like ``name`` (a likely misspelling), if any does."""
    import difflib

    close = difflib.get_close_matches(name, sorted(set(candidates)), n=1)
    return close[0] if close else None


def listing(names: Iterable[str], most: int = 8) -> str:
    """Sorted names, comma-separated, the first ``most`` of them then '...'."""
    ordered = sorted(set(names))
    return ", ".join(ordered[:most]) + (", ..." if len(ordered) > most else "")


def has_errors(diagnostics: Iterable[Diagnostic], *, strict: bool = False) -> bool:
    """True when any finding is an error (or, with ``strict``, a warning)."""
    failing = {Severity.ERROR, Severity.WARNING} if strict else {Severity.ERROR}
    return any(d.severity in failing for d in diagnostics)


def sort_key(diagnostic: Diagnostic) -> tuple[str, int, int, str]:
    """Order findings by file, line and column, as a compiler lists them."""
    return (diagnostic.path, diagnostic.line or 0, diagnostic.column or 0, diagnostic.rule)
