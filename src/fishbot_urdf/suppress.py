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
import heapq
import os
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .catalog import Family, all_rules, ids
from .catalog.setup import UNUSED_SUPPRESSION
from .diagnostics import Diagnostic, Kind, Subject
from .errors import InputError
from .inputs import Deadline, deadline, read_input
from .location import Location
from .wording import did_you_mean

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
                # Each rule once, as written: a comment's findings grow with its rules.
                names = tuple(dict.fromkeys(n.strip() for n in mark[1].split(",") if n.strip()))
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
    findings = list(findings)
    if not marks:
        return findings, []
    index = _Index(marks)
    used: set[tuple[int, str]] = set()
    kept, silenced = index.split(findings, used)
    if config.applies(UNUSED_SUPPRESSION.id):
        unused = _unused(marks, used, config, lint=False)
        more_kept, more_silenced = index.split(unused, used)
        kept.extend(more_kept)
        silenced.extend(more_silenced)
        # Whether an ignore[unused-suppression] silenced anything is known only now.
        kept.extend(_unused(marks, used, config, lint=True))
    return kept, silenced


class _Index:
    """The suppressions by the file and rule they are about, to find the narrowest one
    that covers each finding.

    In time about linear in suppressions plus findings (and in memory linear in the
    comments' text): the spans of the marks naming a rule in a file, and the findings of
    that rule there, are swept through once in the order of their positions, the spans
    begun so far kept on a heap, narrowest on top (one that has ended before a finding has
    ended for every later one too).
    """

    def __init__(self, marks: Sequence[Suppression]) -> None:
        self.fatal = {rule.id for rule in all_rules() if rule.fatal}
        self.files: dict[str, str] = {}
        limit = deadline()
        order = sorted(range(len(marks)), key=lambda i: marks[i].size)
        # How narrow each mark is: 0 for the narrowest (the first of equals).
        self.rank = {index: place for place, index in enumerate(order)}
        # (file, rule) -> the best whole-file mark naming it, and the other marks' spans.
        self.wholes: dict[tuple[str, str], int] = {}
        self.spans: dict[tuple[str, str], list[tuple[Position, Position, int]]] = {}
        for index, mark in enumerate(marks):
            if index % 256 == 0:
                limit.check("matching suppression comments")
            if mark.start is not None and mark.end is None:
                continue  # before no element: it covers nothing
            file = self.resolved(mark.at.path)
            for rule in set(mark.rules):
                key = (file, rule)
                if mark.start is None or mark.end is None:
                    best = self.wholes.get(key)
                    if best is None or self.rank[index] < self.rank[best]:
                        self.wholes[key] = index
                else:
                    self.spans.setdefault(key, []).append((mark.start, mark.end, index))

    def resolved(self, name: str) -> str:
        file = self.files.get(name)
        if file is None:
            file = self.files[name] = _resolved(name)
        return file

    def split(
        self, findings: Sequence[Diagnostic], used: set[tuple[int, str]]
    ) -> tuple[list[Diagnostic], list[Diagnostic]]:
        """Findings kept and silenced, each silenced one credited in ``used`` to the
        narrowest suppression that covers it."""
        limit = deadline()
        hits: list[int | None] = [None] * len(findings)
        asked: dict[tuple[str, str], list[int]] = {}  # (file, rule) -> findings to place
        for number, finding in enumerate(findings):
            if number % 256 == 0:
                limit.check("matching suppression comments")
            if finding.rule in self.fatal:
                continue
            key = (self.resolved(finding.path), finding.rule)
            if key in self.wholes or key in self.spans:
                asked.setdefault(key, []).append(number)
        for key, numbers in asked.items():
            marked = self.spans.get(key, [])
            # A finding with a column is covered by an element's span; one with only a
            # line by the element's lines; one with no line by a whole-file comment only.
            located = [n for n in numbers if findings[n].line is not None]
            exact = [n for n in located if findings[n].column is not None]
            lines = [n for n in located if findings[n].column is None]
            if exact:
                where = [((findings[n].line or 0, findings[n].column or 0), n) for n in exact]
                _sweep(where, marked, self.rank, hits, limit)
            if lines:
                where = [((findings[n].line or 0, 0), n) for n in lines]
                # Lines only: a span from its start's line to its end's, both included.
                widened = [((s[0], 0), (e[0] + 1, 0), i) for s, e, i in marked]
                _sweep(where, widened, self.rank, hits, limit)
            whole = self.wholes.get(key)
            if whole is not None:
                for number in numbers:
                    if hits[number] is None:
                        hits[number] = whole
        kept: list[Diagnostic] = []
        silenced: list[Diagnostic] = []
        for finding, hit in zip(findings, hits, strict=True):
            if hit is None:
                kept.append(finding)
            else:
                used.add((hit, finding.rule))
                silenced.append(finding)
        return kept, silenced


def _sweep(
    where: list[tuple[Position, int]],
    marked: list[tuple[Position, Position, int]],
    rank: Mapping[int, int],
    hits: list[int | None],
    limit: Deadline,
) -> None:
    """Set ``hits[n]`` to the narrowest of the ``marked`` spans (start, end: the end not
    included; the mark's index) that holds each position of ``where`` (position, n),
    narrowness by ``rank``."""
    where.sort()
    marked = sorted(marked)
    begun: list[tuple[int, Position, int]] = []  # (narrowness, end, mark), narrowest first
    next_span = 0
    for step, (position, number) in enumerate(where):
        if step % 256 == 0:
            limit.check("matching suppression comments")
        while next_span < len(marked) and marked[next_span][0] <= position:
            _, end, index = marked[next_span]
            heapq.heappush(begun, (rank[index], end, index))
            next_span += 1
        while begun and begun[0][1] <= position:  # ended: for every later position too
            heapq.heappop(begun)
        if begun:
            hits[number] = begun[0][2]


def _unused(
    marks: Sequence[Suppression], used: set[tuple[int, str]], config: Config, *, lint: bool
) -> list[Diagnostic]:
    """The findings about faulty suppressions; with ``lint``, only those naming
    unused-suppression that silence nothing, else all the others."""
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
    limit = deadline()
    for index, mark in enumerate(marks):
        limit.check("matching suppression comments")
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
        guesses = 0  # each costs a comparison with every rule: a few for each comment
        for count, rule in enumerate(mark.rules):
            if count % 256 == 255:
                limit.check("matching suppression comments")
            if rule not in known:
                guess = ""
                if rule not in families and guesses < _SHOWN_RULES:
                    guesses += 1
                    guess = did_you_mean(rule, known)
                hint = (
                    f"{rule!r} is a family: name its rules (`fishbot rules {rule}` lists them)"
                    if rule in families
                    else f"{guess}`fishbot rules` lists them"
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


_SHOWN_RULES = 8  # a comment naming more is named by its first rules (and how many)


def _finding(mark: Suppression, message: str, hint: str) -> Diagnostic:
    # Bounded: a comment naming thousands of rules has a finding for each of them.
    names = ", ".join(mark.rules[:_SHOWN_RULES])
    if len(mark.rules) > _SHOWN_RULES:
        names += f", ... ({len(mark.rules)} rules)"
    subject = Subject(Kind.COMMENT, f"fishbot: ignore[{names}]")
    return UNUSED_SUPPRESSION.report(
        message, mark.at, path=mark.at.path, subject=subject, hint=hint
    )
