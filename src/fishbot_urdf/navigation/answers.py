"""What navigation answers with: places in files, outline symbols, completions."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Completion", "Span", "Symbol"]


@dataclass(frozen=True, slots=True)
class Span:
    """A stretch of a file: 1-based lines and columns in characters (a Python string index
    plus one), the end exclusive."""

    path: str
    line: int
    column: int
    end_line: int
    end_column: int


@dataclass(frozen=True, slots=True)
class Symbol:
    """A named thing a file defines, for its outline.

    Attributes:
        name: Its name as written (an expression for a name a macro builds).
        kind: ``link``, ``joint``, ``material``, ``macro``, ``property``, ``arg``,
            ``include`` or ``robot``.
        span: The whole element.
        selection: Its name.
        detail: A short description (a joint's type, a property's value, a macro's
            parameters, an include's file).
        children: What it holds (a macro's links, joints and properties).
    """

    name: str
    kind: str
    span: Span
    selection: Span
    detail: str = ""
    children: tuple[Symbol, ...] = ()


@dataclass(frozen=True, slots=True)
class Completion:
    """Something that may be written at a place.

    Attributes:
        label: What is offered.
        kind: ``link``, ``joint``, ``macro``, ``parameter``, ``property``, ``arg``,
            ``element``, ``attribute`` or ``rule``.
        detail: A short description.
        documentation: Markdown, longer.
        insert_text: What to write, when not the label.
    """

    label: str
    kind: str
    detail: str = ""
    documentation: str = ""
    insert_text: str | None = None
