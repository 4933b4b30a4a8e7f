"""The `fishbot` command line: one click group, one short module per subcommand, imported
only when that subcommand runs.

Exit status: 0 the robot is valid, 1 the robot has errors, 2 usage, configuration or I/O
problem, 130 interrupted (Ctrl-C), 143 terminated (SIGTERM).
"""

from __future__ import annotations

import contextlib
import errno
import importlib
import os
import signal
import sys
import threading
from collections.abc import Sequence
from typing import IO, NoReturn

import click

from ..escaping import escape_controls

__all__ = ["cli", "main"]

# Each subcommand (defined by the function of its name in the module of its name) and the
# first sentence of its help, which `fishbot --help` shortens as click would, without
# importing the module (tests/test_cli.py keeps the two in step).
COMMANDS = {
    "check": "Check URDF or xacro files, like check_urdf, and more strictly.",
    "rules": "List the rules of `fishbot check`, or explain one (as `ruff rule` does).",
    "expand": "Expand a xacro file to URDF, as ROS's xacro command does, without ROS.",
    "graph": "Draw the link/joint tree of a URDF or xacro file, like urdf_to_graphviz.",
    "inertia": "Inertia: an <inertial> block for a solid shape, or a robot's mass table.",
    "tf": "Where frame TO is in frame FROM (both links of FILE, a URDF or xacro file), as "
    "`ros2 run tf2_ros tf2_echo FROM TO` prints it with robot_state_publisher running.",
    "render": "A shaded PNG of FILE (URDF or xacro) at a joint configuration: no display, GPU "
    "or ROS needed.",
    "lsp": "The language server for URDF and xacro files, over standard input and output: the "
    "findings of `fishbot check` as you type, in the file each is in (and at the macro call "
    "that made it), quick fixes, and each rule explained on hover; go to definition, "
    "references, rename, completion and the outline of the robot's names across its files.",
    "mjcf": "The MJCF of FILE (URDF or xacro): the model file MuJoCo loads, with no mass made up.",
    "sdf": "The SDF of FILE (URDF or xacro) as Gazebo's converter makes it: what `ign sdf -p` "
    "prints.",
    "sim": "Drop FILE (URDF or xacro) on a floor in MuJoCo and drive it, or hold it, and say "
    "what went wrong, as a learner would check it in Gazebo: no ROS, no Gazebo, no display.",
    "view": "Show FILE (URDF or xacro) in a web browser: visuals in their colours, link frames as "
    "axes, and a slider per moving joint within its limits, from the root outwards (mimic "
    "joints follow).",
}


def summary(name: str) -> click.Command:
    """A stand-in for subcommand ``name`` that knows only its help's first sentence."""
    return click.Command(name, help=COMMANDS[name])


class _Commands(click.Group):
    """A group whose subcommands load on first use: `fishbot check` imports no drawing code
    and `fishbot --help` no subcommand at all."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in COMMANDS:
            return None
        module = importlib.import_module(f"{__name__}.{cmd_name}")
        command: click.Command = getattr(module, cmd_name)
        return command

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        names = self.list_commands(ctx)
        limit = formatter.width - 6 - max(len(name) for name in names)
        rows = [(name, summary(name).get_short_help_str(limit)) for name in names]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


@click.group(
    name="fishbot",
    cls=_Commands,
    context_settings={"help_option_names": ["-h", "--help"]},
)
@click.version_option(package_name="fishbot-urdf", prog_name="fishbot")
def cli() -> None:
    """fishbot: check and explore URDF robot descriptions, with or without ROS.

    Exit status: 0 ok, 1 the robot has errors, 2 usage, configuration or I/O problem,
    130 interrupted (Ctrl-C), 143 terminated.

    \b
    Examples:
      fishbot check robots/fishbot/urdf/first_robot.urdf
      fishbot check --format json robot.urdf
      fishbot check --format sarif -o fishbot.sarif robot.urdf.xacro
      fishbot rules massless-link
      fishbot expand robot.urdf.xacro -o robot.urdf
      fishbot graph robot.urdf.xacro -o tree.pdf
      fishbot inertia cylinder --mass 1 --radius 0.1 --length 0.12
      fishbot inertia robot.urdf.xacro
      fishbot tf robot.urdf.xacro base_link laser_link -j left_wheel_joint=90deg
      fishbot render robot.urdf.xacro -o robot.png --view side
      fishbot view robot.urdf.xacro
      fishbot sdf robot.urdf.xacro -o robot.sdf
      fishbot mjcf robot.urdf.xacro -o robot.xml
      fishbot sim robot.urdf.xacro --drive 0.2,0.5
      fishbot lsp
    """


EXIT_INTERRUPTED, EXIT_TERMINATED = 130, 143  # as a shell reports SIGINT and SIGTERM


class _Terminated(BaseException):
    """SIGTERM, raised where the program is, so that what it was writing is cleaned up."""


def _terminate(signum: int, frame: object) -> NoReturn:
    raise _Terminated


def main(argv: Sequence[str] | None = None) -> NoReturn:
    """Entry point of the `fishbot` console script and of `python -m fishbot_urdf`.

    Exit status: 0 ok, 1 the robot has errors, 2 usage, configuration or I/O problem, 130
    interrupted (Ctrl-C), 143 terminated (SIGTERM). With no ``argv`` (the command line is the
    process's own), the process ends once its output is flushed, without taking apart the
    objects the command built; given ``argv``, it raises SystemExit as usual.
    """
    try:
        _run(argv)
    except SystemExit as done:
        if argv is None:
            # Python's own end takes apart every module and object one by one: for
            # `fishbot check first_robot.urdf` that was 1.40x the time of the same command
            # ending here (1.15x against 1.40x the previous release's, median of 15 pairs),
            # and 1.36x against 1.16x for the 10,000-link tree. Output is flushed first.
            _end_process(done.code)
        raise


def _run(argv: Sequence[str] | None) -> NoReturn:
    if sys.stdout is None:  # closed by the caller (`>&-`)
        sys.stdout = _closed_stdout()
    if sys.stderr is None:  # closed too: what would be said there goes nowhere
        sys.stderr = open(os.devnull, "w", encoding="utf-8")  # noqa: SIM115
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, _terminate)
    try:
        cli.main(
            args=list(argv) if argv is not None else None,
            prog_name="fishbot",
            standalone_mode=False,
        )
    except click.exceptions.Abort:  # Ctrl-C; click has ended the ^C line
        _quiet_exit(EXIT_INTERRUPTED)
    except _Terminated:
        _quiet_exit(EXIT_TERMINATED)
    except click.ClickException as exc:
        # One line, whatever a name in it holds (click declares the message final).
        exc.message = escape_controls(exc.message)  # type: ignore[misc]
        exc.show()
        sys.exit(exc.exit_code)
    except BrokenPipeError:
        _quiet_exit(0)
    except OSError as exc:
        if exc.errno not in _UNWRITABLE:
            raise
        # click's own output (help, version) that cannot be written: one line, as any
        from ._common import EXIT_USAGE, report_unwritten  # (see _quiet_exit)

        report_unwritten(exc)
        _quiet_exit(EXIT_USAGE)
    sys.exit(0)


# Why a write to standard output fails: closed (`>&-`), a full disk, a device's error.
_UNWRITABLE = (errno.EBADF, errno.ENOSPC, errno.EIO)


def _closed_stdout() -> IO[str]:
    """A standard output for one the caller closed, on which every write fails as on the
    closed one (EBADF: the command says so and exits 2, if it has anything to write). Its
    descriptor, 1, is held on os.devnull opened for reading, so that no file the command
    opens takes that number and gets what is written to standard output."""
    held = os.open(os.devnull, os.O_RDONLY)
    if held != 1:  # (0 when standard input is closed too)
        os.dup2(held, 1)
        os.close(held)
    return open(1, "w", encoding="utf-8", closefd=False)


def _end_process(code: object) -> NoReturn:
    """End the process as Python would on SystemExit(code), without its clean-up, once the
    output is flushed: output that cannot be written (a full disk) is one line and status 2,
    and a reader that has gone is no error."""
    if code is None:
        status = 0
    elif isinstance(code, int):
        status = code
    else:
        print(code, file=sys.stderr)
        status = 1
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _unwritten()  # the reader has gone: nothing more to say
    except OSError as exc:  # a full disk
        from ._common import EXIT_USAGE, report_unwritten  # (see _quiet_exit)

        report_unwritten(exc)
        status = max(status, EXIT_USAGE)
        _unwritten()
    except ValueError:
        pass  # closed by the command itself
    with contextlib.suppress(OSError, ValueError):
        sys.stderr.flush()
    os._exit(status)


def _unwritten() -> None:
    """What standard output still holds goes nowhere (not to fail again at the end)."""
    with contextlib.suppress(OSError, ValueError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())


def _quiet_exit(status: int) -> NoReturn:
    # what the commands share loads with the first that runs: `fishbot --help` needs none
    from ._common import stop_quietly

    stop_quietly(status)
