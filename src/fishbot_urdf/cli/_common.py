"""What the subcommands share: printing findings and output, exit statuses, reading the
robot, and the options more than one command takes."""

from __future__ import annotations

import functools
import math
import os
import sys
from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from typing import IO, TYPE_CHECKING, Any, NoReturn, TypeVar

import click

from ..diagnostics import Diagnostic, Severity, escape_controls, from_error
from ..errors import (
    ConfigError,
    FishbotUrdfError,
    InputError,
    LimitError,
    ToolError,
    ToolNotFoundError,
)
from ..expansion import ExpansionLimitError, parse_args
from ..inputs import (
    InputTooLargeError,
    allowing_reads,
    max_bytes,
    max_seconds,
    read_input,
    recording_inputs,
    size_limit,
    time_limit,
    trusting_expressions,
)
from ..packages import PackageNotFoundError
from ..sourcetext import Texts, with_ranges
from ._hints import command_hint, error_hint

if TYPE_CHECKING:
    pass

EXIT_OK, EXIT_INVALID, EXIT_USAGE = 0, 1, 2

Wrapped = TypeVar("Wrapped", bound=Callable[..., object])

_COLORS = {Severity.ERROR: "red", Severity.WARNING: "magenta", Severity.NOTE: "cyan"}

PACKAGE_HELP = "Where ROS package NAME is, for $(find NAME) and package:// (repeatable)."


def use_color(stream: IO[str]) -> bool:
    """Colour only on a terminal, and never with NO_COLOR set."""
    if os.environ.get("NO_COLOR"):
        return False
    return stream.isatty()


_LINES_A_WRITE = 500  # findings written at once: few writes, and no robot's worth held twice


def emit_findings(diagnostics: Iterable[Diagnostic]) -> None:
    """Each finding as one line on stderr, its hint phrased for the command line."""
    err = sys.stderr
    color = use_color(err)
    lines: list[str] = []
    for d in diagnostics:
        line = d.format_with(command_hint(d))
        if color:
            label = f"{d.severity.value}:"
            line = line.replace(
                f" {label} ", " " + click.style(label, fg=_COLORS[d.severity], bold=True) + " ", 1
            )
        lines.append(line)
        if len(lines) == _LINES_A_WRITE:
            _echo_raw("\n".join(lines), err)
            lines.clear()
    if lines:
        _echo_raw("\n".join(lines), err)


def _echo_raw(line: str, stream: IO[str]) -> None:
    """A line on ``stream`` with file names that are no UTF-8 written as their own bytes."""
    data = (line + "\n").encode("utf-8", "surrogateescape")
    binary = getattr(stream, "buffer", None)
    if binary is None:
        stream.write(data.decode("utf-8", "replace"))
        return
    stream.flush()  # after what went through the text layer
    binary.write(data)
    binary.flush()


def fail(exc: FishbotUrdfError) -> Diagnostic:
    """One finding for an exception that stopped a file from being read, with its range
    where the file shows one."""
    (finding,) = with_ranges([from_error(exc)], Texts(read_input))
    phrasing = error_hint(exc)
    if phrasing is None:
        return finding
    message, hint = phrasing
    return replace(finding, message=message, hint=hint)


def not_installed(exc: ToolNotFoundError, command: str, needs: str) -> Diagnostic:
    """The line for an optional package not installed (viser, pygls): about ``command`` and
    the setup, not the input; ``needs`` names what needs the package."""
    return replace(
        fail(exc),
        path=command,
        subject=None,
        message=f"setup: the {exc.tool} package, an optional part of fishbot-urdf that "
        f"{needs} needs, is not installed",
        hint=f"install it: {exc.hint}",
    )


def status_of(exc: FishbotUrdfError) -> int:
    """Exit status for an error that stopped a file: 2 when the input or the setup is at
    fault (a file cannot be read or written, a package or a program is not found, the
    configuration is wrong, a limit is reached), 1 when the robot is."""
    setup = (
        InputError,
        PackageNotFoundError,
        ToolError,
        ConfigError,
        ExpansionLimitError,
        LimitError,
    )
    return EXIT_USAGE if isinstance(exc, setup) else EXIT_INVALID


def stop_on(exc: FishbotUrdfError) -> NoReturn:
    """Report an error that stops the command, and exit with its status."""
    emit_findings([fail(exc)])
    sys.exit(status_of(exc))


def packages_option(items: Sequence[str]) -> dict[str, str]:
    """``--package NAME=PATH`` values as a mapping."""
    packages: dict[str, str] = {}
    for item in items:
        name, sep, folder = item.partition("=")
        if not sep or not name or not folder:
            raise click.BadParameter(
                escape_controls(f"'{item}' is not NAME=PATH"), param_hint="--package"
            )
        if not os.path.isdir(folder):
            raise click.BadParameter(
                escape_controls(f"{folder} is not a folder"), param_hint="--package"
            )
        packages[name] = folder
    return packages


def xacro_args(items: Sequence[str]) -> dict[str, str]:
    """``name:=value`` arguments as a mapping."""
    if not items:
        return {}

    try:
        return parse_args(list(items))
    except FishbotUrdfError as exc:
        raise click.BadParameter(escape_controls(exc.message), param_hint="ARGS") from None


def inputs_read() -> list[str]:
    """Every file the command reads from now on (the robot, its includes and YAML files,
    the configuration files looked at, the package.xml files of its packages, the meshes
    it opens), added to the list as they are read: an output is never written over one."""
    return click.get_current_context().with_resource(recording_inputs())


def stdin_urdf() -> bytes:
    """Standard input, which must be URDF: xacro there has no folder for its includes."""
    limit = max_bytes()
    stream: IO[bytes] | None = getattr(sys.stdin, "buffer", None)
    if stream is None:  # closed by the caller (`<&-`)
        raise InputError(
            "standard input is closed (give a FILE, or pipe the robot in)", path="<stdin>"
        )
    chunks: list[bytes] = []
    left = limit + 1  # within the size limit, as files are; read in parts, as they are
    try:
        while left > 0:
            chunk = stream.read(min(left, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
    except (OSError, ValueError) as exc:  # not readable, or closed since
        reason = getattr(exc, "strerror", None) or str(exc)
        raise InputError(f"cannot read: {reason}", path="<stdin>") from exc
    data = b"".join(chunks)
    if len(data) > limit:
        raise InputTooLargeError("<stdin>", None, limit)
    if b"xmlns:xacro" in data[:4096] or b"<xacro:" in data:
        raise InputError(
            "standard input is read as URDF, and this is xacro (give the .xacro file's "
            "path, or pipe its expansion: fishbot expand FILE | fishbot check -)",
            path="<stdin>",
        )
    return data


def write_chunks(chunks: Iterable[str]) -> None:
    """Write text to stdout in large blocks (a deep tree prints hundreds of megabytes)."""
    buffer: list[str] = []
    size = 0
    for chunk in chunks:
        buffer.append(chunk)
        size += len(chunk)
        if size > 1 << 20:
            to_stdout("".join(buffer).encode("utf-8", "surrogateescape"), flush=False)
            buffer, size = [], 0
    to_stdout("".join(buffer).encode("utf-8", "surrogateescape"))


def to_stdout(data: bytes, *, flush: bool = True) -> None:
    """Write to stdout. When the reader has gone (`fishbot check big.urdf | head`), the
    rest of the output goes nowhere, quietly, and the command goes on to its own end and
    status: the reader chose to stop, and the robot's findings still go to stderr. Output
    that cannot be written (standard output closed, a full disk) is one line and exit 2."""
    try:
        sys.stdout.buffer.write(data)
        if flush:
            sys.stdout.buffer.flush()
    except BrokenPipeError:
        discard_stdout()
    except OSError as exc:  # closed (`>&-`), a full disk: one line, no traceback
        report_unwritten(exc)
        stop_quietly(EXIT_USAGE)


def report_unwritten(exc: OSError) -> None:
    """The one line for output that could not be written to stdout."""
    emit_findings([fail(InputError(f"cannot write: {exc.strerror}", path="<stdout>"))])


def discard_stdout() -> None:
    """From now on, what goes to stdout goes nowhere (the reader has gone, or it failed):
    nothing more may reach it, not even the flush at exit."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass  # stdout is no real file (a test runner's buffer)


def stop_quietly(status: int = EXIT_OK) -> NoReturn:
    """Exit, with nothing more sent to stdout (see `discard_stdout`)."""
    discard_stdout()
    sys.exit(status)


def format_option(choices: Sequence[str], text: str) -> Callable[[Wrapped], Wrapped]:
    """``--format`` among ``choices`` (the first is the default), stored as ``fmt``."""
    return click.option(
        "--format",
        "fmt",
        type=click.Choice(list(choices)),
        default=choices[0],
        show_default=True,
        help=text,
    )


def package_option() -> Callable[[Wrapped], Wrapped]:
    """``--package NAME=PATH`` (repeatable), stored as ``package_items``."""
    return click.option(
        "--package", "package_items", multiple=True, metavar="NAME=PATH", help=PACKAGE_HELP
    )


def output_option(what: str) -> Callable[[Wrapped], Wrapped]:
    """``-o/--output FILE`` for a command that writes ``what`` (the SDF, the URDF, ...):
    standard output by default."""
    return click.option(
        "-o",
        "--output",
        default="-",
        show_default=True,
        metavar="FILE",
        help=f"Where to write {what}; - is standard output. Folders are made as needed.",
    )


def base_options(fixed: str, floating: str) -> Callable[[Wrapped], Wrapped]:
    """``--fixed-base`` and ``--floating-base`` (``fixed`` and ``floating`` their help),
    given to the command as ``base`` (``fixed``, ``floating`` or None); both at once are a
    usage error."""

    def decorate(function: Wrapped) -> Wrapped:
        @functools.wraps(function)
        def chosen(*args: Any, fixed_base: bool, floating_base: bool, **kwargs: Any) -> Any:
            if fixed_base and floating_base:
                raise click.UsageError("--fixed-base and --floating-base cannot both be given")
            base = "fixed" if fixed_base else "floating" if floating_base else None
            return function(*args, base=base, **kwargs)

        with_floating = click.option(
            "--floating-base", "floating_base", is_flag=True, help=floating
        )(chosen)
        return click.option("--fixed-base", "fixed_base", is_flag=True, help=fixed)(with_floating)  # type: ignore[return-value]

    return decorate


def joint_option() -> Callable[[Wrapped], Wrapped]:
    """``-j/--joint NAME=VALUE`` (repeatable), stored as ``joint_items``: a joint position,
    written with ``=`` so that it is never taken for a xacro ``name:=value``."""
    return click.option(
        "-j",
        "--joint",
        "joint_items",
        multiple=True,
        metavar="NAME=VALUE",
        help="A joint's position (repeatable): radians for revolute and continuous joints "
        "(or degrees, written 90deg), metres for prismatic ones. Joints not given are at 0; "
        "mimic joints follow.",
    )


def joint_positions(items: Sequence[str]) -> dict[str, float]:
    """``-j NAME=VALUE`` values as a mapping (``90deg`` in radians)."""
    found: dict[str, float] = {}
    for item in items:
        name, sep, text = item.partition("=")
        text = text.strip()
        degrees = text.lower().endswith("deg")
        try:
            value = float(text[:-3] if degrees else text)
        except ValueError:
            value = math.nan
        if not sep or not name.strip() or not math.isfinite(value):
            raise click.BadParameter(
                f"{item!r} is not NAME=VALUE with a number VALUE (1.57, or 90deg)",
                param_hint="--joint",
            )
        if name.strip() in found:
            raise click.BadParameter(f"joint {name.strip()!r} is given twice", param_hint="--joint")
        found[name.strip()] = math.radians(value) if degrees else value
    return found


def limit_options() -> Callable[[Wrapped], Wrapped]:
    """``--max-size MIB`` and ``--timeout SECONDS``: the command runs within those limits;
    ``--trust-expressions``, and ``--allow-read DIR`` (repeatable): what its xacro
    expansions may do (see :mod:`fishbot_urdf.inputs`)."""

    def decorate(function: Wrapped) -> Wrapped:
        @functools.wraps(function)
        def run(
            *args: Any,
            max_size: float | None,
            timeout: float | None,
            trust_expressions: bool,
            allow_read: tuple[str, ...],
            **kwargs: Any,
        ) -> Any:
            limit = max_bytes() if max_size is None else _bytes(max_size)
            seconds = max_seconds() if timeout is None else timeout
            with (
                size_limit(limit),
                time_limit(seconds),
                trusting_expressions(trust_expressions),
                allowing_reads(allow_read),
            ):
                return function(*args, **kwargs)

        size = click.option(
            "--max-size",
            type=Number(positive=True),
            metavar="MIB",
            help="Refuse a file bigger than this, in MiB (default 256).",
        )
        seconds = click.option(
            "--timeout",
            type=Number(positive=True),
            metavar="SECONDS",
            help="Stop the work on a robot that takes longer (default 60).",
        )
        trust = click.option(
            "--trust-expressions",
            is_flag=True,
            help="Run xacro expressions as Python, as ROS's xacro does: the file's code runs "
            "with your rights. Only for files you trust (default: an allowlist).",
        )
        reads = click.option(
            "--allow-read",
            "allow_read",
            multiple=True,
            type=click.Path(exists=True, file_okay=False),
            metavar="DIR",
            help="Let xacro files read in DIR too (repeatable): they read only in the "
            "robot's tree (its git repository, else its package, else its folder) and the "
            "packages $(find) finds.",
        )
        return size(seconds(trust(reads(run))))  # type: ignore[return-value]

    return decorate


def _bytes(mebibytes: float) -> int:
    """``--max-size`` in bytes: at least 1, and at most what a process can hold (a larger
    limit is no limit, and a number beyond it overflows what reads are counted in)."""
    size = mebibytes * 1024 * 1024
    return sys.maxsize if size >= sys.maxsize else max(1, int(size))


class Number(click.ParamType):  # type: ignore[type-arg]
    """A finite number (click's float lets nan and inf through), > 0 with ``positive``,
    >= 0 with ``zero``."""

    name = "float"

    def __init__(self, *, positive: bool = False, zero: bool = False) -> None:
        self.positive = positive
        self.zero = zero

    def convert(
        self, value: Any, param: click.Parameter | None, ctx: click.Context | None
    ) -> float:
        try:
            number = float(value)
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number", param, ctx)
        if not math.isfinite(number):
            self.fail(f"{value!r} is not a finite number", param, ctx)
        if self.positive and not number > 0:
            self.fail(f"{value!r} must be > 0", param, ctx)
        if self.zero and number < 0:
            self.fail(f"{value!r} must be >= 0", param, ctx)
        return number
