"""Check a robot: read it, analyse it once, apply every selected rule, honour suppressions."""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

from .analysis import Analysis, analyse, of
from .analysis.topology import Topology
from .catalog import Consumer, Rule
from .catalog.reading import BAD_NUMBER, MISSING_ATTRIBUTE, ROBOT_NAME
from .config import Config
from .diagnostics import (
    Diagnostic,
    Kind,
    Subject,
    shown_path,
    sort_key,
    without_consequences,
)
from .fixes import attach
from .inputs import allowing_reads, read_input, reads_allowed, trusts_expressions
from .model import Robot
from .packages import PackageFinder
from .parsing import is_xacro_path, read
from .rules import CHECKS, Settings
from .rules.physics import GROUND_TOLERANCE
from .sourcetext import Texts, with_ranges
from .suppress import apply_suppressions, suppressions
from .targets import consumers_of, retarget, targets_of, urdfdom_refuses
from .validation import values
from .validation._readable import finite, readable
from .workspace import Workspace, package_key

if TYPE_CHECKING:
    from .packages import PackageFinder

__all__ = ["CheckResult", "check", "check_again", "check_file"]

_UNNAMED = (MISSING_ATTRIBUTE, ROBOT_NAME)


@dataclass(frozen=True, slots=True)
class CheckResult:
    """The outcome of checking one file.

    Attributes:
        path: The file checked.
        robot: The robot as read (possibly faulty), or None if there was no <robot>.
        diagnostics: Every finding of the selected rules that no comment silenced, sorted
            by position.
        analysis: The robot's analysis (topology, bodies, ...), when there is a robot.
        files: Every file the robot was read from (for xacro, with everything it includes).
        data: The URDF read: the file's bytes, or a xacro file's expansion.
        suppressed: The findings that ``fishbot: ignore[...]`` comments silenced.
        refused_by_urdfdom: urdfdom (check_urdf) builds no robot from the file, as the
            findings of the selected rules tell (silenced ones too, whatever the targets
            made of them: see `fishbot_urdf.targets.urdfdom_refuses`).
        targets: The programs the robot was checked for (see `fishbot_urdf.targets`).
    """

    path: str
    robot: Robot | None
    diagnostics: tuple[Diagnostic, ...]
    analysis: Analysis | None
    files: tuple[str, ...] = ()
    data: bytes = field(default=b"", repr=False)
    suppressed: tuple[Diagnostic, ...] = ()
    refused_by_urdfdom: bool = False
    targets: tuple[str, ...] = ()

    @property
    def topology(self) -> Topology | None:
        """The link structure, when there is a robot."""
        return None if self.analysis is None else self.analysis.topology

    @property
    def ok(self) -> bool:
        """True when there is a robot and no finding is an error."""
        return self.robot is not None and not any(d.is_error for d in self.diagnostics)


def check_file(
    source: str | Path | bytes,
    *,
    path: str | None = None,
    args: Mapping[str, str] | None = None,
    packages: Mapping[str, str | Path] | PackageFinder | None = None,
    config: Config | None = None,
    workspace: Workspace | None = None,
    fixes: bool = False,
) -> CheckResult:
    """Read and check one URDF or xacro file, collecting every finding.

    A xacro file is expanded with ``args`` and ``packages`` first; findings then point at the
    xacro source. ``packages`` may be a `fishbot_urdf.packages.PackageFinder`, which keeps
    where each mesh package was found for the next files. ``config`` selects the rules, sets
    their severities and the ground tolerance (default: every rule, at its default
    severity), and says which folders a xacro file may read in besides its own tree
    (``allow_read``), and the programs the robot is for (``targets``: an error that harms
    none of them is a warning, see `fishbot_urdf.targets`). ``fishbot: ignore[RULE]``
    comments in the file (and in a xacro file's includes) silence findings.

    With a ``workspace``, the files are read through it (an editor's unsaved texts over the
    disk), its packages are found (unless ``packages`` are given), and the result is kept
    there: asked again, it is given again at once while no file it read (or mesh it looked
    for) has changed.

    Each finding's range ends where its text shows (`fishbot_urdf.sourcetext`); with
    ``fixes``, each also has the fixes that mend it (`fishbot_urdf.fixes`).

    Raises:
        InputError: The file cannot be read.
        XmlSyntaxError: The file is not well-formed XML.
        XacroError: The xacro file cannot be expanded (a ReadOutsideError when it reads
            outside the folders it may read).
        PackageNotFoundError: The xacro file names a package that is not found.
    """
    config = config or Config()
    if workspace is None:
        return _checked(source, path, args, packages, config, None, fixes)
    finder = workspace.packages if packages is None else packages
    named = source if isinstance(source, bytes) else os.path.abspath(source)
    # Everything the answer depends on besides the files it reads: the context's trust and
    # the folders it allows too.
    key = (
        "check",
        named,
        path,
        tuple(sorted((args or {}).items())),
        package_key(finder),
        repr(config),
        fixes,
        trusts_expressions(),
        reads_allowed(),
    )
    return workspace.memo(
        key, lambda: _checked(source, path, args, finder, config, workspace, fixes)
    )


def _checked(
    source: str | Path | bytes,
    path: str | None,
    args: Mapping[str, str] | None,
    packages: Mapping[str, str | Path] | PackageFinder | None,
    config: Config,
    workspace: Workspace | None,
    fixes: bool,
) -> CheckResult:
    folders: Mapping[str, str | Path] | PackageFinder | None = packages
    if workspace is None and isinstance(packages, PackageFinder):
        folders = packages.packages  # (a workspace's finder keeps its answers: given whole)
    with allowing_reads(config.allow_read):
        parsed = read(source, path=path, args=args, packages=folders, workspace=workspace)
    found = list(parsed.diagnostics)
    analysis = None
    if parsed.robot is not None:
        analysis = analyse(parsed.robot, parsed.path, parsed.references, packages)
        found.extend(_rule_findings(analysis, found, config, packages))
    marks = suppressions(_sources(parsed.path, parsed.files, parsed.data))
    targets = targets_of(parsed.robot, config.targets)
    refused = urdfdom_refuses(config.apply(found), analysis)
    kept, silenced = apply_suppressions(
        config.apply(retarget(found, targets, analysis)), marks, config
    )
    kept = without_consequences(kept)
    kept.sort(key=sort_key)
    texts = Texts(read_input)  # through the workspace, when there is one: unsaved texts
    if not (parsed.files and is_xacro_path(parsed.files[0])):
        texts.add(parsed.path, parsed.data)
    kept = with_ranges(kept, texts)
    if fixes:
        kept = attach(kept, texts, parsed.files[0] if parsed.files else parsed.path, analysis)
    return CheckResult(
        parsed.path,
        parsed.robot,
        tuple(kept),
        analysis,
        parsed.files,
        parsed.data,
        tuple(sorted(silenced, key=sort_key)),
        refused,
        targets,
    )


def check(
    robot: Robot | Analysis,
    *,
    config: Config | None = None,
    packages: Mapping[str, str | Path] | PackageFinder | None = None,
) -> tuple[Diagnostic, ...]:
    """Check a robot's structure and values: every finding of the selected rules.

    The findings are sorted by position. ``packages`` are folders for the ``package://``
    names of meshes (looked up as for xacro's ``$(find)``). (Comments are not read here:
    see `check_file`.) ``config`` chooses the rules, their severities and the targets, as
    for `check_file`.

    A robot built in Python is held to what the reader gives: a number that is not finite, a
    missing name or a character XML cannot hold is the reader's finding (see
    `fishbot_urdf.validation`), and the other rules say nothing more about its link or
    joint.

    Raises:
        FieldTypeError: A field of the robot holds a value of the wrong type (a str where a
            number is, a list where a tuple is); a TypeError too.
    """
    given = robot.robot if isinstance(robot, Analysis) else robot
    path = robot.path if isinstance(robot, Analysis) else None
    model = values(given, path)  # first: an analysis needs the types right
    unnamed = any(d.definition in _UNNAMED for d in model)
    infinite = any(d.definition is BAD_NUMBER for d in model)
    if unnamed or infinite:
        # The rules compare and sort names: one that is None is read as one left out, "".
        # They do arithmetic on numbers: one that is not finite is read as 0.
        readable_robot = readable(given) if unnamed else given
        robot_read = finite(readable_robot) if infinite else readable_robot
        analysis = analyse(robot_read, path, packages=packages)
    else:
        analysis = of(robot, packages)
    config = config or Config()
    found = [*model, *_rule_findings(analysis, model, config, packages)]
    targeted = retarget(found, targets_of(given, config.targets), analysis)
    return tuple(sorted(without_consequences(config.apply(targeted)), key=sort_key))


def check_again(result: CheckResult, config: Config) -> tuple[Diagnostic, ...]:
    """The findings of ``config``'s rules on the robot ``result`` read, its analysis reused
    (a file read once, standard input too), silenced by the same ``fishbot: ignore``
    comments, for the programs ``config`` targets (default: those of the first check)."""
    analysis = result.analysis
    if analysis is None:
        return ()
    found = _rule_findings(analysis, [], config, analysis.packages)
    marks = suppressions(_sources(result.path, result.files, result.data))
    targets = targets_of(result.robot, config.targets) if config.targets else result.targets
    kept, _ = apply_suppressions(config.apply(retarget(found, targets, analysis)), marks, config)
    return tuple(sorted(without_consequences(kept), key=sort_key))


def _sources(path: str, files: tuple[str, ...], data: bytes) -> dict[str, bytes | None]:
    """The texts whose comments silence findings: a xacro file's sources (read again), or
    the URDF read."""
    if files and is_xacro_path(files[0]):  # the comments are in the sources
        return {shown_path(f): None for f in files}
    return {path: data}


def _rule_findings(
    analysis: Analysis,
    read_findings: list[Diagnostic] | tuple[()],
    config: Config,
    packages: Mapping[str, str | Path] | PackageFinder | None,
) -> Iterator[Diagnostic]:
    # A link or joint whose values could not be read has no trustworthy numbers: findings
    # about them would only repeat the fault (a mass of "1kg" read as none is no "massless
    # link", an effort limit left out is no "zero effort").
    unread: dict[Subject, list[Diagnostic]] = {}
    for d in read_findings:
        if d.is_error and d.subject is not None and d.subject.kind in (Kind.LINK, Kind.JOINT):
            unread.setdefault(d.subject, []).append(d)
    mm = config.ground_tolerance
    consumers = consumers_of(targets_of(analysis.robot, config.targets))
    selected = frozenset(r.id for check in CHECKS for r in check.reports if config.applies(r.id))
    settings = Settings(
        packages,
        GROUND_TOLERANCE if mm is None else mm / 1000.0,
        Consumer.GAZEBO in consumers,
        selected,
        for_mujoco=Consumer.MUJOCO in consumers,
    )
    # A check runs only when one of its rules is selected (--ignore meshes reads no mesh file).
    for check in CHECKS:
        if not _selected(check.reports, config):
            continue
        for finding in check.run(analysis, settings):
            subject = finding.subject
            faults = unread.get(subject, []) if check.uses_values and subject is not None else []
            if check.by_line and finding.line is not None:
                faults = [d for d in faults if (d.path, d.line) == (finding.path, finding.line)]
            if faults:
                finding = replace(finding, follows=tuple(sorted({d.rule for d in faults})))
            yield finding


def _selected(reports: Iterable[Rule], config: Config) -> bool:
    return any(config.applies(rule.id) for rule in reports)
