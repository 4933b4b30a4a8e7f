"""The `fishbot` command line: one click group, one short module per subcommand.

Exit status: 0 the robot is valid, 1 the robot has errors, 2 usage, configuration or I/O
problem, 130 interrupted (Ctrl-C), 143 terminated (SIGTERM).
"""

from __future__ import annotations

import os
import sys
import threading
from collections.abc import Sequence
from typing import NoReturn

import click

from ._common import EXIT_OK, stop_quietly
from .check import check
from .expand import expand
from .graph import graph
from .inertia import inertia
from .render import render
from .rules import rules
from .tf import tf
from .view import view

__all__ = ["cli", "main"]


@click.group(name="fishbot", context_settings={"help_option_names": ["-h", "--help"]})
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
    """


for _command in (check, rules, expand, graph, inertia, tf, render, view):
    cli.add_command(_command)


EXIT_INTERRUPTED, EXIT_TERMINATED = 130, 143  # as a shell reports SIGINT and SIGTERM


class _Terminated(BaseException):
    """SIGTERM, raised where the program is, so that what it was writing is cleaned up."""


def _terminate(signum: int, frame: object) -> NoReturn:
    raise _Terminated


def main(argv: Sequence[str] | None = None) -> NoReturn:
    """Entry point of the `fishbot` console script and of `python -m fishbot_urdf`.

    Exit status: 0 ok, 1 the robot has errors, 2 usage, configuration or I/O problem, 130
    interrupted (Ctrl-C), 143 terminated (SIGTERM).
    """
    import signal

    for name in ("stdout", "stderr"):  # closed by the caller (`>&-`): output goes nowhere
        if getattr(sys, name) is None:
            setattr(sys, name, open(os.devnull, "w", encoding="utf-8"))  # noqa: SIM115
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, _terminate)
    try:
        cli.main(
            args=list(argv) if argv is not None else None,
            prog_name="fishbot",
            standalone_mode=False,
        )
    except click.exceptions.Abort:  # Ctrl-C; click has ended the ^C line
        stop_quietly(EXIT_INTERRUPTED)
    except _Terminated:
        stop_quietly(EXIT_TERMINATED)
    except click.ClickException as exc:
        exc.show()
        sys.exit(exc.exit_code)
    except BrokenPipeError:
        stop_quietly()
    sys.exit(EXIT_OK)
