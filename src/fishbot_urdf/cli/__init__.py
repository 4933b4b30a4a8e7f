"""The `fishbot` command line: one click group, one short module per subcommand.

Exit status: 0 the robot is valid, 1 the robot has errors, 2 usage, configuration or I/O
problem.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import NoReturn

import click

from ._common import EXIT_OK, stop_quietly
from .check import check
from .expand import expand
from .graph import graph
from .inertia import inertia
from .rules import rules

__all__ = ["cli", "main"]


@click.group(name="fishbot", context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="fishbot-urdf", prog_name="fishbot")
def cli() -> None:
    """fishbot: check and explore URDF robot descriptions, with or without ROS.

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
    """


for _command in (check, rules, expand, graph, inertia):
    cli.add_command(_command)


def main(argv: Sequence[str] | None = None) -> NoReturn:
    """Entry point of the `fishbot` console script and of `python -m fishbot_urdf`."""
    try:
        cli.main(
            args=list(argv) if argv is not None else None, prog_name="fishbot", standalone_mode=True
        )
    except BrokenPipeError:
        stop_quietly()
    sys.exit(EXIT_OK)
