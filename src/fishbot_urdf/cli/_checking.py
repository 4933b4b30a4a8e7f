"""What the commands that read and check a robot share: reading FILE with its nearest
configuration, what it read (never to be written over), and the narrower check of the
commands that pose the robot (tf, render, view)."""

from __future__ import annotations

import sys
from collections.abc import Iterable, Mapping
from dataclasses import replace
from typing import TYPE_CHECKING

import click

from ..catalog import all_rules
from ..catalog.xacro import XACRO_UNKNOWN_ARG, UnknownArgFacts
from ..config import Config, find_config, load_config
from ..diagnostics import Diagnostic
from ..errors import FishbotUrdfError
from ..lint import CheckResult, check_file
from ..model import JointType
from ..output import Source
from ..packages import PackageFinder
from ..rules import Family
from ..workspace import Workspace
from ._common import EXIT_INVALID, emit_findings, stdin_urdf, stop_on

if TYPE_CHECKING:
    from ..analysis import Analysis

__all__ = [
    "STDIN",
    "check_input",
    "nearest_config",
    "posable_input",
    "posing",
    "posing_errors",
    "posing_findings",
    "read_files",
]


def check_input(
    name: str,
    args: dict[str, str],
    packages: dict[str, str] | PackageFinder | Workspace,
    config: Config | None = None,
) -> CheckResult:
    """Read and check FILE (- is standard input, read as URDF: ``args`` are warned of),
    through ``packages`` when it is a workspace (one that keeps answers gives a robot
    again at once while none of its files changed), else through one for this read."""
    workspace = packages if isinstance(packages, Workspace) else Workspace(packages, keep=0)
    if name == "-":
        data = stdin_urdf()
        return check_file(data, path="<stdin>", args=args, config=config, workspace=workspace)
    return check_file(name, args=args, config=config, workspace=workspace)


STDIN = 0
"""Standard input's file descriptor: an input that is a file when stdin is one (`fishbot
check - -o robot.urdf < robot.urdf` is refused)."""


def read_files(name: str, result: CheckResult | None) -> list[Source]:
    """What a command made from FILE ``name``, never to be written over: the file (standard
    input for -, when that is a file), every file its reading read (includes, YAML), and
    the mesh files it names that are there (as its analysis found them), opened or not.
    Every other file read on the way (configuration, package.xml) is `inputs_read`'s."""
    found: list[Source] = [STDIN] if name == "-" else [name]
    if result is not None:
        found.extend(result.files)
        if result.analysis is not None:
            found.extend(map(str, result.analysis.mesh_paths.found(result.analysis.robot)))
    return found


def nearest_config(file: str) -> Config:
    """The configuration of the nearest fishbot.toml or pyproject.toml above ``file`` (the
    current folder for -), or the default; a wrong one stops the command."""
    found = find_config("." if file == "-" else file)
    try:
        return Config() if found is None else load_config(found)
    except FishbotUrdfError as exc:
        stop_on(exc)


def posing_errors(diagnostics: Iterable[Diagnostic]) -> list[Diagnostic]:
    """The errors that leave a robot's shape or tree in doubt (reading, URDF and structure
    rules, but for those about a link's inertial alone: its mass, inertia and their origin
    place nothing): `tf`, `render` and `view` stop on them; physics and mesh findings are
    `check`'s."""
    ids = {rule.id for rule in all_rules() if rule.family.value in _SHAPING}
    return [d for d in diagnostics if d.is_error and d.rule in ids and d.element != "inertial"]


_SHAPING = ("xml", "urdf", "structure", "xacro")  # the families of `posing_errors`


def posing(config: Config) -> Config:
    """``config`` with only the rules `posing_errors` looks at: a command that poses the
    robot runs no other check (and opens no mesh file to check it)."""
    return config.updated(ignore=[f.value for f in Family if f.value not in _SHAPING])


def posable_input(
    name: str,
    args: dict[str, str],
    packages: dict[str, str],
    refusal: str | None = None,
    *,
    config: Config | None = None,
) -> CheckResult:
    """FILE read and checked (with ``config``, else the nearest configuration, narrowed to
    the rules of `posing_errors`), for a command that poses the robot (tf, render): a robot
    whose shape or tree is in doubt stops it with its errors (and ``refusal``), exit 1; any
    other robot's findings are printed, as check prints them, and the command goes on."""
    config = config or nearest_config(name)
    try:
        result = check_input(name, args, packages, posing(config))
    except FishbotUrdfError as exc:
        stop_on(exc)
    blocking = posing_errors(result.diagnostics)
    if result.analysis is None or blocking:
        emit_findings(blocking)
        if refusal:
            click.echo(refusal, err=True)
        sys.exit(EXIT_INVALID)
    emit_findings(posing_findings(result, args))
    return result


def posing_findings(result: CheckResult, args: Mapping[str, str]) -> list[Diagnostic]:
    """The findings a command that poses the robot prints, once it can pose it: the check's,
    with a word for each name:=value argument that names a joint (-j places joints; xacro
    reads name:=value), whether no xacro file reads it or the file is URDF, which reads
    none."""
    analysis = result.analysis
    if not args or analysis is None:
        return list(result.diagnostics)
    return [_with_joint_hint(d, analysis, args) for d in result.diagnostics]


def _with_joint_hint(
    finding: Diagnostic, analysis: Analysis, args: Mapping[str, str]
) -> Diagnostic:
    facts = finding.data
    if finding.definition is not XACRO_UNKNOWN_ARG or not isinstance(facts, UnknownArgFacts):
        return finding
    arg = facts.argument
    if arg not in analysis.joints or arg not in args:
        return finding
    return replace(finding, hint=_joint_hint(analysis, arg, args[arg]))


def _joint_hint(analysis: Analysis, joint: str, value: str) -> str:
    if analysis.joints[joint].type is JointType.FIXED:
        return f"{joint!r} is a fixed joint, which takes no position"
    return f"{joint!r} is a joint: did you mean `-j {joint}={value}`?"
