"""The `fishbot` command line: one click group, one short function per subcommand.

Exit status: 0 the robot is valid, 1 the robot has errors, 2 usage or I/O problem.
"""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Iterable, Sequence
from typing import IO, TYPE_CHECKING, Any, NoReturn

import click

from ..diagnostics import Diagnostic, Severity, has_errors
from ..dot import FORMATS
from ..errors import FishbotUrdfError, InputError, ToolError
from ._options import PACKAGE_HELP, Number, text_or_json

if TYPE_CHECKING:
    from ..check import CheckResult
    from ..model import Robot

EXIT_OK, EXIT_INVALID, EXIT_USAGE = 0, 1, 2

_COLORS = {Severity.ERROR: "red", Severity.WARNING: "magenta", Severity.NOTE: "cyan"}


def _use_color(stream: IO[str]) -> bool:
    if os.environ.get("NO_COLOR"):
        return False
    return stream.isatty()


def _emit_findings(diagnostics: Iterable[Diagnostic]) -> None:
    err = sys.stderr
    color = _use_color(err)
    for d in diagnostics:
        line = d.format()
        if color:
            label = f"{d.severity.value}:"
            line = line.replace(
                f" {label} ", " " + click.style(label, fg=_COLORS[d.severity], bold=True) + " ", 1
            )
        click.echo(line, err=True, color=color)


def _fail(exc: FishbotUrdfError) -> Diagnostic:
    """One finding for an exception that stopped a file from being read."""
    hint = getattr(exc, "hint", None)
    return Diagnostic(
        exc.rule, Severity.ERROR, exc.message, exc.path or "<input>", exc.line, exc.column, hint
    )


def _status(exc: FishbotUrdfError) -> int:
    """Exit status for an error that stopped a file: 2 when the input or the setup is at
    fault (a file cannot be read or written, a package or a program is not found), 1 when
    the robot is."""
    from ..packages import PackageNotFoundError

    setup = (InputError, PackageNotFoundError, ToolError)
    return EXIT_USAGE if isinstance(exc, setup) else EXIT_INVALID


def _packages(items: Sequence[str]) -> dict[str, str]:
    packages: dict[str, str] = {}
    for item in items:
        name, sep, folder = item.partition("=")
        if not sep or not name or not folder:
            raise click.BadParameter(f"'{item}' is not NAME=PATH", param_hint="--package")
        if not os.path.isdir(folder):
            raise click.BadParameter(f"{folder} is not a folder", param_hint="--package")
        packages[name] = folder
    return packages


def _xacro_args(items: Sequence[str]) -> dict[str, str]:
    from ..expand import parse_args

    try:
        return parse_args(list(items))
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="ARGS") from None


def _check_input(
    name: str, args: dict[str, str], packages: dict[str, str], ground_mm: float = 2.0
) -> CheckResult:
    """Read and check FILE (- is standard input, read as URDF)."""
    from ..check import check_file

    tolerance = ground_mm / 1000.0
    if name == "-":
        return check_file(_stdin_urdf(), path="<stdin>", ground_tolerance=tolerance)
    return check_file(name, args=args, packages=packages, ground_tolerance=tolerance)


_PACKAGE_HELP = PACKAGE_HELP


def _stdin_urdf() -> bytes:
    """Standard input, which must be URDF: xacro there has no folder for its includes."""
    data = sys.stdin.buffer.read()
    if b"xmlns:xacro" in data[:4096] or b"<xacro:" in data:
        raise InputError(
            "standard input is read as URDF, and this is xacro (give the .xacro file's "
            "path, or pipe its expansion: fishbot expand FILE | fishbot check -)",
            path="<stdin>",
        )
    return data


@click.group(name="fishbot", context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="fishbot-urdf", prog_name="fishbot")
def cli() -> None:
    """fishbot: check and explore URDF robot descriptions, with or without ROS.

    \b
    Examples:
      fishbot check robots/fishbot/urdf/first_robot.urdf
      fishbot check --format json robot.urdf
      fishbot expand robot.urdf.xacro -o robot.urdf
      fishbot graph robot.urdf.xacro -o tree.pdf
      fishbot inertia cylinder --mass 1 --radius 0.1 --length 0.12
      fishbot inertia robot.urdf.xacro
    """


@cli.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(dir_okay=True, allow_dash=True))
@text_or_json("text: check_urdf's output; json: a report for machines.")
@click.option("--strict", is_flag=True, help="Warnings fail too (exit 1).")
@click.option(
    "--ground-tolerance",
    "ground_mm",
    type=Number(zero=True),
    default=2.0,
    show_default=True,
    metavar="MM",
    help="How far (millimetres) the lowest collision point may be below or above the ground "
    "(z = 0 of a footprint root link) before a warning.",
)
@click.option("--package", "package_items", multiple=True, metavar="NAME=PATH", help=_PACKAGE_HELP)
def check(
    files: Sequence[str], fmt: str, strict: bool, ground_mm: float, package_items: Sequence[str]
) -> None:
    """Check URDF or xacro files, like check_urdf, and more strictly.

    Prints exactly what check_urdf prints (the robot's name and its link tree) whenever the
    tree can be read, errors or not. Every finding goes to stderr as one line,
    path:line:col: error: ... [rule].
    A .xacro file is expanded first (name:=value arguments go to it) and findings point
    at the xacro source. Beyond check_urdf it checks masses and inertias (errors where a
    simulator would refuse them), inertias against their collision shapes, and whether a
    robot on a footprint root stands on the ground. FILE may be - to read standard input
    (URDF). Exit status: 0 valid (warnings allowed), 1 the robot has errors, 2 a file could
    not be read, a package was not found or the command line is wrong.

    \b
    Examples:
      fishbot check robots/fishbot/urdf/first_robot.urdf
      fishbot check robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot check --strict a.urdf robot.urdf.xacro use_gpu:=false
      fishbot check --ground-tolerance 5 robot.urdf.xacro
      xacro robot.urdf.xacro | fishbot check -
    """
    from ..graph import tree_text

    args = _xacro_args([f for f in files if ":=" in f])
    packages = _packages(package_items)
    status = EXIT_OK
    reports: list[dict[str, Any]] = []
    for name in (f for f in files if ":=" not in f):
        try:
            result = _check_input(name, args, packages, ground_mm)
        except FishbotUrdfError as exc:
            _report_failure(fmt, exc, reports)
            status = max(status, _status(exc))
            continue
        failed = result.robot is None or has_errors(result.diagnostics, strict=strict)
        if failed:
            status = max(status, EXIT_INVALID)
        if fmt == "json":
            reports.append(_json_report(result, failed))
            continue
        _emit_findings(result.diagnostics)
        # check_urdf's output whenever the tree can be printed, errors or not: a script
        # reading it keeps working, and the exit status tells the rest.
        topo = result.topology
        if result.robot is not None and topo and topo.root and not topo.loop_from_root:
            _write_chunks(tree_text(result.robot, topo))
    if fmt == "json":
        text = json.dumps({"ok": status == EXIT_OK, "files": reports}, indent=2) + "\n"
        _to_stdout(text.encode("utf-8"))
    sys.exit(status)


@cli.command()
@click.argument("file", type=click.Path())
@click.argument("args", nargs=-1)
@click.option(
    "-o",
    "--output",
    default="-",
    show_default=True,
    help="Where to write the URDF; - is standard output. Folders are made as needed.",
)
@click.option("--deps", is_flag=True, help="Print the files the expansion reads instead.")
@click.option("--package", "package_items", multiple=True, metavar="NAME=PATH", help=_PACKAGE_HELP)
def expand(
    file: str, args: Sequence[str], output: str, deps: bool, package_items: Sequence[str]
) -> None:
    """Expand a xacro file to URDF, as ROS's xacro command does, without ROS.

    ARGS are name:=value values for <xacro:arg>. $(find PKG) is resolved without ROS:
    --package first, then the package.xml above the file, ROS_PACKAGE_PATH,
    AMENT_PREFIX_PATH, the colcon workspace around the file, and ament_index_python.
    Errors point at the xacro source and the macro calls that led there. Exit status: 0
    done, 1 xacro refuses the input, 2 a file could not be read or written, a package was
    not found, or the command line is wrong.

    \b
    Examples:
      fishbot expand robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot expand robot.urdf.xacro use_gpu:=false -o build/robot.urdf
      fishbot expand robot.urdf.xacro --package my_description=src/my_description
      fishbot expand robot.urdf.xacro --deps
    """
    from ..expand import expand as run
    from ..output import write_atomic

    values = _xacro_args(args)
    packages = _packages(package_items)
    try:
        expansion = run(file, args=values, packages=packages)
        if deps:  # like xacro's, but one line in the order first read
            text = " ".join(expansion.dependencies) + "\n" if expansion.dependencies else ""
        else:
            text = expansion.text
        if output == "-":
            _to_stdout(text.encode("utf-8"))
        else:
            write_atomic(output, text, inputs=[file, *expansion.dependencies])
    except FishbotUrdfError as exc:
        _emit_findings([_fail(exc)])
        sys.exit(_status(exc))
    from ..parse import xacro_warning

    _emit_findings(xacro_warning(message, file) for message in expansion.messages)
    sys.exit(EXIT_OK)


_GRAPH_FORMATS = tuple(FORMATS)


@cli.command()
@click.argument("file", type=click.Path(allow_dash=True))
@click.argument("args", nargs=-1, metavar="[OUT] [name:=value]...")
@click.option(
    "-o",
    "--output",
    metavar="FILE",
    help="The file to write, its format from its extension; - writes DOT to standard output.",
)
@click.option(
    "--format",
    "fmt",
    type=click.Choice(_GRAPH_FORMATS),
    help="The output format, whatever the extension: gv/dot DOT, mmd Mermaid, or pdf/svg/png.",
)
@click.option(
    "--detail",
    is_flag=True,
    help="Also show joint types (one colour each), axes, limits, mimics, and link masses.",
)
@click.option("--package", "package_items", multiple=True, metavar="NAME=PATH", help=_PACKAGE_HELP)
def graph(
    file: str,
    args: Sequence[str],
    output: str | None,
    fmt: str | None,
    detail: bool,
    package_items: Sequence[str],
) -> None:
    """Draw the link/joint tree of a URDF or xacro file, like urdf_to_graphviz.

    As urdf_to_graphviz does, writes ROBOT_NAME.gv and ROBOT_NAME.pdf in the current
    folder, or OUT.gv and OUT.pdf when OUT is given, and the .gv is byte for byte the same
    (names with a quote or a backslash aside: they are escaped here). With -o the format
    follows the extension: .gv/.dot DOT text, .mmd a Mermaid flowchart for Markdown,
    .pdf/.svg/.png drawn by Graphviz's dot program. Joints named like links get their own
    node, and links the root does not reach are drawn in red. The robot's findings go to
    stderr as in `fishbot check`. Exit status: 0 drawn, 1 the robot has errors (drawn as far
    as it could be read), 2 a file could not be read or written, Graphviz is missing or
    failed, or the command line is wrong.

    \b
    Examples:
      fishbot graph robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot graph robot.urdf build/tree
      fishbot graph robot.urdf -o tree.svg
      fishbot graph robot.urdf.xacro use_gpu:=false -o tree.png --detail
      fishbot graph robot.urdf -o - | dot -Tpng -o tree.png
      fishbot graph robot.urdf -o README-tree.mmd
    """
    names = [a for a in args if ":=" not in a]
    if len(names) > 1 or (names and output is not None):
        raise click.UsageError("give one OUT (as urdf_to_graphviz ROBOT OUT) or -o FILE, not both")
    if file == "-" and len(names) < len(args):
        raise click.UsageError("name:=value arguments are for a .xacro file, not standard input")
    values = _xacro_args([a for a in args if ":=" in a])
    packages = _packages(package_items)
    outputs = None if output is None else _graph_output(output, fmt)
    try:
        result = _check_input(file, values, packages)
    except FishbotUrdfError as exc:
        _emit_findings([_fail(exc)])
        sys.exit(_status(exc))
    _emit_findings(result.diagnostics)
    robot = result.robot
    if robot is None:
        sys.exit(EXIT_INVALID)
    status = EXIT_INVALID if has_errors(result.diagnostics) else EXIT_OK
    if outputs is None:
        outputs = _graph_pair(names[0] if names else _file_name(robot.name), fmt)
    try:
        _draw_all(robot, outputs, detail, result.files)
    except FishbotUrdfError as exc:
        _emit_findings([_fail(exc)])
        sys.exit(_status(exc))
    sys.exit(status)


def _file_name(robot: str) -> str:
    if not robot or robot in (".", "..") or "/" in robot or "\\" in robot:
        raise click.UsageError(f"the robot's name {robot!r} is no file name: give OUT or -o FILE")
    return robot


def _graph_pair(stem: str, fmt: str | None) -> list[tuple[str, str]]:
    """urdf_to_graphviz's files: STEM.gv and STEM.pdf (or STEM.FORMAT with --format)."""
    if fmt is not None:
        return [(f"{stem}.{fmt}", fmt)]
    return [(f"{stem}.gv", "gv"), (f"{stem}.pdf", "pdf")]


def _graph_output(output: str, fmt: str | None) -> list[tuple[str, str]]:
    """-o FILE as (path, format): the format from --format, else from the extension."""
    if output in ("-", os.devnull):
        return [(output, fmt or "gv")]
    chosen = fmt or os.path.splitext(output)[1].lstrip(".").lower()
    if chosen not in _GRAPH_FORMATS:
        raise click.BadParameter(
            f"cannot tell the format of {output!r} (extensions: {', '.join(_GRAPH_FORMATS)}; "
            "or give --format)",
            param_hint="-o",
        )
    return [(output, chosen)]


def _draw_all(
    robot: Robot, outputs: list[tuple[str, str]], detail: bool, inputs: Sequence[str]
) -> None:
    """Write each output, saying "Created file" only for files really written."""
    from ..dot import draw
    from ..output import write_atomic

    for path, fmt in outputs:
        try:
            data = draw(robot, fmt, detail=detail)
        except FishbotUrdfError as exc:
            exc.path = path  # the finding is about the file that could not be made
            raise
        if path == "-":
            _to_stdout(data)
            continue
        write_atomic(path, data, inputs=inputs)
        _to_stdout(f"Created file {path}\n".encode())


def _report_failure(fmt: str, exc: FishbotUrdfError, reports: list[dict[str, Any]]) -> None:
    finding = _fail(exc)
    if fmt == "json":
        reports.append(
            {"path": finding.path, "ok": False, "robot": None, "diagnostics": [finding.to_dict()]}
        )
    else:
        _emit_findings([finding])


def _json_report(result: Any, failed: bool) -> dict[str, Any]:
    robot = result.robot
    topo = result.topology
    return {
        "path": result.path,
        "ok": not failed,
        "robot": None if robot is None else robot.name,
        "root": None if topo is None else topo.root,
        "links": None if robot is None else len(robot.links),
        "joints": None if robot is None else len(robot.joints),
        "diagnostics": [d.to_dict() for d in result.diagnostics],
    }


def _write_chunks(chunks: Iterable[str]) -> None:
    """Write text to stdout in large blocks (a deep tree prints hundreds of megabytes)."""
    buffer: list[str] = []
    size = 0
    for chunk in chunks:
        buffer.append(chunk)
        size += len(chunk)
        if size > 1 << 20:
            _to_stdout("".join(buffer).encode("utf-8"), flush=False)
            buffer, size = [], 0
    _to_stdout("".join(buffer).encode("utf-8"))


def _to_stdout(data: bytes, *, flush: bool = True) -> None:
    """Write to stdout; when the reader has gone (`fishbot check big.urdf | head`), stop
    quietly with status 0 rather than let click turn the broken pipe into status 1."""
    try:
        sys.stdout.buffer.write(data)
        if flush:
            sys.stdout.buffer.flush()
    except BrokenPipeError:
        _stop_quietly()
    except OSError as exc:  # a full disk, a closed terminal: one line, no traceback
        _emit_findings(
            [Diagnostic("io", Severity.ERROR, f"cannot write: {exc.strerror}", "<stdout>")]
        )
        _stop_quietly(EXIT_USAGE)


def _stop_quietly(status: int = EXIT_OK) -> NoReturn:
    try:  # nothing more may reach the closed pipe, not even the flush at exit
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass  # stdout is no real file (a test runner's buffer)
    sys.exit(status)


def main(argv: Sequence[str] | None = None) -> NoReturn:
    """Entry point of the `fishbot` console script and of `python -m fishbot_urdf`."""
    try:
        cli.main(
            args=list(argv) if argv is not None else None, prog_name="fishbot", standalone_mode=True
        )
    except BrokenPipeError:
        _stop_quietly()
    sys.exit(EXIT_OK)


from . import inertia as _inertia  # noqa: E402  (registers `fishbot inertia`)

cli.add_command(_inertia.inertia)
