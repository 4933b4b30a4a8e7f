"""`fishbot check`: check_urdf's output and every finding, in the format CI wants."""

from __future__ import annotations

import contextlib
import json
import os
import sys
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import click

from ..config import Config, check_selectors, check_severities, find_config, load_config
from ..diagnostics import Severity, shown_path
from ..errors import ConfigError, FishbotUrdfError, UnknownNameError
from ..inputs import recording_inputs
from ..output import AtomicFile, write_atomic
from ..packages import PackageFinder
from ..parsing import is_xacro_path
from ..report import github_annotations, json_report, sarif_report
from ..targets import target_name
from ._batch import Run, outcomes, tree_chunks
from ._checking import STDIN
from ._common import (
    EXIT_INVALID,
    EXIT_OK,
    EXIT_USAGE,
    Number,
    emit_findings,
    fail,
    limit_options,
    package_option,
    packages_option,
    status_of,
    stop_on,
    to_stdout,
    write_chunks,
    xacro_args,
)
from ._hints import phrased

if TYPE_CHECKING:
    from ..config import Config
    from ..diagnostics import Diagnostic
    from ..output import AtomicFile, Source
    from ..report import FileReport

FORMATS = ("text", "json", "sarif", "github")


class _Rules(click.ParamType):  # type: ignore[type-arg]
    """Rule ids or family names, comma-separated (the option may be repeated), checked
    against the registry as the option is read: a wrong one is a usage error."""

    name = "RULES"

    def __init__(self, key: str) -> None:
        self.key = key

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> tuple[str, ...]:
        if isinstance(value, tuple):
            return value
        names = tuple(part.strip() for part in str(value).split(",") if part.strip())
        try:
            check_selectors(self.key, names)
        except ConfigError as exc:
            self.fail(exc.problem, param, ctx)
        return names


class _Severity(click.ParamType):  # type: ignore[type-arg]
    """RULE=LEVEL, LEVEL one of error, warning, note."""

    name = "RULE=LEVEL"

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> tuple[str, str]:
        if isinstance(value, tuple):
            return value
        rule, sep, level = (part.strip() for part in str(value).partition("="))
        if not sep or not rule or level not in ("error", "warning", "note"):
            self.fail(f"{value!r} is not RULE=error|warning|note", param, ctx)
        try:
            check_severities({rule: level})
        except ConfigError as exc:
            self.fail(exc.problem, param, ctx)
        return rule, level


class _Targets(click.ParamType):  # type: ignore[type-arg]
    """Programs the robots are for, comma-separated (the option may be repeated)."""

    name = "PROGRAM"

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> tuple[str, ...]:
        if isinstance(value, tuple):
            return value
        names = tuple(part.strip() for part in str(value).split(",") if part.strip())
        try:
            return tuple(target_name(name) for name in names)
        except UnknownNameError as exc:
            self.fail(exc.message, param, ctx)


@dataclass(frozen=True, slots=True)
class _Options:
    """What the command line says about rules, on top of any configuration file."""

    select: tuple[str, ...] | None
    extend_select: tuple[str, ...]
    ignore: tuple[str, ...]
    severity: dict[str, str]
    strict: bool | None
    ground_mm: float | None
    targets: tuple[str, ...] | None
    config_file: str | None
    isolated: bool

    def config_for(
        self, file: str, found: dict[str, Config], folders: dict[Path, Path | None]
    ) -> Config:
        """The configuration that applies to ``file``: its nearest configuration file (or
        ``--config``, or none with ``--isolated``), with the options on top. ``found`` and
        ``folders`` keep what earlier files of the run found."""
        if self.isolated:
            where = None
        elif self.config_file is not None:
            where = self.config_file
        else:
            near = find_config("." if file == "-" else file, folders)
            where = None if near is None else shown_path(str(near))
        key = where or ""
        if key in found:
            return found[key]
        base = load_config(where) if where else Config()
        found[key] = base.updated(
            select=self.select,
            extend_select=self.extend_select,
            ignore=self.ignore,
            severity={rule: Severity(level) for rule, level in self.severity.items()},
            strict=self.strict,
            ground_tolerance=self.ground_mm,
            targets=self.targets,
        )
        return found[key]


@click.command()
@click.argument(
    "files",
    nargs=-1,
    metavar="FILE... [name:=value]...",
    type=click.Path(dir_okay=True, allow_dash=True),
)
@click.option(
    "--format",
    "fmt",
    type=click.Choice(FORMATS),
    default="text",
    show_default=True,
    help="text: check_urdf's tree on stdout, one line per finding on stderr; json: a report "
    "for programs; sarif: SARIF 2.1.0 for code scanning; github: workflow annotations.",
)
@click.option(
    "-o",
    "--output",
    metavar="FILE",
    help="Write what goes to standard output (the tree, or the report) to FILE instead "
    "(whole or not at all; never over a checked file).",
)
@click.option(
    "-q", "--quiet", is_flag=True, help="Findings only: no tree (text format; for hooks)."
)
@click.option(
    "--strict/--no-strict",
    default=None,
    help="Warnings fail too (exit 1). [default: the configuration's strict, else no]",
)
@click.option(
    "--select",
    type=_Rules("select"),
    multiple=True,
    help="Only these rules (ids or families, comma-separated; ALL for every rule), instead "
    "of the configuration's selection.",
)
@click.option(
    "--extend-select",
    type=_Rules("extend-select"),
    multiple=True,
    help="These rules as well as those selected.",
)
@click.option(
    "--ignore", type=_Rules("ignore"), multiple=True, help="Not these rules (ids or families)."
)
@click.option(
    "--severity",
    "severities",
    type=_Severity(),
    multiple=True,
    help="Report RULE's findings as errors, warnings or notes (repeatable).",
)
@click.option(
    "--target",
    "targets",
    type=_Targets(),
    multiple=True,
    help="The programs the robots are for (comma-separated, repeatable): ros (check_urdf, "
    "robot_state_publisher, RViz, MoveIt), check_urdf (its exit status exactly), gazebo, "
    "mujoco, drake, pybullet, ros2_control, all. A finding that harms none of them is a "
    "warning. [default: the configuration's targets, else ros, with gazebo for a robot with "
    "<gazebo> and ros2_control for one with <ros2_control> or <transmission>]",
)
@click.option(
    "--config",
    "config_file",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Read the rules' settings from this file (a fishbot.toml, or a pyproject.toml's "
    "[tool.fishbot]) instead of the nearest one above each checked file.",
)
@click.option("--isolated", is_flag=True, help="Read no configuration file.")
@click.option(
    "--skip-includes",
    is_flag=True,
    help="Pass over xacro files that define no robot (no name, no links: macros and "
    "properties for other files to include); they are still expanded, so a fault that "
    "stops the expansion is reported.",
)
@click.option(
    "--ground-tolerance",
    "ground_mm",
    type=Number(zero=True),
    metavar="MM",
    help="How far (millimetres) the lowest collision point may be below or above the ground "
    "(z = 0 of a footprint root link) before a warning. [default: 2]",
)
@click.option(
    "--jobs",
    type=click.IntRange(min=1),
    metavar="N",
    help="Check the files in N processes at once (Linux; from 8 files on). "
    "[default: one per usable processor]",
)
@click.option(
    "--fix",
    is_flag=True,
    help="Apply the safe fixes (a misspelt name that has a close match, a mesh's scale from "
    "millimetres) to the files of the robot's own package, then report what is left.",
)
@click.option(
    "--unsafe-fixes",
    is_flag=True,
    help="With --fix or --diff, also the fixes that guess (an <inertial> at water's density).",
)
@click.option(
    "--diff",
    is_flag=True,
    help="Print the fixes as a unified diff instead of applying them (exit 1 if there are "
    "any); nothing is written.",
)
@package_option()
@limit_options()
def check(
    files: Sequence[str],
    fmt: str,
    output: str | None,
    quiet: bool,
    strict: bool | None,
    select: Sequence[tuple[str, ...]],
    extend_select: Sequence[tuple[str, ...]],
    ignore: Sequence[tuple[str, ...]],
    severities: Sequence[tuple[str, str]],
    targets: Sequence[tuple[str, ...]],
    config_file: str | None,
    isolated: bool,
    skip_includes: bool,
    ground_mm: float | None,
    jobs: int | None,
    fix: bool,
    unsafe_fixes: bool,
    diff: bool,
    package_items: Sequence[str],
) -> None:
    """Check URDF or xacro files, like check_urdf, and more strictly.

    Prints on stdout exactly what check_urdf prints: the robot's name and its link tree
    where urdfdom builds the robot (whatever else is found), nothing where urdfdom refuses
    the file (a fault of <robot>, of a joint, of the names or of the tree). Every finding
    goes to stderr as one line,
    path:line:col: error: ... [rule]. A .xacro file is expanded first (name:=value
    arguments go to it) and findings point at the xacro source. Beyond check_urdf it checks
    masses and inertias (errors where a simulator would refuse them), inertias against
    their collision shapes, and whether a robot on a footprint root stands on the ground.

    A finding that harms only programs the robot is not for is a warning: by default a
    robot is for the ROS tools (check_urdf, robot_state_publisher, RViz), for Gazebo when
    it has <gazebo> elements, for ros2_control when it has <ros2_control> or <transmission>;
    --target names others (--target check_urdf: exit 1
    exactly where check_urdf fails).

    Rules are chosen by [tool.fishbot] in the nearest pyproject.toml, or a fishbot.toml,
    above each file (keys select, extend-select, ignore, severity, strict,
    ground-tolerance, allow-read, targets), then by the options: --select replaces the
    file's selection, the other options add to it. A comment
    <!-- fishbot: ignore[RULE, ...] --> right before an element silences RULE for it and
    everything inside it (before the root element, for the whole file). `fishbot rules`
    lists the rules. FILE may be - to read standard input (URDF).

    \b
    Exit status:
      0  every robot is valid (warnings allowed, unless strict)
      1  a robot has errors (with --strict, warnings too)
      2  a file could not be read or written, a package was not found,
         the configuration or the command line is wrong

    \b
    Examples:
      fishbot check robots/fishbot/urdf/first_robot.urdf
      fishbot check robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot check --strict a.urdf robot.urdf.xacro use_gpu:=false
      fishbot check --select physics --ignore inertia-mismatch robot.urdf
      fishbot check --severity limit-range=warning robot.urdf
      fishbot check --target gazebo --target mujoco robot.urdf
      fishbot check --config ci/fishbot.toml urdf/*.urdf
      fishbot check --format sarif -o fishbot.sarif urdf/*.urdf
      fishbot check --format github robot.urdf.xacro
      fishbot check -q --skip-includes $(git ls-files '*.urdf' '*.xacro')
      fishbot check --jobs 1 urdf/*.urdf
      fishbot check --diff robot.urdf.xacro
      fishbot check --fix robot.urdf.xacro
      xacro robot.urdf.xacro | fishbot check -
    """
    args = xacro_args([f for f in files if ":=" in f])
    packages = packages_option(package_items)
    names = [f for f in files if ":=" not in f]
    if not files:
        raise click.UsageError("Missing argument 'FILE...'.")
    if not names:
        raise click.UsageError("no FILE to check (name:=value arguments go with a .xacro file)")
    if isolated and config_file is not None:
        raise click.UsageError("--config and --isolated cannot be used together")
    if (fix or diff) and "-" in names:
        raise click.UsageError("--fix and --diff mend files: give the file, not - (stdin)")
    if diff and (fmt != "text" or output is not None):
        raise click.UsageError("--diff prints a diff on stdout: no --format or -o with it")
    options = _Options(
        select=tuple(r for group in select for r in group) if select else None,
        extend_select=tuple(r for group in extend_select for r in group),
        ignore=tuple(r for group in ignore for r in group),
        severity=dict(severities),
        strict=strict,
        ground_mm=ground_mm,
        targets=tuple(dict.fromkeys(t for group in targets for t in group)) if targets else None,
        config_file=config_file,
        isolated=isolated,
    )
    found: dict[str, Config] = {}
    folders: dict[Path, Path | None] = {}
    # every configuration first: a wrong one stops everything, before any output
    with recording_inputs() as looked_at:
        try:
            configs = [options.config_for(name, found, folders) for name in names]
        except FishbotUrdfError as exc:
            stop_on(exc)

    status = EXIT_OK
    if fix or diff:
        status = _fixing(names, configs, args, packages, diff=diff, unsafe=unsafe_fixes)

    reports: list[FileReport] = []
    # Never written over: the files checked (standard input, when it is a file), what
    # they read, the configuration files read (pyproject.toml files without a table too).
    inputs: list[Source] = [name for name in (*names, *looked_at) if name and name != "-"]
    if "-" in names:
        inputs.append(STDIN)
    sink = _tree_file(output, inputs) if fmt == "text" else None
    run = Run(
        args=args,
        finder=PackageFinder(packages),
        fmt=fmt,
        skip_includes=skip_includes,
        meshes=output not in (None, "-"),
        tree=fmt == "text" and not quiet,
        urdf_args=not any(map(is_xacro_path, names)),
    )
    with sink if sink is not None else contextlib.nullcontext():
        for done in outcomes(names, configs, run, _usable_processors() if jobs is None else jobs):
            status = max(status, done.status)
            inputs.extend(done.inputs)
            if done.report is not None:
                reports.append(done.report)
            emit_findings(done.findings)
            if done.tree is not None:
                _tree([done.tree], sink)
            elif done.result is not None:
                _tree(tree_chunks(done.result), sink)
        _finish(fmt, reports, output, sink, inputs)
    sys.exit(status)


def _fixing(
    names: Sequence[str],
    configs: Sequence[Config],
    args: dict[str, str],
    packages: dict[str, str],
    *,
    diff: bool,
    unsafe: bool,
) -> int:
    """--diff: print the fixes and stop (1: there are some); --fix: write them and go on
    (the status so far: 2 if a file could not be written, which the others still are)."""
    from ._fixing import fix_files, write_fixed  # difflib and the fixes load only here

    fixed = fix_files(names, configs, args, packages, unsafe=unsafe)
    if diff:
        to_stdout(fixed.diff().encode("utf-8", "surrogateescape"))
        _say_hidden(fixed.hidden)
        emit_findings(fail(exc) for exc in fixed.errors.values())
        statuses = [status_of(exc) for exc in fixed.errors.values()]
        sys.exit(max([EXIT_INVALID if fixed.changed() else EXIT_OK, *statuses]))
    failed = write_fixed(fixed)
    emit_findings(fail(exc) for exc in failed)
    changed = fixed.changed()
    if changed:
        files = "1 file" if len(changed) == 1 else f"{len(changed)} files"
        fixes = "1 fix" if fixed.count == 1 else f"{fixed.count} fixes"
        click.echo(f"fishbot check: {fixes} made in {files}", err=True)
    for path in dict.fromkeys(fixed.refused):
        click.echo(
            f"fishbot check: {shown_path(path)}: a fix left out: another robot that reads "
            "the file had more findings with it",
            err=True,
        )
    _say_hidden(fixed.hidden)
    return EXIT_USAGE if failed else EXIT_OK  # a file not written: an I/O fault


def _say_hidden(count: int) -> None:
    if count:
        fixes = "1 more fix" if count == 1 else f"{count} more fixes"
        click.echo(f"fishbot check: {fixes} with --unsafe-fixes", err=True)


def _tree_file(output: str | None, inputs: list[Source]) -> AtomicFile | None:
    """The file the trees stream into, for -o FILE (checked now, put in place at the end)."""
    if output is None or output == "-":
        return None

    try:
        return AtomicFile(output, inputs=inputs)
    except FishbotUrdfError as exc:
        stop_on(exc)


def _tree(chunks: Iterable[str], sink: AtomicFile | None) -> None:
    """A tree on stdout, streamed (a deep chain's tree is hundreds of megabytes), or into
    the -o file."""
    if sink is None:
        write_chunks(chunks)
        return
    try:
        for chunk in chunks:
            sink.write(chunk)
    except FishbotUrdfError as exc:  # a full disk
        stop_on(exc)


def _usable_processors() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # (not on macOS or Windows)
        return os.cpu_count() or 1


def _finish(
    fmt: str,
    reports: list[FileReport],
    output: str | None,
    sink: AtomicFile | None,
    inputs: Sequence[Source],
) -> None:
    """Write the report (or, for text, the trees) to stdout or ``output``."""
    if fmt == "text":  # the trees: on stdout already, or in the file, put in place now
        if sink is not None:
            try:
                sink.commit(inputs)
            except FishbotUrdfError as exc:
                stop_on(exc)
        return

    phrased_reports = [_with(r, tuple(phrased(d) for d in r.diagnostics)) for r in reports]
    if fmt == "json":
        data = (json.dumps(json_report(phrased_reports), indent=2) + "\n").encode(
            "utf-8", "surrogateescape"
        )
    elif fmt == "sarif":
        log = sarif_report(phrased_reports, version=_version())
        data = (json.dumps(log, indent=2) + "\n").encode("utf-8", "surrogateescape")
    else:
        findings = (d for r in phrased_reports for d in r.diagnostics)
        data = github_annotations(findings).encode("utf-8", "surrogateescape")
    if output is None or output == "-":
        to_stdout(data)
        return

    try:
        write_atomic(output, data, inputs=inputs)
    except FishbotUrdfError as exc:
        emit_findings([fail(exc)])
        sys.exit(EXIT_USAGE)


def _with(report: FileReport, diagnostics: tuple[Diagnostic, ...]) -> FileReport:
    return replace(report, diagnostics=diagnostics)


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version  # ~50 ms: only for --version

    try:
        return version("fishbot-urdf")
    except PackageNotFoundError:
        return "0"
