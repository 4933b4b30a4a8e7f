"""Findings and fixes as the protocol writes them: 1-based character columns to the client's
0-based positions (UTF-16 code units unless it chose another encoding), a finding made in
an included macro shown at its call too, fixes as code actions."""

from __future__ import annotations

import bisect
import itertools
import os
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from lsprotocol import types
from pygls.uris import from_fs_path, to_fs_path

from ..diagnostics import Diagnostic, Edit, Fix, Severity
from ..location import Location
from ..sourcetext import SourceText

__all__ = [
    "Lines",
    "Shown",
    "absolute",
    "code_actions",
    "path_of",
    "shown_findings",
    "to_range",
    "uri_of",
]

SOURCE = "fishbot"

_SEVERITY = {
    Severity.ERROR: types.DiagnosticSeverity.Error,
    Severity.WARNING: types.DiagnosticSeverity.Warning,
    Severity.NOTE: types.DiagnosticSeverity.Information,
}

# the rest of a name or number from where a finding starts, when it starts inside a tag
_WORD = re.compile(r"[\w.:/${}*+-]+")

Units = Callable[[str], int]
"""How many of the client's code units a text is (UTF-16 by default)."""


def utf16_units(text: str) -> int:
    """The UTF-16 code units of ``text``: the protocol's default position encoding."""
    return len(text.encode("utf-16-le")) // 2


class Lines:
    """A file's lines as the reader counts them (split at line feeds, columns in characters)
    and the client's units, to turn 1-based lines and character columns into positions,
    whose lines the protocol ends at a lone CR too."""

    __slots__ = ("_starts", "lines", "units")

    def __init__(self, lines: Sequence[str], units: Units = utf16_units) -> None:
        self.lines = lines
        self.units = units
        # the protocol's line each line starts on, where a lone CR makes them differ
        self._starts: list[int] | None = None
        if any("\r" in line for line in lines):
            crs = (_lone_crs(lines, i) for i in range(len(lines)))
            before = itertools.accumulate(crs, initial=0)
            self._starts = [i + count for i, count in enumerate(before)]

    @classmethod
    def of(cls, text: str | bytes, units: Units = utf16_units) -> Lines:
        """The lines of ``text`` (bytes are read as UTF-8, a wrong byte as U+FFFD)."""
        if isinstance(text, bytes):
            text = text.decode("utf-8", "replace")
        return cls(text.split("\n"), units)

    def line(self, index: int) -> str:
        """Line ``index`` (0-based) without its line end, or "" past the end."""
        if 0 <= index < len(self.lines):
            text = self.lines[index]
            return text[:-1] if index < len(self.lines) - 1 and text.endswith("\r") else text
        return ""

    def position(self, line: int, column: int) -> types.Position:
        """The position of 1-based ``line`` and character ``column`` (clamped to the line)."""
        index = max(line - 1, 0)
        prefix = self.line(index)[: max(column - 1, 0)]
        if self._starts is None:
            return types.Position(index, self.units(prefix))
        start = self._starts[min(index, len(self.lines))] + max(index - len(self.lines), 0)
        after = prefix.rpartition("\r")[2]
        return types.Position(start + prefix.count("\r"), self.units(after))

    def place(self, position: types.Position) -> tuple[int, int]:
        """The 1-based line and character column of a client's ``position`` (a position
        inside a character, or past its line's end, is taken to the character's start, or
        the line's end)."""
        index, offset = position.line, 0
        if self._starts is not None:
            index = max(bisect.bisect_right(self._starts, position.line) - 1, 0)
            if index < len(self.lines):
                pieces = self.line(index).split("\r")
                before = min(position.line - self._starts[index], len(pieces) - 1)
                offset = sum(len(piece) + 1 for piece in pieces[:before])
                return index + 1, offset + _characters(pieces[before], position, self.units) + 1
            index = len(self.lines) + position.line - self._starts[-1]
        return index + 1, _characters(self.line(index), position, self.units) + 1


def _characters(text: str, position: types.Position, units: Units) -> int:
    """How many characters of ``text`` come before ``position.character`` units."""
    count = taken = 0
    for character in text:
        taken += units(character)
        if taken > position.character:
            break
        count += 1
    return count


def _lone_crs(lines: Sequence[str], index: int) -> int:
    """The CRs of line ``index`` not followed by its LF."""
    text = lines[index]
    crs = text.count("\r")
    return crs - 1 if index < len(lines) - 1 and text.endswith("\r") else crs


def to_range(
    lines: Lines,
    line: int | None,
    column: int | None,
    end_line: int | None = None,
    end_column: int | None = None,
) -> types.Range:
    """The range of a finding or edit: from ``line``:``column`` to ``end_line``:``end_column``
    when it is known, else over the tag or word that starts there (the line, for a finding
    without a column; the first line, for one about the whole file)."""
    if line is None:
        return types.Range(lines.position(1, 1), lines.position(1, len(lines.line(0)) + 1))
    text = lines.line(line - 1)
    if column is None:
        indent = len(text) - len(text.lstrip())
        return types.Range(lines.position(line, indent + 1), lines.position(line, len(text) + 1))
    start = lines.position(line, column)
    if end_line is not None and end_column is not None:
        return types.Range(start, lines.position(end_line, end_column))
    return types.Range(start, lines.position(line, column + _extent(text, column - 1)))


def _extent(text: str, at: int) -> int:
    """How many characters from ``at`` a finding that gives no end covers: its tag (to its
    '>' on the line, or the line's end), or its word, or one character."""
    if at >= len(text):
        return 0
    if text[at] == "<":
        close = text.find(">", at)
        return (close + 1 if close >= 0 else len(text)) - at
    word = _WORD.match(text, at)
    return word.end() - at if word else 1


def absolute(path: str) -> str:
    """A finding's path as an absolute one (a relative path is the server's folder's)."""
    return os.path.normpath(os.path.abspath(path))


def path_of(uri: str) -> str | None:
    """The absolute path of a file URI, or None for any other (an unsaved buffer's)."""
    if not uri.startswith("file:"):
        return None
    path = to_fs_path(uri)
    return None if path is None else absolute(path)


def uri_of(path: str) -> str:
    """The file URI of ``path``."""
    return from_fs_path(path) or Path(path).as_uri()


@dataclass(frozen=True, slots=True)
class Shown:
    """A finding as published in one file: the protocol's diagnostic and the finding (at a
    macro's call, ``at_call`` is True)."""

    diagnostic: types.Diagnostic
    finding: Diagnostic
    at_call: bool = False


def shown_findings(
    findings: Iterable[Diagnostic], top: str, lines_of: Callable[[str], Lines]
) -> dict[str, list[Shown]]:
    """Each finding of the check of ``top``, by the absolute path of the file it is in, and,
    for one made inside a macro another file calls, also at that call (the outermost call
    in a file other than the finding's), each pointing at the other."""
    shown: dict[str, list[Shown]] = {}
    texts: dict[str, SourceText] = {}  # the files calls are in, each joined once
    for finding in findings:
        path = top if finding.path.startswith("<") else absolute(finding.path)
        lines = lines_of(path)
        where = to_range(lines, finding.line, finding.column, finding.end_line, finding.end_column)
        call = _outer_call(finding, path)
        text = finding.message + (f" ({finding.hint})" if finding.hint else "")
        related = None
        if call is not None:
            name, site = call
            site_path = absolute(site.path)
            site_lines = lines_of(site_path)
            if site_path not in texts:
                texts[site_path] = SourceText(site_path, "\n".join(site_lines.lines))
            # the call's start tag, over as many lines as it takes
            end = texts[site_path].end_of(site.line, site.column)
            site_range = to_range(site_lines, site.line, site.column, *(end or (None, None)))
            here = types.Location(uri_of(path), where)
            there = types.Location(uri_of(site_path), site_range)
            related = [types.DiagnosticRelatedInformation(there, f"macro {name} called here")]
            at_call = _diagnostic(finding, site_range, f"in macro {name}: {text}")
            at_call.related_information = [
                types.DiagnosticRelatedInformation(here, "the finding, in the macro")
            ]
            shown.setdefault(site_path, []).append(Shown(at_call, finding, at_call=True))
        diagnostic = _diagnostic(finding, where, text)
        diagnostic.related_information = related
        shown.setdefault(path, []).append(Shown(diagnostic, finding))
    return shown


def _outer_call(finding: Diagnostic, path: str) -> tuple[str, Location] | None:
    for name, site in reversed(finding.calls):
        if absolute(site.path) != path:
            return name, site
    return None


def _diagnostic(finding: Diagnostic, where: types.Range, text: str) -> types.Diagnostic:
    return types.Diagnostic(
        range=where,
        message=text,
        severity=_SEVERITY.get(finding.severity, types.DiagnosticSeverity.Error),
        code=finding.rule,
        source=SOURCE,
    )


def code_actions(shown: Shown, lines_of: Callable[[str], Lines]) -> list[types.CodeAction]:
    """The quick fixes of a finding: one code action per fix, the first safe one preferred."""
    actions = []
    preferred = next((fix for fix in shown.finding.fixes if fix.safe), None)
    for fix in shown.finding.fixes:
        actions.append(
            types.CodeAction(
                title=fix.title,
                kind=types.CodeActionKind.QuickFix,
                diagnostics=[shown.diagnostic],
                is_preferred=fix is preferred or None,
                edit=workspace_edit(fix, lines_of),
            )
        )
    return actions


def workspace_edit(fix: Fix, lines_of: Callable[[str], Lines]) -> types.WorkspaceEdit:
    """A fix's edits, by file."""
    changes: dict[str, list[types.TextEdit]] = {}
    for edit in fix.edits:
        path = absolute(edit.path)
        changes.setdefault(uri_of(path), []).append(text_edit(edit, lines_of(path)))
    return types.WorkspaceEdit(changes=changes)


def text_edit(edit: Edit, lines: Lines) -> types.TextEdit:
    """One edit, its columns in the client's units."""
    start = lines.position(edit.line, edit.column)
    end = lines.position(edit.end_line, edit.end_column)
    return types.TextEdit(types.Range(start, end), edit.text)
