"""Inline suppressions: ``<!-- fishbot: ignore[rule, ...] -->`` in a robot file.

A comment right before an element (only white space and other comments between) silences
those rules for that element and everything inside it; one before the root element, for
the whole file. A suppression that silences nothing is itself reported.
"""

from __future__ import annotations

import bisect
import os
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from .diagnostics import Diagnostic, Kind, Subject, did_you_mean
from .model import Location

if TYPE_CHECKING:
    from .config import Config

__all__ = ["Suppression", "apply_suppressions", "suppressions"]

_MARK = re.compile(r"fishbot\s*:\s*ignore\s*\[([^\]]*)\]")
# Comments, CDATA, processing instructions, the DOCTYPE, start tags (group 1: the name,
# group 2: "/" when self-closing) and end tags (group 3).
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
        end: Where that element ends (just after it).
    """

    rules: tuple[str, ...]
    at: Location
    start: Position | None
    end: Position | None

    def covers(self, finding: Diagnostic, file: str) -> bool:
        """Whether ``finding`` (in ``file``, a resolved path) is about this suppression's
        element (or file)."""
        if file != _resolved(self.at.path):
            return False
        if self.start is None:
            return True
        if self.end is None:
            return False  # the comment stands before no element
        if finding.line is None:
            return False
        here = (finding.line, finding.column or 1)
        return self.start <= here < self.end


def suppressions(sources: Mapping[str, bytes | None]) -> tuple[Suppression, ...]:
    """Every suppression comment in ``sources``: file name (as findings name it) -> its
    bytes, or None to read it from disk (a file that cannot be read has none)."""
    found: list[Suppression] = []
    for name, data in sources.items():
        if data is None:
            try:
                data = Path(name).read_bytes()
            except OSError:
                continue
        if b"fishbot" in data:
            found.extend(_scan(data, name))
    return tuple(found)


def _resolved(name: str) -> str:
    return name if name.startswith("<") else os.path.realpath(name)


def _scan(data: bytes, path: str) -> list[Suppression]:
    lines = _LineTable(data)
    pending: list[tuple[tuple[str, ...], Location]] = []  # marks waiting for their element
    open_elements: list[tuple[int, list[tuple[tuple[str, ...], Location]]]] = []
    found: list[Suppression] = []
    seen_root = False
    for match in _TOKEN.finditer(data):
        comment, start_name, closing, end_name = match.group(1, 2, 3, 4)
        if comment is not None:
            mark = _MARK.search(comment.decode("utf-8", "replace"))
            if mark:
                names = tuple(n.strip() for n in mark[1].split(",") if n.strip())
                pending.append((names, lines.location(path, match.start())))
            continue
        if start_name is not None:
            marks, pending = pending, []
            if not seen_root:
                seen_root = True
                # Before the root element: the whole file.
                found.extend(Suppression(names, at, None, None) for names, at in marks)
                marks = []
            if closing:
                span = (lines.position(match.start()), lines.position(match.end()))
                found.extend(Suppression(names, at, *span) for names, at in marks)
            else:
                open_elements.append((match.start(), marks))
            continue
        if end_name is not None and open_elements:
            begin, marks = open_elements.pop()
            if marks:
                span = (lines.position(begin), lines.position(match.end()))
                found.extend(Suppression(names, at, *span) for names, at in marks)
            # A comment right before an end tag stands before no element.
            found.extend(
                Suppression(names, at, (at.line, at.column), None) for names, at in pending
            )
            pending = []
    found.extend(Suppression(names, at, (at.line, at.column), None) for names, at in pending)
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
    """Split ``findings`` into those kept and those a suppression silences; suppressions
    that silence nothing (of a rule that applies) or name no rule are reported in the kept
    list as ``unused-suppression`` findings."""
    from .rules import all_rules, ids
    from .rules.setup import UNUSED_SUPPRESSION

    findings = list(findings)
    if not marks:
        return findings, []
    fatal = {rule.id for rule in all_rules() if rule.fatal}
    files: dict[str, str] = {}
    used: set[tuple[int, str]] = set()
    kept: list[Diagnostic] = []
    silenced: list[Diagnostic] = []
    for finding in findings:
        file = files.get(finding.path)
        if file is None:
            file = files[finding.path] = _resolved(finding.path)
        hit = next(
            (
                index
                for index, mark in enumerate(marks)
                if finding.rule in mark.rules and mark.covers(finding, file)
            ),
            None,
        )
        if hit is None or finding.rule in fatal:
            kept.append(finding)
        else:
            used.add((hit, finding.rule))
            silenced.append(finding)
    known = ids()
    if config.applies(UNUSED_SUPPRESSION.id):
        for index, mark in enumerate(marks):
            subject = Subject(Kind.COMMENT, f"fishbot: ignore[{', '.join(mark.rules)}]")
            if not mark.rules:
                kept.append(
                    UNUSED_SUPPRESSION.report(
                        "fishbot: ignore[] names no rule",
                        mark.at,
                        path=mark.at.path,
                        subject=subject,
                        hint="name the rules to silence: fishbot: ignore[rule-id, ...]",
                    )
                )
            for rule in mark.rules:
                if rule not in known:
                    kept.append(
                        UNUSED_SUPPRESSION.report(
                            f"fishbot: ignore[{rule}] names no rule",
                            mark.at,
                            path=mark.at.path,
                            subject=subject,
                            hint=f"{did_you_mean(rule, known)}`fishbot rules` lists them",
                        )
                    )
                elif (index, rule) not in used and config.applies(rule):
                    scope = (
                        "in this file"
                        if mark.start is None
                        else "for the element after it"
                        if mark.end is not None
                        else "(it stands before no element)"
                    )
                    kept.append(
                        UNUSED_SUPPRESSION.report(
                            f"fishbot: ignore[{rule}] silences nothing {scope}",
                            mark.at,
                            path=mark.at.path,
                            subject=subject,
                            hint="remove it, or move it right before the element the "
                            "finding is about",
                        )
                    )
    return kept, silenced
