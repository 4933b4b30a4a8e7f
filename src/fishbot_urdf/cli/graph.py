"""`fishbot graph`: the link/joint tree drawn, as urdf_to_graphviz draws it."""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

import click

from ..diagnostics import escape_controls, has_errors
from ..drawing.dot import draw
from ..errors import FishbotUrdfError, InputError
from ..output import AtomicFile
from ._checking import check_input, nearest_config, read_files
from ._common import (
    EXIT_INVALID,
    EXIT_OK,
    emit_findings,
    fail,
    inputs_read,
    limit_options,
    package_option,
    packages_option,
    status_of,
    stop_on,
    to_stdout,
    xacro_args,
)

if TYPE_CHECKING:
    from ..analysis import Analysis
    from ..output import Source

# fishbot_urdf.drawing.dot.FORMATS, written out so that `fishbot --help` does not load the drawing
# code (tests/test_dot.py keeps the two equal).
_GRAPH_FORMATS = ("gv", "dot", "pdf", "svg", "png", "mmd")


@click.command()
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
@package_option()
@limit_options()
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
    values = xacro_args([a for a in args if ":=" in a])
    packages = packages_option(package_items)
    outputs = None if output is None else _graph_output(output, fmt)
    read = inputs_read()
    config = nearest_config(file)
    try:
        result = check_input(file, values, packages, config)
    except FishbotUrdfError as exc:
        stop_on(exc)
    emit_findings(result.diagnostics)
    if result.analysis is None:
        sys.exit(EXIT_INVALID)
    status = EXIT_INVALID if has_errors(result.diagnostics, strict=config.strict) else EXIT_OK
    named = outputs is not None or bool(names)  # else named after the robot, by the command
    try:
        if outputs is None:
            stem = names[0] if names else _file_name(result.analysis.robot.name, fmt)
            outputs = _graph_pair(stem, fmt)
        inputs = [*read_files(file, result), *read]
        _draw_all(result.analysis, outputs, detail, inputs, through_links=named)
    except InputError as exc:
        if named:
            stop_on(exc)
        # A name the command made itself, that it may not write: the user names one.
        emit_findings([replace(fail(exc), hint="name the output: give OUT or -o FILE")])
        sys.exit(status_of(exc))
    except FishbotUrdfError as exc:
        stop_on(exc)
    sys.exit(status)


def _file_name(robot: str, fmt: str | None) -> str:
    """The robot's name as the stem of the files written in the current folder, if it is a
    plain file name there (no folder in it, not . or ..).

    Raises:
        InputError: It is not.
    """
    separators = {"/", "\\", os.sep, os.altsep or os.sep, "\0"}
    if not robot or robot in (".", "..") or any(c in separators for c in robot):
        raise InputError(
            f"the robot's name {robot!r} is no file name in the current folder",
            path="<output>" if robot in ("", ".", "..") else f"{robot}.{fmt or 'gv'}",
        )
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
    robot: Analysis,
    outputs: list[tuple[str, str]],
    detail: bool,
    inputs: Sequence[Source],
    *,
    through_links: bool,
) -> None:
    """Write each output, saying "Created file" only for files really written; none when
    one of them may not be written (an input; without ``through_links``, a link)."""
    with contextlib.ExitStack() as stack:
        files = {
            path: stack.enter_context(AtomicFile(path, inputs=inputs, through_links=through_links))
            for path, _ in outputs
            if path != "-"
        }
        for path, fmt in outputs:
            try:
                data = draw(robot, fmt, detail=detail)
            except FishbotUrdfError as exc:
                exc.path = path  # the finding is about the file that could not be made
                raise
            if path == "-":
                to_stdout(data)
                continue
            files[path].write(data)
            files[path].commit(inputs)
            shown = escape_controls(path)
            to_stdout(f"Created file {shown}\n".encode("utf-8", "surrogateescape"))
