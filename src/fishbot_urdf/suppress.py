"""Inline suppressions: ``<!-- fishbot: ignore[rule, ...] -->`` in a robot file.

A comment right before an element (only white space, text and other comments between)
silences those rules for that element and everything inside it; one before the root
element, for the whole file. In a xacro file the comments are read from the sources (the
file and its includes): one before an element of a macro's body silences it in every call.
A suppression that silences nothing, names no rule, or stands before no element is itself
reported (``unused-suppression``); a fatal finding (the file cannot be read past it) is
never silenced.
"""

from __future__ import annotations

import bisect
import os
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .diagnostics import Diagnostic, Kind, Subject, did_you_mean
from .errors import InputError
from .inputs import read_input
from .location import Location

if TYPE_CHECKING:
    from .config import Config

__all__ = ["Suppression", "apply_suppressions", "suppressions"]

# The rule list holds no bracket: a try stops at the next marker's "[" (linear time).
_MARK = re.compile(r"fishbot\s*:\s*ignore\s*\[([^\[\]]*)\]")
# What looks meant as a suppression, well-formed or not.
_LOOSE = re.compile(r"fishbot\s*:\s*ignore", re.IGNORECASE)
# Comments (group 1: the text), CDATA, processing instructions, the DOCTYPE (with its
# internal subset), start tags (group 2: the name, group 3: "/" when self-closing; quoted
# attribute values may hold ">" and "/>") and end tags (group 4).
_TOKEN = re.compile(
    rb"<!--(.*?)-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>|<!DOCTYPE(?:[^\[>]|\[.*?\])*>"
    rb"|<([^\s/>!?][^\s/>]*)(?:\"[^\"]*\"|'[^']*'|[^>\"'])*?(/?)>|</([^\s>]+)\s*>",
    re.DOTALL,
)

Position = tuple[int, int]  # line, column (1-based, columns in characters)


@dataclass(frozen=True, slots=True)
class Suppression:
    """One ``fishbot: ignore[...]`` comment.

    Attributes:
        rules: The rule ids it names.
        at: Where the comment is.
        start: Where the element it covers begins; None for the whole file.
        end: Where that element ends (just after it); None when the comment stands before
            no element (or, with ``start`` None, for the whole file).
        malformed: The comment looks meant as a suppression but is not one
            (``fishbot: ignore massless-link``, a missing bracket).
    """

    rules: tuple[str, ...]
    at: Location
    start: Position | None
    end: Position | None
    malformed: bool = False

    def covers(self, finding: Diagnostic, file: str) -> bool:
        """Whether ``finding`` (in ``file``, a resolved path) is about this suppression's
        element (or file). A finding with a line but no column is covered when its line is
        one of the element's lines; one with no line only by a whole-file suppression."""
        if file != _resolved(self.at.path):
            return False
        if self.start is None:
            return True
        if self.end is None or finding.line is None:
            return False
        if finding.column is None:
            return self.start[0] <= finding.line <= self.end[0]
        return self.start <= (finding.line, finding.column) < self.end

    @property
    def size(self) -> tuple[int, int]:
        """How far the covered span reaches (for the narrowest first); the whole file is
        the widest."""
        if self.start is None or self.end is None:
            return (1 << 62, 0)
        return (self.end[0] - self.start[0], self.end[1] - self.start[1])


def suppressions(sources: Mapping[str, bytes | None]) -> tuple[Suppression, ...]:
    """Every suppression comment in ``sources``: file name (as findings name it) -> its
    bytes, or None to read it from disk (a file that cannot be read, or is not XML, such as
    a YAML file a xacro file loads, has none)."""
    found: list[Suppression] = []
    for name, data in sources.items():
        if data is None:
            try:
                data = read_input(name)
            except InputError:
                continue
        if b"fishbot" in data and data.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"<"):
            found.extend(_scan(data, name))
    return tuple(found)


def _resolved(name: str) -> str:
    return name if name.startswith("<") else os.path.realpath(name)


_Mark = tuple[tuple[str, ...], Location, bool]  # rules, where, malformed


def _scan(data: bytes, path: str) -> list[Suppression]:
    lines = _LineTable(data)
    pending: list[_Mark] = []  # marks waiting for their element
    open_elements: list[tuple[int, list[_Mark]]] = []  # start offset, the marks before it
    found: list[Suppression] = []
    seen_root = False

    def before_nothing(marks: Iterable[_Mark]) -> None:
        found.extend(
            Suppression(names, at, (at.line, at.column), None, bad) for names, at, bad in marks
        )

    for match in _TOKEN.finditer(data):
        comment, start_name, closing, end_name = match.group(1, 2, 3, 4)
        if comment is not None:
            text = comment.decode("utf-8", "replace")
            mark = _MARK.search(text)
            if mark:
                names = tuple(n.strip() for n in mark[1].split(",") if n.strip())
                pending.append((names, lines.location(path, match.start()), False))
            elif _LOOSE.search(text):
                pending.append(((), lines.location(path, match.start()), True))
            continue
        if start_name is not None:
            marks, pending = pending, []
            if not seen_root:
                seen_root = True
                # Before the root element: the whole file.
                found.extend(Suppression(names, at, None, None, bad) for names, at, bad in marks)
                marks = []
            if closing:
                span = (lines.position(match.start()), lines.position(match.end()))
                found.extend(Suppression(names, at, *span, bad) for names, at, bad in marks)
            else:
                open_elements.append((match.start(), marks))
            continue
        if end_name is not None and open_elements:
            # A comment right before an end tag stands before no element.
            before_nothing(pending)
            pending = []
            begin, marks = open_elements.pop()
            if marks:
                span = (lines.position(begin), lines.position(match.end()))
                found.extend(Suppression(names, at, *span, bad) for names, at, bad in marks)
    before_nothing(pending)
    found.sort(key=lambda mark: (mark.at.line, mark.at.column))
    return found


class _LineTable:
    """Byte offsets -> (line, column in characters)."""

    def __init__(self, data: bytes) -> None:
        self._data = data
        self._starts = [0] + [m.end() for m in re.finditer(rb"\n", data)]

    def position(self, offset: int) -> Position:
        index = bisect.bisect_right(self._starts, offset) - 1
        begin = self._starts[index]
        column = len(self._data[begin:offset].decode("utf-8", "replace")) + 1
        return index + 1, column

    def location(self, path: str, offset: int) -> Location:
        line, column = self.position(offset)
        return Location(path, line, column)


def apply_suppressions(
    findings: Iterable[Diagnostic], marks: Sequence[Suppression], config: Config
) -> tuple[list[Diagnostic], list[Diagnostic]]:
    """Split ``findings`` into those kept and those a suppression silences.

    Each silenced finding is credited to the narrowest suppression that covers it. The
    suppressions that silence nothing (of a rule that applies), name no rule or an unknown
    one, name a fatal rule, are malformed, or stand before no element are reported in the
    kept list as ``unused-suppression`` findings, which a ``fishbot: ignore
    [unused-suppression]`` comment covering them silences in turn.
    """
    from .rules.setup import UNUSED_SUPPRESSION

    findings = list(findings)
    if not marks:
        return findings, []
    order = sorted(range(len(marks)), key=lambda i: marks[i].size)
    used: set[tuple[int, str]] = set()
    kept, silenced = _split(findings, marks, order, used)
    if config.applies(UNUSED_SUPPRESSION.id):
        unused = _unused(marks, used, config, lint=False)
        more_kept, more_silenced = _split(unused, marks, order, used)
        kept.extend(more_kept)
        silenced.extend(more_silenced)
        # Whether an ignore[unused-suppression] silenced anything is known only now.
        kept.extend(_unused(marks, used, config, lint=True))
    return kept, silenced


def _split(
    findings: Iterable[Diagnostic],
    marks: Sequence[Suppression],
    order: Sequence[int],
    used: set[tuple[int, str]],
) -> tuple[list[Diagnostic], list[Diagnostic]]:
    from .rules import all_rules

    fatal = {rule.id for rule in all_rules() if rule.fatal}
    files: dict[str, str] = {}
    kept: list[Diagnostic] = []
    silenced: list[Diagnostic] = []
    for finding in findings:
        if finding.rule in fatal:
            kept.append(finding)
            continue
        file = files.get(finding.path)
        if file is None:
            file = files[finding.path] = _resolved(finding.path)
        hit = next(
            (
                index
                for index in order
                if finding.rule in marks[index].rules and marks[index].covers(finding, file)
            ),
            None,
        )
        if hit is None:
            kept.append(finding)
        else:
            used.add((hit, finding.rule))
            silenced.append(finding)
    return kept, silenced


def _unused(
    marks: Sequence[Suppression], used: set[tuple[int, str]], config: Config, *, lint: bool
) -> list[Diagnostic]:
    """The findings about faulty suppressions; with ``lint``, only those naming
    unused-suppression that silence nothing, else all the others."""
    from .rules import Family, all_rules, ids
    from .rules.setup import UNUSED_SUPPRESSION

    lint_id = UNUSED_SUPPRESSION.id
    remove = "remove it, or move it right before the element the finding is about"
    if lint:
        return [
            _finding(mark, f"fishbot: ignore[{lint_id}] silences nothing {_scope(mark)}", remove)
            for index, mark in enumerate(marks)
            if lint_id in mark.rules
            and (index, lint_id) not in used
            and (mark.start is None or mark.end is not None)
        ]
    known = ids()
    fatal = {rule.id for rule in all_rules() if rule.fatal}
    families = {family.value for family in Family}
    found: list[Diagnostic] = []
    for index, mark in enumerate(marks):
        if mark.malformed:
            found.append(
                _finding(
                    mark,
                    "this comment is not a suppression fishbot understands",
                    "write <!-- fishbot: ignore[rule-id, ...] -->",
                )
            )
            continue
        if not mark.rules:
            found.append(
                _finding(
                    mark,
                    "fishbot: ignore[] names no rule",
                    "name the rules to silence: fishbot: ignore[rule-id, ...]",
                )
            )
        for rule in mark.rules:
            if rule not in known:
                hint = (
                    f"{rule!r} is a family: name its rules (`fishbot rules {rule}` lists them)"
                    if rule in families
                    else f"{did_you_mean(rule, known)}`fishbot rules` lists them"
                )
                found.append(_finding(mark, f"fishbot: ignore[{rule}] names no rule", hint))
            elif rule in fatal:
                found.append(
                    _finding(
                        mark,
                        f"fishbot: ignore[{rule}] cannot silence {rule}",
                        "the file cannot be read past it: fix the fault",
                    )
                )
            elif mark.start is not None and mark.end is None:
                found.append(
                    _finding(
                        mark,
                        f"fishbot: ignore[{rule}] stands before no element",
                        "move it right before the element the finding is about",
                    )
                )
            elif (index, rule) not in used and config.applies(rule) and rule != lint_id:
                message = f"fishbot: ignore[{rule}] silences nothing {_scope(mark)}"
                found.append(_finding(mark, message, remove))
    return found


def _scope(mark: Suppression) -> str:
    return "in this file" if mark.start is None else "for the element after it"


def _finding(mark: Suppression, message: str, hint: str) -> Diagnostic:
    from .rules.setup import UNUSED_SUPPRESSION

    subject = Subject(Kind.COMMENT, f"fishbot: ignore[{', '.join(mark.rules)}]")
    return UNUSED_SUPPRESSION.report(
        message, mark.at, path=mark.at.path, subject=subject, hint=hint
    )
