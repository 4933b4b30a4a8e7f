"""`fishbot view`: the robot in a web browser, with a slider per joint (RViz and
joint_state_publisher_gui without ROS)."""

from __future__ import annotations

import sys
import time
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import click

from ..config import Config
from ..diagnostics import Diagnostic, escape_controls
from ..drawing.viewer import Viewer
from ..errors import (
    ArgumentError,
    FishbotUrdfError,
    RobotError,
    ToolNotFoundError,
    UnknownNameError,
)
from ..kinematics.positions import check_variables
from ..workspace import Workspace
from ._checking import (
    check_input,
    nearest_config,
    posing,
    posing_errors,
    posing_findings,
)
from ._common import (
    EXIT_INVALID,
    emit_findings,
    fail,
    joint_option,
    joint_positions,
    limit_options,
    not_installed,
    package_option,
    packages_option,
    status_of,
    stop_on,
    to_stdout,
    xacro_args,
)

if TYPE_CHECKING:
    from ..lint import CheckResult


@click.command()
@click.argument("file", type=click.Path())
@click.argument("args", nargs=-1, metavar="[name:=value]...")
@click.option("--host", default="127.0.0.1", show_default=True, help="Where to serve the page.")
@click.option(
    "--port",
    default=8080,
    show_default=True,
    type=click.IntRange(0, 65535),
    help="The port (0: any free one).",
)
@joint_option()
@package_option()
@limit_options()
def view(
    file: str,
    args: Sequence[str],
    host: str,
    port: int,
    joint_items: Sequence[str],
    package_items: Sequence[str],
) -> None:
    """Show FILE (URDF or xacro) in a web browser: visuals in their colours, link frames as
    axes, and a slider per moving joint within its limits, from the root outwards (mimic
    joints follow). Toggles show the visuals, the collision shapes, each link's mass (a red
    ball of lead at its centre of mass) and inertia (the red box of uniform density with the
    same mass and principal moments), and the link frames, as RViz's robot model does; untick
    Visual to see the mass and inertia inside the robot. Two more show what Gazebo will
    simulate: Sensors (each lidar's rays and camera's frustum of the <gazebo> blocks) and
    "Gazebo: lumped links" (the visuals in one colour per Gazebo link, each link sdformat
    lumps into another or leaves out labelled so). What cannot be drawn (a mesh not
    found, an inertia no box has) is printed as render prints it. The robot reloads when FILE or a
    file it includes changes, keeping the sliders. A change that breaks the robot is
    printed as check prints its errors and shown on the page, which keeps the robot read
    last until the file is fixed; a robot broken from the start is served as a page of its
    errors, and shown once fixed. Prints the URL to open; Ctrl-C stops. Only pages served on --host
    and --port may talk to the viewer. --timeout and --max-size bound each (re)load of
    the robot. Needs `pip install 'fishbot-urdf[view]'`.

    \b
    Examples:
      fishbot view robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot view robot.urdf.xacro use_sim:=true --port 8081 -j shoulder=45deg
    """
    values = xacro_args(args)
    packages = packages_option(package_items)
    positions = joint_positions(joint_items)
    config = nearest_config(file)

    loaded: list[CheckResult] = []  # the last load: its findings, and the -j names
    # Each reload asks it again: a robot none of whose files changed is not read again.
    workspace = Workspace(packages, keep=4)

    def load() -> tuple[Any, Sequence[str]]:
        result = check_input(file, values, workspace, posing(config))
        blocking = posing_errors(result.diagnostics)
        if result.analysis is None or blocking:
            raise RobotError(blocking, path=file)
        loaded[:] = [result]
        return result.analysis, result.files

    terminal = _Terminal(file, config)
    try:
        viewer = Viewer(
            load,
            host=host,
            port=port,
            packages=packages,
            watch=(file,),
            wait=lambda exc: status_of(exc) == EXIT_INVALID,  # the robot's fault: fixable
            report=terminal.report,
        )
    except ToolNotFoundError as exc:  # viser: the setup's fault, not the robot's
        emit_findings([not_installed(exc, "fishbot view", "the viewer")])
        sys.exit(status_of(exc))  # 2, as render and graph without Graphviz's dot
    except FishbotUrdfError as exc:  # cannot serve there, a limit reached
        stop_on(exc)
    terminal.viewer = viewer
    if viewer.error is None:
        try:
            first = loaded[0]
            assert first.analysis is not None
            check_variables(first.analysis, positions, viewer.values)
            for name, value in positions.items():
                viewer.set(name, value)
        except (UnknownNameError, ArgumentError) as exc:
            viewer.close()
            raise click.BadParameter(exc.message, param_hint="--joint") from None
        emit_findings(posing_findings(first, values))
        terminal.drawn()
    else:  # set, within their joints' ranges, once the robot is read
        viewer.values.update(positions)
    try:
        _say(f"fishbot view: {viewer.url} (Ctrl-C stops)")
        while True:
            time.sleep(3600)
    finally:
        viewer.close()


class _Terminal:
    """What the terminal is told as the robot is read again: a load's errors, as check
    prints them; that the robot is shown again after them; and the drawing's findings
    when they change."""

    def __init__(self, file: str, config: Config) -> None:
        self.file = file
        self.config = config
        self.viewer: Viewer | None = None  # (None while the first load is under way)
        self.failed = False
        self.said: list[Diagnostic] | None = None

    def report(self, error: FishbotUrdfError | None) -> None:
        """The viewer's `report` (on its watching thread)."""
        if error is not None:
            found = list(error.diagnostics) if isinstance(error, RobotError) else []
            emit_findings(found or [fail(error)])
            self.failed = True
            return
        if self.failed:
            self.failed = False
            _say(f"fishbot view: {self.file} is read again: the page shows it")
        self.drawn()

    def drawn(self) -> None:
        """Print the drawing's findings, unless they are those printed last."""
        viewer = self.viewer
        if viewer is None:
            return
        found = self.config.apply(viewer.findings)
        if found != self.said:
            emit_findings(found)
            self.said = found


def _say(line: str) -> None:
    """A line on stdout, as every command writes there (a closed stdout is an error)."""
    to_stdout(f"{escape_controls(line)}\n".encode("utf-8", "surrogateescape"))
