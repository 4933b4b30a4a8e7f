"""`fishbot check --fix` and `--diff`: the findings' fixes applied to the files that wrote them.

The robot is checked through a workspace; the fixes of its findings (`fishbot_urdf.fixes`:
only files of the robot's own package, only the safe ones unless ``--unsafe-fixes``) are
made in the texts the workspace holds, and the robot checked again from them, until no fix
is left (or ten rounds). Then each changed file is written whole, atomically, or, with
``--diff``, the changes are printed as a unified diff and nothing is written.
"""

from __future__ import annotations

import difflib
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from ..config import Config
from ..diagnostics import Diagnostic, Edit, Fix, shown_path
from ..errors import FishbotUrdfError, InputError
from ..fixes import apply, error_finding
from ..inputs import read_input
from ..lint import check_file
from ..output import write_atomic
from ..sourcetext import Texts
from ..workspace import Workspace

__all__ = ["Fixed", "fix_files", "write_fixed"]

ROUNDS = 10
"""How many times a robot is checked and fixed again at most (a fix can uncover another)."""


@dataclass
class Fixed:
    """What the fixes changed: each file's text before and after, by absolute path, how
    many fixes were made, how many more ``--unsafe-fixes`` would make, and the files where
    a fix was undone because another robot reading the file lost by it."""

    before: dict[str, str] = field(default_factory=dict)
    after: dict[str, str] = field(default_factory=dict)
    count: int = 0
    hidden: int = 0  # fixes left for --unsafe-fixes
    refused: list[str] = field(default_factory=list)  # files a fix was undone in
    errors: dict[str, FishbotUrdfError] = field(default_factory=dict)  # robots not read

    def diff(self) -> str:
        """The changes as a unified diff, file by file (as git and patch read it)."""
        chunks = []
        for path, old in self.before.items():
            new = self.after[path]
            if new == old:
                continue
            name = shown_path(path)
            before, after = (name, name) if os.path.isabs(name) else (f"a/{name}", f"b/{name}")
            for line in difflib.unified_diff(
                old.splitlines(keepends=True), new.splitlines(keepends=True), before, after
            ):
                chunks.append(line)
                if not line.endswith("\n"):
                    chunks.append("\n\\ No newline at end of file\n")
        return "".join(chunks)

    def changed(self) -> list[str]:
        """The files whose text changed."""
        return [path for path, old in self.before.items() if self.after[path] != old]


def fix_files(
    names: Sequence[str],
    configs: Sequence[Config],
    args: Mapping[str, str],
    packages: Mapping[str, str],
    *,
    unsafe: bool = False,
) -> Fixed:
    """Fix the robots ``names`` (each checked with its configuration), in memory: the texts
    before and after. A robot that cannot be read is not fixed (the check that follows says
    why). A fix of a file that a robot fixed before also reads is undone when that robot
    then has more findings (a macro file two robots include, each naming the link its own
    way)."""
    workspace = Workspace(packages, keep=64)
    fixed = Fixed()
    done: list[tuple[str, Config, int]] = []  # the robots fixed so far, and their findings
    for name, config in zip(names, configs, strict=True):
        for _ in range(ROUNDS):
            try:
                findings = _findings(workspace, name, args, config)
            except FishbotUrdfError as exc:  # nothing to fix: the check says why
                fixed.errors[name] = exc
                break
            chosen, hidden = _chosen(findings, unsafe)
            undo = _apply(fixed, workspace, chosen)
            if not undo:
                fixed.hidden += hidden
                break
            if any(
                len(_findings(workspace, other, args, other_config)) > count
                for other, other_config, count in done
            ):
                for path, text in undo.items():
                    workspace.open(path, text)
                    fixed.after[path] = text
                fixed.refused.extend(undo)
                break
            fixed.count += len(chosen)
        if name not in fixed.errors:
            done.append((name, config, len(_findings(workspace, name, args, config))))
    for path in fixed.before:
        fixed.after.setdefault(path, fixed.before[path])
    return fixed


def _findings(
    workspace: Workspace, name: str, args: Mapping[str, str], config: Config
) -> tuple[Diagnostic, ...]:
    try:
        return check_file(
            name, args=args, config=config, workspace=workspace, fixes=True
        ).diagnostics
    except FishbotUrdfError as exc:  # a misspelt property stops the expansion
        found = error_finding(exc, Texts(workspace.read), name, name)
        if not found.fixes:
            raise
        return (found,)


def _chosen(findings: Sequence[Diagnostic], unsafe: bool) -> tuple[list[Fix], int]:
    """The fixes to make, each once (two calls of a macro share one), and how many more an
    unsafe choice would make."""
    chosen: dict[tuple[Edit, ...], Fix] = {}
    hidden: set[tuple[Edit, ...]] = set()
    for finding in findings:
        mending = [fix for fix in finding.fixes if not fix.silences]
        usable = [fix for fix in mending if fix.safe or unsafe]
        if usable:
            chosen.setdefault(usable[0].edits, usable[0])
        elif mending:
            hidden.add(mending[0].edits)
    return list(chosen.values()), len(hidden - set(chosen))


def _apply(fixed: Fixed, workspace: Workspace, fixes: Sequence[Fix]) -> dict[str, str]:
    """Make ``fixes`` in the workspace's texts (and note them in ``fixed``): the texts
    before, by file, of the files they changed (to undo them)."""
    edits: dict[str, list[Edit]] = {}
    for fix in fixes:
        for edit in fix.edits:
            edits.setdefault(os.path.abspath(edit.path), []).append(edit)
    undo: dict[str, str] = {}
    for path, wanted in edits.items():
        text = _text(workspace, path)
        new = apply(text, dict.fromkeys(wanted))  # one of each edit
        if new != text:
            undo[path] = text
            fixed.before.setdefault(path, text)
            fixed.after[path] = new
            workspace.open(path, new)
    return undo


def write_fixed(fixed: Fixed) -> list[InputError]:
    """Write each changed file whole, atomically, unless it changed on disk meanwhile: the
    files that could not be written, each an error (the others are written)."""
    failed = []
    for path in fixed.changed():
        try:
            if read_input(path).decode("utf-8", "surrogateescape") != fixed.before[path]:
                raise InputError("changed on disk while it was fixed: not written", path=path)
            write_atomic(path, fixed.after[path].encode("utf-8", "surrogateescape"))
        except InputError as exc:
            failed.append(exc)
            fixed.after[path] = fixed.before[path]
    return failed


def _text(workspace: Workspace, path: str) -> str:
    try:
        return workspace.read(path).decode("utf-8", "surrogateescape")
    except FishbotUrdfError as exc:
        raise InputError(f"cannot read it to fix it: {exc.message}", path=path) from exc
