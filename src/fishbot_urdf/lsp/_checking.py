"""One round of checks, in the worker thread: the robots the open files belong to, each
checked through the session's workspace (a robot none of whose files changed is given again
at once), its findings placed in the files they are in."""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Mapping
from dataclasses import dataclass, replace

from ..diagnostics import Diagnostic
from ..errors import FishbotUrdfError
from ..fixes import error_finding
from ..lint import check_file
from ..navigation import Index
from ..sourcetext import Texts
from ..tops import find_tops, nearest_config
from ..workspace import Workspace
from ._convert import Lines, Shown, Units, shown_findings

__all__ = [
    "Checked",
    "Round",
    "check_round",
    "findings_of",
    "index_of",
    "lines_reader",
    "merged",
]


@dataclass(frozen=True, slots=True)
class Checked:
    """A robot's findings, and where they are shown: by file, each file's list."""

    findings: tuple[Diagnostic, ...]
    shown: Mapping[str, list[Shown]]


@dataclass(frozen=True, slots=True)
class Round:
    """What a round found: the robots each open file belongs to (by their top files), and
    each of those robots checked."""

    tops_of: Mapping[str, tuple[str, ...]]
    checked: Mapping[str, Checked]


def check_round(
    workspace: Workspace,
    open_files: Collection[str],
    known: Mapping[str, Checked],
    units: Units,
) -> Round:
    """Check the robots the ``open_files`` belong to, every file read through
    ``workspace``; a robot whose findings are those ``known`` (none of its files changed:
    the check kept is given again) keeps what was shown of them, the very object.

    Raises:
        Cancelled: The round was cancelled (see `fishbot_urdf.inputs.cancellable`).
    """
    tops_of = {path: find_tops(path, workspace) for path in sorted(open_files)}
    lines = _LinesOf(workspace, units)
    checked = {}
    for top in sorted({top for tops in tops_of.values() for top in tops}):
        findings = findings_of(top, workspace)
        before = known.get(top)
        if before is not None and before.findings is findings:
            checked[top] = before
        else:
            checked[top] = Checked(findings, shown_findings(findings, top, lines))
    return Round(tops_of, checked)


def findings_of(top: str, workspace: Workspace) -> tuple[Diagnostic, ...]:
    """The findings of ``top``'s check, with its nearest configuration, as `fishbot check`
    gives them, each with its fixes; an error that stops the reading (or a wrong
    configuration) is one, with its fix where it has one (a property misspelt)."""
    try:
        config = nearest_config(top, workspace)
    except FishbotUrdfError as exc:  # shown in the configuration, and atop the robot too
        found = error_finding(exc, Texts(workspace.read), top, top)
        atop = replace(found, path=top, line=1, column=1, end_line=None, end_column=None)
        return (found, atop) if found.path != top else (found,)
    try:
        return check_file(top, config=config, workspace=workspace, fixes=True).diagnostics
    except FishbotUrdfError as exc:
        return (error_finding(exc, Texts(workspace.read), top, top),)


def index_of(path: str, workspace: Workspace) -> Index:
    """The navigation index of the first robot ``path`` belongs to whose check reads it
    (the check kept by the last round, while none of its files changed), else of ``path``
    alone (a robot that cannot be read in the middle of an edit, a file no robot reads).

    Raises:
        FishbotUrdfError: ``path`` cannot be read.
    """
    for top in find_tops(path, workspace):
        try:
            config = nearest_config(top, workspace)
            result = check_file(top, config=config, workspace=workspace, fixes=True)
        except FishbotUrdfError:
            continue
        index = Index.of(workspace, result)
        if path in index.files:
            return index
    return Index.of_file(workspace, path)


class _LinesOf:
    """Each file's lines, read once a round (the held text first)."""

    def __init__(self, workspace: Workspace, units: Units) -> None:
        self.workspace = workspace
        self.units = units
        self.known: dict[str, Lines] = {}

    def __call__(self, path: str) -> Lines:
        lines = self.known.get(path)
        if lines is None:
            try:
                text = self.workspace.read(path)
            except FishbotUrdfError:
                text = b""
            lines = self.known[path] = Lines.of(text, self.units)
        return lines


def lines_reader(workspace: Workspace, units: Units) -> Callable[[str], Lines]:
    """A reader of files' lines through ``workspace`` (each read once)."""
    return _LinesOf(workspace, units)


def merged(contributions: Iterable[list[Shown]]) -> list[Shown]:
    """The findings several robots show in one file, each once (two robots that include a
    file show its findings twice; one robot's two alike findings are both kept)."""
    seen: set[tuple[object, ...]] = set()
    kept: list[Shown] = []
    for shown in contributions:
        keys = [_key(item) for item in shown]
        kept.extend(item for item, key in zip(shown, keys, strict=True) if key not in seen)
        seen.update(keys)
    return kept


def _key(item: Shown) -> tuple[object, ...]:
    d = item.diagnostic
    return (d.range.start.line, d.range.start.character, d.code, d.message)
