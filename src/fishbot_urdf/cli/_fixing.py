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
from ..diagnostics import Edit, shown_path
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
    """What the fixes changed: each file's text before and after, by absolute path, and how
    many fixes were made."""

    before: dict[str, str] = field(default_factory=dict)
    after: dict[str, str] = field(default_factory=dict)
    count: int = 0

    def diff(self) -> str:
        """The changes as a unified diff, file by file."""
        chunks = []
        for path, old in self.before.items():
            new = self.after[path]
            if new == old:
                continue
            name = shown_path(path)
            chunks.extend(
                difflib.unified_diff(
                    old.splitlines(keepends=True),
                    new.splitlines(keepends=True),
                    f"a/{name}",
                    f"b/{name}",
                )
            )
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
    before and after. Standard input (-) is not fixed, nor a robot that cannot be read (the
    check that follows says why)."""
    workspace = Workspace(packages, keep=8)
    fixed = Fixed()
    for name, config in zip(names, configs, strict=True):
        if name == "-":
            continue
        for _ in range(ROUNDS):
            try:
                result = check_file(name, args=args, config=config, workspace=workspace, fixes=True)
                findings = result.diagnostics
            except FishbotUrdfError as exc:  # a misspelt property stops the expansion
                findings = (error_finding(exc, Texts(workspace.read), name, name),)
            edits: dict[str, list[Edit]] = {}
            made = 0
            for finding in findings:
                for fix in finding.fixes:
                    if (fix.safe or unsafe) and not fix.silences:
                        for edit in fix.edits:
                            edits.setdefault(os.path.abspath(edit.path), []).append(edit)
                        made += 1
                        break  # one fix per finding
            if not edits:
                break
            progress = False
            for path, wanted in edits.items():
                text = _text(workspace, path)
                fixed.before.setdefault(path, text)
                new = apply(text, dict.fromkeys(wanted))  # one of each edit
                if new != text:
                    progress = True
                    fixed.after[path] = new
                    workspace.open(path, new)
            if not progress:
                break
            fixed.count += made
    for path in fixed.before:
        fixed.after.setdefault(path, fixed.before[path])
    return fixed


def write_fixed(fixed: Fixed) -> None:
    """Write each changed file whole, atomically, unless it changed on disk meanwhile.

    Raises:
        InputError: A file changed on disk since it was read, or cannot be written.
    """
    for path in fixed.changed():
        if read_input(path).decode("utf-8", "surrogateescape") != fixed.before[path]:
            raise InputError("changed on disk while it was fixed: not written", path=path)
        write_atomic(path, fixed.after[path].encode("utf-8", "surrogateescape"))


def _text(workspace: Workspace, path: str) -> str:
    try:
        return workspace.read(path).decode("utf-8", "surrogateescape")
    except FishbotUrdfError as exc:
        raise InputError(f"cannot read it to fix it: {exc.message}", path=path) from exc
