"""Diagnostics: one finding about a robot description, what it is about, and how it prints."""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, fields
from types import MappingProxyType
from typing import Any

from .edits import Edit, Fix
from .errors import FishbotUrdfError
from .escaping import escape_controls, escape_line_controls
from .facts import Facts
from .location import Location
from .vocabulary import Consumer, Family, Kind, Severity, Subject

__all__ = [
    "ELEMENT",
    "FOLLOWS",
    "Consumer",
    "Diagnostic",
    "Edit",
    "Facts",
    "Family",
    "Fix",
    "Kind",
    "Rule",
    "Severity",
    "Subject",
    "diagnostic",
    "escape_controls",
    "escape_line_controls",
    "from_error",
    "has_errors",
    "shown_path",
    "sort_key",
    "without_consequences",
]

_NO_DATA: Mapping[str, Any] = MappingProxyType({})


FOLLOWS = "follows"
"""The key under which `Diagnostic.to_dict` lists the rules a finding follows from (see
`Diagnostic.follows`)."""

ELEMENT = "element"
"""The key under which `Diagnostic.to_dict` names the element a finding is about (see
`Diagnostic.element`)."""


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """One finding, located in a source file.

    Make one with `diagnostic` (or a rule's ``Rule.report``).

    Attributes:
        rule: Stable rule id, e.g. ``undefined-link``.
        severity: ERROR, WARNING or NOTE.
        message: What is wrong, naming the element (``joint 'wheel_joint': ...``).
        path: File the finding is in ('<string>' for text parsed from memory).
        line: 1-based line, or None when the finding is about the whole file.
        column: 1-based column (in characters), or None.
        hint: What is allowed or what to do; rendered in parentheses.
        subject: What the finding is about (the link, joint, ... and its name), if anything.
        data: Facts behind the finding for programs (numbers, names): a `Facts` of the
            rule's own type (a read-only mapping too); not compared.
        definition: The `Rule` it is a finding of (None for an error that stopped a file
            from being read, whose ``rule`` is a kind of error); not compared.
        follows: Ids of the rules whose findings this one follows from: it is only news
            when none of them is reported (see `without_consequences`); not compared.
        element: The element of its subject the finding is about, where that matters more
            than its rule's family: ``"inertial"`` for a link's mass, inertia and their
            origin, which leave the robot's shape and frames as they are; ``"axis"`` for a
            joint's axis, which urdfdom does not read for a fixed or floating joint; not
            compared.
        end_line: The line just past the range the finding is about (its element's start
            tag, or the value at fault in it), or None when only its start is known.
        end_column: The column just past that range (1-based, in characters).
        calls: For an element a xacro macro call made, the calls that made it: ``(macro
            name, where it was called)``, innermost first; not compared.
        fixes: The changes that mend it, as text edits (see `Fix`); not compared.
    """

    rule: str
    severity: Severity
    message: str
    path: str = "<string>"
    line: int | None = None
    column: int | None = None
    hint: str | None = None
    subject: Subject | None = None
    data: Mapping[str, Any] = field(default_factory=lambda: _NO_DATA, compare=False, repr=False)
    definition: Rule | None = field(default=None, compare=False, repr=False)
    follows: tuple[str, ...] = field(default=(), compare=False, repr=False)
    element: str | None = field(default=None, compare=False, repr=False)
    end_line: int | None = field(default=None, compare=False, repr=False)
    end_column: int | None = field(default=None, compare=False, repr=False)
    calls: tuple[tuple[str, Location], ...] = field(default=(), compare=False, repr=False)
    fixes: tuple[Fix, ...] = field(default=(), compare=False, repr=False)

    @property
    def is_error(self) -> bool:
        """True for ERROR findings."""
        return self.severity is Severity.ERROR

    @property
    def where(self) -> str:
        """``path:line:col`` (as much of it as is known)."""
        where = self.path
        if self.line is not None:
            where += f":{self.line}"
            if self.column is not None:
                where += f":{self.column}"
        return where

    def __reduce__(self) -> tuple[Any, ...]:
        # Pickled with plain facts as a dict (a read-only mapping does not pickle), so that
        # findings can come back from other processes.
        data = self.data if isinstance(self.data, Facts) else dict(self.data)
        return (_unpickled, (*(getattr(self, name) for name in _FIELDS), data))

    def with_hint(self, hint: str | None) -> Diagnostic:
        """This finding with ``hint`` in the place of its own."""
        # (as dataclasses.replace would make it, in half the time: a check may phrase
        # thousands)
        d = self
        return Diagnostic(
            d.rule,
            d.severity,
            d.message,
            d.path,
            d.line,
            d.column,
            hint,
            d.subject,
            d.data,
            d.definition,
            d.follows,
            d.element,
            d.end_line,
            d.end_column,
            d.calls,
            d.fixes,
        )

    def format(self) -> str:
        """Render as one GCC-style line: ``path:line:col: error: message (hint) [rule]``.

        Always one line, safe to print to a terminal: control characters in the path, the
        message or the hint are written as `escape_controls` writes them (a newline as
        ``\\n``, ESC as ``\\x1b``).
        """
        return self.format_with(self.hint)

    def format_with(self, hint: str | None) -> str:
        """`format`'s line, with ``hint`` in the place of the finding's own."""
        text = f"{self.where}: {self.severity.value}: {self.message}"
        if hint:
            text += f" ({hint})"
        return escape_controls(f"{text} [{self.rule}]")

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field (``fixes`` only when the check made them)."""
        subject = self.subject
        return {
            "rule": self.rule,
            "severity": self.severity.value,
            "message": self.message,
            "path": self.path,
            "line": self.line,
            "column": self.column,
            "end_line": self.end_line,
            "end_column": self.end_column,
            "hint": self.hint,
            "subject": None
            if subject is None
            else {"kind": subject.kind.value, "name": subject.name},
            "data": self._data_dict(),
        } | ({"fixes": [fix.to_dict() for fix in self.fixes]} if self.fixes else {})

    def _data_dict(self) -> dict[str, Any]:
        data = self.data
        facts = data.to_dict() if isinstance(data, Facts) else dict(data)
        if self.follows:
            facts[FOLLOWS] = list(self.follows)
        if self.element is not None:
            facts[ELEMENT] = self.element
        return facts


_FIELDS = (
    "rule",
    "severity",
    "message",
    "path",
    "line",
    "column",
    "hint",
    "subject",
    "definition",
    "follows",
    "element",
    "end_line",
    "end_column",
    "calls",
    "fixes",
)


def _unpickled(*values: Any) -> Diagnostic:
    *fixed, data = values
    (
        rule,
        severity,
        message,
        path,
        line,
        column,
        hint,
        subject,
        definition,
        follows,
        element,
        end_line,
        end_column,
        calls,
        fixes,
    ) = fixed
    return Diagnostic(
        rule,
        severity,
        message,
        path,
        line,
        column,
        hint,
        subject,
        data if isinstance(data, Facts) else (MappingProxyType(data) if data else _NO_DATA),
        definition,
        follows,
        element,
        end_line,
        end_column,
        calls,
        fixes,
    )


# Compared and hashed by identity: each rule is made once, and a dict keyed by rules (the
# CLI's hints) then hashes no text.
@dataclass(frozen=True, slots=True, eq=False)
class Rule:
    """One kind of finding.

    Attributes:
        id: Stable id, shown in brackets after each finding (``undefined-link``).
        severity: Its default severity.
        family: The group it belongs to.
        summary: One line: what it finds.
        explanation: Why it matters and what to do, a few sentences.
        bad: A small input that has the fault.
        good: The same input, fixed.
        consumers: The programs that refuse or misread what it finds.
        language: What ``bad`` and ``good`` are: ``urdf``, ``xacro`` or ``shell``.
        fatal: The input cannot be read past it; it cannot be turned off.
    """

    id: str
    severity: Severity
    family: Family
    summary: str
    explanation: str = ""
    bad: str = ""
    good: str = ""
    consumers: tuple[Consumer, ...] = (Consumer.URDFDOM,)
    language: str = "urdf"
    fatal: bool = False

    def __post_init__(self) -> None:
        _MADE.setdefault(self.id, self)

    def __reduce__(self) -> tuple[Any, ...]:
        # A catalogued rule comes back from another process as the same object (findings
        # made in worker processes keep their rule).
        if _MADE.get(self.id) is self:
            return (_made, (self.id,))
        return (Rule, tuple(getattr(self, f.name) for f in fields(self)))

    def report(
        self,
        message: str,
        where: Location | None,
        *,
        path: str,
        subject: Subject | None = None,
        hint: str | None = None,
        severity: Severity | None = None,
        data: Mapping[str, Any] | None = None,
        follows: Iterable[str] = (),
        element: str | None = None,
    ) -> Diagnostic:
        """A finding of this rule at ``where`` (or about the whole file ``path``), at its
        default severity unless ``severity`` says otherwise. ``data`` holds the facts behind
        it (a `Facts`), ``follows`` the ids of rules whose findings it follows from, ``element``
        the element of the subject it is about (see `Diagnostic`)."""
        return diagnostic(
            self.id,
            severity or self.severity,
            message,
            where,
            path=path,
            hint=hint,
            subject=subject,
            data=data,
            definition=self,
            follows=follows,
            element=element,
        )

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return {
            "id": self.id,
            "severity": self.severity.value,
            "family": self.family.value,
            "summary": self.summary,
            "explanation": self.explanation,
            "bad": self.bad,
            "good": self.good,
            "consumers": [c.value for c in self.consumers],
            "language": self.language,
            "fatal": self.fatal,
        }


_MADE: dict[str, Rule] = {}


def _made(rule_id: str) -> Rule:
    return _MADE[rule_id]


def diagnostic(
    rule: str,
    severity: Severity,
    message: str,
    where: Location | None = None,
    *,
    path: str = "<string>",
    line: int | None = None,
    column: int | None = None,
    hint: str | None = None,
    subject: Subject | None = None,
    data: Mapping[str, Any] | None = None,
    definition: Rule | None = None,
    follows: Iterable[str] = (),
    element: str | None = None,
) -> Diagnostic:
    """The one way to make a finding: at ``where`` (a Location), or else in ``path`` at
    ``line`` and ``column`` (None for the whole file). ``data`` is best a `Facts`; a plain
    mapping is kept as a read-only copy."""
    if isinstance(data, Facts):
        facts: Mapping[str, Any] = data
    else:
        facts = _NO_DATA if not data else MappingProxyType(dict(data))
    calls: tuple[tuple[str, Location], ...] = ()
    if where is not None:
        path, line, column = where.path, where.line, where.column
        calls = getattr(where, "calls", ())  # a MacroLocation's
    return Diagnostic(
        rule,
        severity,
        message,
        path,
        line,
        column,
        hint,
        subject,
        facts,
        definition,
        tuple(follows),
        element,
        None,
        None,
        calls,
    )


def from_error(exc: FishbotUrdfError, path: str = "<input>") -> Diagnostic:
    """The finding for an error that stopped a file from being read or written, of the
    catalogued rule of the error's id (None for an error of the library's own use, which
    no command reports)."""
    # An error names its rule by id: errors are the lowest layer, below the rules; each rule
    # is known by its id from the moment the catalogue makes it.
    return diagnostic(
        exc.rule,
        Severity.ERROR,
        exc.message,
        path=exc.path or path,
        line=exc.line,
        column=exc.column,
        hint=getattr(exc, "hint", None),
        subject=Subject(Kind.FILE, exc.path) if exc.path else None,
        definition=_MADE.get(exc.rule),
    )


def shown_path(name: str) -> str:
    """A path as a user would write it: relative to the current folder when inside it."""
    try:
        relative = os.path.relpath(name)
    except ValueError:  # another drive (Windows)
        return name
    return name if relative.startswith("..") else relative


def without_consequences(findings: Iterable[Diagnostic]) -> list[Diagnostic]:
    """``findings`` without those that only follow from another one reported among them
    (an extra root left by a misspelt parent link, say). When the cause is not reported (its
    rule is turned off or silenced), the consequence is."""
    kept = list(findings)
    rules = {finding.rule for finding in kept}
    return [f for f in kept if not rules.intersection(f.follows)]


def has_errors(diagnostics: Iterable[Diagnostic], *, strict: bool = False) -> bool:
    """True when any finding is an error (or, with ``strict``, a warning)."""
    failing = {Severity.ERROR, Severity.WARNING} if strict else {Severity.ERROR}
    return any(d.severity in failing for d in diagnostics)


def sort_key(diagnostic: Diagnostic) -> tuple[str, int, int, str]:
    """Order findings by file, line and column, as a compiler lists them."""
    return (diagnostic.path, diagnostic.line or 0, diagnostic.column or 0, diagnostic.rule)
