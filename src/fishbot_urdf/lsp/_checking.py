"""One round of checks, in the worker thread: the robots the changed files belong to, each
checked through the session's workspace, its findings placed in the files they are in."""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Mapping
from dataclasses import dataclass

from ..diagnostics import Diagnostic, from_error
from ..errors import FishbotUrdfError
from ..lint import check_file
from ..tops import find_tops, nearest_config
from ..workspace import Workspace
from ._convert import Lines, Shown, Units, shown_findings

__all__ = ["Round", "check_round", "findings_of", "lines_reader", "merged"]


@dataclass(frozen=True, slots=True)
class Round:
    """What a round found: the robots each open file belongs to (by their top files), and,
    for each robot checked, its findings by the file they are shown in."""

    tops_of: Mapping[str, tuple[str, ...]]
    shown: Mapping[str, Mapping[str, list[Shown]]]


def check_round(
    workspace: Workspace,
    changed: Collection[str],
    open_files: Collection[str],
    checked: Collection[str],
    units: Units,
) -> Round:
    """Check the robots of the files ``changed`` that an open file belongs to, and those of
    the open files not yet ``checked``; every file is read through ``workspace``.

    Raises:
        Cancelled: The round was cancelled (see `fishbot_urdf.inputs.cancellable`).
    """
    tops_of = {path: find_tops(path, workspace) for path in open_files}
    active = {top for tops in tops_of.values() for top in tops}
    wanted = {top for path in changed for top in tops_of.get(path) or find_tops(path, workspace)}
    wanted |= active - set(checked)
    lines = _LinesOf(workspace, units)
    shown = {
        top: shown_findings(findings_of(top, workspace), top, lines) for top in wanted & active
    }
    return Round(tops_of, shown)


def findings_of(top: str, workspace: Workspace) -> tuple[Diagnostic, ...]:
    """The findings of ``top``'s check, with its nearest configuration, as `fishbot check`
    gives them; an error that stops the reading (or a wrong configuration) is one."""
    try:
        config = nearest_config(top, workspace)
        return check_file(top, config=config, workspace=workspace).diagnostics
    except FishbotUrdfError as exc:
        return (from_error(exc, top),)


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
