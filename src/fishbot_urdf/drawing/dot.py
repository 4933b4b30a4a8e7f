"""Robot -> DOT text as urdf_to_graphviz writes it, and rendering through Graphviz's `dot`.

The DOT text is written from the drawing's plan (`fishbot_urdf.drawing.layout`). For a
robot urdfdom accepts it is byte for byte what urdf_to_graphviz writes; beyond that, names
are escaped, a joint named like a link gets its own node, and links the root does not reach
are drawn too, marked.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import time
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from ..analysis import Analysis, of
from ..errors import ArgumentError, ToolError, ToolNotFoundError, ToolTimeoutError
from ..inputs import max_seconds
from ..model import Joint, Link, Robot
from ..output import write_atomic
from ..spatial import urdfdom_rpy
from .layout import JOINT_COLORS, Drawing, drawing, joint_facts, link_facts, numbers
from .mermaid import to_mermaid

__all__ = [
    "FORMATS",
    "Drawing",
    "draw",
    "drawing",
    "pipe_dot",
    "render",
    "render_graph",
    "source_files",
    "to_dot",
]

#: Output formats by file extension: DOT text, what `dot` renders, and Mermaid.
FORMATS = {"gv": "DOT", "dot": "DOT", "pdf": "PDF", "svg": "SVG", "png": "PNG", "mmd": "Mermaid"}

INSTALL_GRAPHVIZ = (
    "install Graphviz: apt install graphviz, brew install graphviz, winget install graphviz, "
    "or conda install -c conda-forge graphviz"
)


def to_dot(robot: Robot | Analysis, detail: bool = False) -> str:
    """The robot's kinematic tree as Graphviz DOT text.

    Without ``detail`` it is what urdf_to_graphviz writes: links as boxes, joints as blue
    ellipses, each joint's origin on the edge from its parent (xyz in metres, rpy in radians
    as urdfdom recovers them from the rotation). With ``detail``, joints show their type
    (one colour per type), axis, limits and mimic, and links their visuals, collisions and
    mass.
    """
    return "".join(_dot_lines(drawing(robot), detail))


def _dot_lines(plan: Drawing, detail: bool) -> Iterator[str]:
    yield "digraph G {\n"
    yield "node [shape=box];\n"
    for name in plan.links:
        link = plan.defined[name]
        label = name if not detail or link is None else "\n".join([name, *link_facts(link)])
        extra = ""
        if link is None:
            label += "\n(not defined)"
            extra = ", style=dotted, color=red, fontcolor=red"
        elif name in plan.unreachable:
            label += "\n(not reached from the root)"
            extra = ", style=dashed, color=red, fontcolor=red"
        yield f'"{_quote(name)}" [label="{_label(label)}"{extra}];\n'
    yield "node [shape=ellipse, color=blue, fontcolor=blue];\n"
    for edge in plan.edges:
        joint = edge.joint
        if detail:
            color = JOINT_COLORS[joint.type]
            label = "\n".join([edge.name, *joint_facts(joint)])
            yield f'"{_quote(edge.node)}" [label="{_label(label)}", color={color}, '
            yield f"fontcolor={color}];\n"
        elif edge.node != edge.name:
            yield f'"{_quote(edge.node)}" [label="{_label(edge.name)}"];\n'
        xyz, rpy = origin_numbers(joint)
        yield f'"{_quote(edge.parent)}" -> "{_quote(edge.node)}" '
        yield f'[label="xyz: {xyz} \\nrpy: {rpy}"]\n'
        yield f'"{_quote(edge.node)}" -> "{_quote(edge.child)}"\n'
    yield "}\n"


def _quote(text: str) -> str:
    """Text inside a DOT double-quoted string: a backslash or a quote must not end it."""
    return text.replace("\\", "\\\\").replace('"', '\\"')


def _label(text: str) -> str:
    return _quote(text).replace("\n", "\\n")


def origin_numbers(joint: Joint) -> tuple[str, str]:
    """A joint's origin as urdf_to_graphviz prints it: xyz, and rpy as urdfdom recovers it."""
    return numbers(joint.origin.xyz), numbers(urdfdom_rpy(joint.origin.rpy))


def pipe_dot(text: str, format: str, *, timeout: float | None = None) -> bytes:
    """Render DOT text with Graphviz's `dot` to ``format`` (``pdf``, ``svg`` or ``png``).

    `dot` runs in a process group of its own and is stopped, with everything it started,
    when it takes longer than ``timeout`` seconds (default: the time limit in force, see
    :func:`fishbot_urdf.inputs.time_limit`).

    Raises:
        ToolNotFoundError: `dot` is not installed (the message says how to install it).
        ToolTimeoutError: `dot` took longer than ``timeout``.
        ToolError: `dot` failed.
    """

    if timeout is None:
        timeout = max_seconds()
    executable = shutil.which("dot")
    missing = ToolNotFoundError(
        f"Graphviz's dot program is needed for {format.upper()} output and was not found",
        tool="dot",
        hint=INSTALL_GRAPHVIZ,
    )
    if executable is None:
        raise missing
    alone = {"start_new_session": True} if os.name == "posix" else {}
    try:
        process = subprocess.Popen(
            [executable, f"-T{format}"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            **alone,  # type: ignore[call-overload]
        )
    except FileNotFoundError as exc:
        raise missing from exc
    except OSError as exc:
        raise ToolError(f"dot could not be started: {exc.strerror}", tool="dot") from exc
    try:
        data, errors = _communicate(process, text.encode("utf-8", "surrogateescape"), timeout)
    except subprocess.TimeoutExpired as exc:
        _stop(process)
        raise ToolTimeoutError(
            f"dot did not finish drawing the {format.upper()} within {timeout:g} s",
            tool="dot",
            seconds=timeout,
        ) from exc
    except BaseException:  # an interrupt: dot goes too
        _stop(process)
        raise
    if process.returncode != 0:
        lines = errors.decode("utf-8", "replace").strip().splitlines()
        reason = lines[0] if lines else f"exit status {process.returncode}"
        raise ToolError(f"dot could not render {format.upper()}: {reason}", tool="dot")
    return data


_LONGEST_WAIT = 86_400.0
"""Seconds: the longest single wait for `dot`. The system's wait counts milliseconds in a C
int (24.8 days at most): a longer one overflows, so a longer timeout is waited in parts."""


def _communicate(process: Any, payload: bytes, timeout: float) -> tuple[bytes, bytes]:
    """``process.communicate(payload, timeout=timeout)``, waited in parts of at most
    `_LONGEST_WAIT`, so that any timeout holds (inf: none)."""
    end = time.monotonic() + timeout
    given: bytes | None = payload
    while True:
        try:
            wait = min(max(end - time.monotonic(), 0.0), _LONGEST_WAIT)
            out, err = process.communicate(given, timeout=wait)
            return out, err
        except subprocess.TimeoutExpired:
            if time.monotonic() >= end:
                raise
            given = None  # sent already: the next wait goes on with the rest


def _stop(process: Any) -> None:
    """Kill a process and what it started (its process group, on POSIX), and reap it."""
    try:
        if os.name == "posix":
            os.killpg(process.pid, signal.SIGKILL)
        else:
            process.kill()
    except OSError:
        pass  # it has just ended
    process.communicate()


def draw(
    robot: Robot | Analysis, format: str, *, detail: bool = False, timeout: float | None = None
) -> bytes:
    """The robot's link/joint graph as the bytes of a file in ``format``.

    ``format`` is a key of ``FORMATS``; Graphviz's `dot`, where it draws, gets ``timeout``
    seconds."""
    format = format.lower()
    if format not in FORMATS:
        raise ArgumentError(
            f"unknown format {format!r} (formats: {', '.join(FORMATS)})", name="format"
        )
    if format == "mmd":
        return to_mermaid(robot, detail=detail).encode("utf-8", "surrogateescape")
    text = to_dot(robot, detail=detail)
    if format in ("gv", "dot"):
        return text.encode("utf-8", "surrogateescape")
    return pipe_dot(text, format, timeout=timeout)


def render_graph(
    robot: Robot | Analysis,
    path: str | Path,
    *,
    format: str | None = None,
    detail: bool = False,
) -> Path:
    """Write the robot's link/joint graph to ``path``, in the format its extension names.

    ``.gv``/``.dot`` DOT text, ``.mmd`` a Mermaid flowchart, ``.pdf``/``.svg``/``.png``
    rendered by Graphviz's `dot`; ``format`` overrides the extension. The file is written
    whole or not at all, and never over a file the robot was read from (as far as its
    elements' locations tell). The 3D picture of the robot is `fishbot_urdf.picture`'s.

    Returns:
        The path written.

    Raises:
        ArgumentError: The format is not known.
        ToolNotFoundError: Rendering needs `dot`, and it is not installed.
        ToolError: `dot` failed.
        InputError: The file cannot be written.
    """
    chosen = format or Path(path).suffix.lstrip(".")
    analysis = of(robot)
    data = draw(analysis, chosen, detail=detail)
    return write_atomic(path, data, inputs=source_files(analysis.robot))


def render(
    robot: Robot | Analysis,
    path: str | Path,
    *,
    format: str | None = None,
    detail: bool = False,
) -> Path:
    """Write the robot's link/joint graph (deprecated: call `render_graph`).

    The same as `render_graph`, under a name that did not say what it draws: the 3D picture
    `fishbot render` makes is `fishbot_urdf.picture`.
    """
    warnings.warn(
        "fishbot_urdf.render is deprecated: it draws the link/joint graph, as "
        "fishbot_urdf.render_graph does (the 3D picture of `fishbot render` is "
        "fishbot_urdf.picture)",
        DeprecationWarning,
        stacklevel=2,
    )
    return render_graph(robot, path, format=format, detail=detail)


def source_files(robot: Robot) -> set[str]:
    """The files the robot's elements were read from, as their locations tell."""
    located: list[Robot | Link | Joint] = [robot, *robot.links, *robot.joints]
    return {item.source.path for item in located if item.source is not None}
