"""The exception tree of fishbot_urdf: every error the library raises is a FishbotUrdfError."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any


class FishbotUrdfError(Exception):
    """Base class of every error raised by fishbot_urdf.

    Attributes:
        path: The file the error is about, or None for text that came from memory.
        line: 1-based line in ``path``, when known.
        column: 1-based column in ``path``, when known.
        rule: A short stable id for the kind of problem (``xml-syntax``, ``io``, ...).
    """

    rule = "error"

    def __init__(
        self,
        message: str,
        *,
        path: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.path = path
        self.line = line
        self.column = column

    def __str__(self) -> str:
        where = ":".join(str(p) for p in (self.path, self.line, self.column) if p is not None)
        return f"{where}: {self.message}" if where else self.message


class InputError(FishbotUrdfError):
    """A file could not be read: it does not exist, is a folder, or is not readable."""

    rule = "io"


class ToolError(FishbotUrdfError):
    """A program the job runs (Graphviz's `dot`) failed; ``tool`` names it."""

    rule = "tool-failed"

    def __init__(
        self, message: str, *, tool: str, hint: str | None = None, path: str | None = None
    ) -> None:
        super().__init__(message, path=path)
        self.tool = tool
        self.hint = hint


class ToolNotFoundError(ToolError):
    """A program the job needs is not installed; ``hint`` says how to install it."""

    rule = "tool-missing"


class XmlSyntaxError(FishbotUrdfError):
    """The input is not well-formed XML (or uses XML features URDF never needs, like entities)."""

    rule = "xml-syntax"


class RobotError(FishbotUrdfError):
    """The robot description has errors; ``diagnostics`` lists every one of them."""

    rule = "invalid-robot"

    def __init__(self, diagnostics: Sequence[Any], *, path: str | None = None) -> None:
        self.diagnostics = tuple(diagnostics)
        first = self.diagnostics[0] if self.diagnostics else None
        count = len(self.diagnostics)
        summary = f"{first.message} [{first.rule}]" if first is not None else "invalid robot"
        if count > 1:
            summary += f" (and {count - 1} more)"
        super().__init__(
            summary,
            path=path if first is None else first.path,
            line=None if first is None else first.line,
            column=None if first is None else first.column,
        )
