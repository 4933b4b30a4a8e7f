"""`fishbot render`: a shaded picture of the robot, with no display and no GPU."""

from __future__ import annotations

import sys
from collections.abc import Sequence

import click

from ..diagnostics import Severity
from ..drawing.picture import render_png
from ..drawing.scene import LAYERS, build_scene
from ..errors import ArgumentError, FishbotUrdfError, UnknownNameError
from ..kinematics import Kinematics
from ..output import write_atomic
from ..wording import did_you_mean
from ._checking import nearest_config, posable_input, read_files
from ._common import (
    EXIT_INVALID,
    EXIT_OK,
    emit_findings,
    inputs_read,
    joint_option,
    joint_positions,
    limit_options,
    package_option,
    packages_option,
    stop_on,
    to_stdout,
    xacro_args,
)

_VIEWS = ("iso", "front", "side", "top")


def _show(text: str | None) -> tuple[str, ...] | None:
    if text is None:
        return None
    layers = tuple(item.strip() for item in text.split(","))
    for layer in layers:
        if layer not in LAYERS:
            close = did_you_mean(layer, LAYERS)
            raise click.BadParameter(
                f"nothing to show called {layer!r} ({close}{', '.join(LAYERS)})",
                param_hint="--show",
            )
    return layers


def _size(text: str) -> tuple[int, int]:
    width, sep, height = text.lower().partition("x")
    try:
        size = (int(width), int(height))
    except ValueError:
        size = (0, 0)
    if not sep or not (size[0] >= 16 and size[1] >= 16):  # the library bounds the pixels
        raise click.BadParameter(f"{text!r} is not WIDTHxHEIGHT (16 pixels or more each)")
    return size


@click.command()
@click.argument("file", type=click.Path(allow_dash=True))
@click.argument("args", nargs=-1, metavar="[name:=value]...")
@click.option(
    "-o",
    "--output",
    required=True,
    metavar="OUT.png",
    help="Where to write the PNG; - is standard output.",
)
@click.option(
    "--view",
    type=click.Choice(_VIEWS),
    default="iso",
    show_default=True,
    help="iso: from the front left, above; front: from +x; side: from +y; top.",
)
@click.option("--collision", is_flag=True, help="Draw the collision shapes, not the visuals.")
@click.option(
    "--show",
    "show_text",
    metavar="LIST",
    help="What to draw, comma-separated (default: visual): visual, collision, mass (a ball "
    "of lead of each link's mass at its centre of mass), inertia (the box of uniform density "
    "with each link's inertia), frames (each link's axes); as RViz draws them, but for the "
    "ball and box seen through when drawn with the shapes; sensors (each Gazebo lidar's rays "
    "and camera's frustum), gazebo (the visuals in one colour per link of the Gazebo model: "
    "the links sdformat lumps into one share it; a link it leaves out, dark and seen through).",
)
@click.option(
    "--size",
    "size_text",
    default="800x600",
    show_default=True,
    metavar="WxH",
    help="The picture's size in pixels.",
)
@joint_option()
@package_option()
@limit_options()
def render(
    file: str,
    args: Sequence[str],
    output: str,
    view: str,
    collision: bool,
    show_text: str | None,
    size_text: str,
    joint_items: Sequence[str],
    package_items: Sequence[str],
) -> None:
    """A shaded PNG of FILE (URDF or xacro) at a joint configuration: no display, GPU or
    ROS needed. The camera frames the whole robot. Visuals keep their materials' colours;
    meshes are found as `fishbot check` finds them and read from STL and OBJ (other formats
    with `pip install 'fishbot-urdf[mesh]'`); one that cannot be read is drawn as its
    bounding box, and what is not drawn as it is is a warning; findings are printed as
    check prints them. --show picks what is drawn, as RViz's robot model shows it: the
    visuals, the collision shapes (--collision is --show collision), each link's mass as a
    red ball of lead at its centre of mass, its inertia as the red box of uniform density
    with the same mass and principal moments (both seen through when drawn with the
    visuals or collision shapes, which an opaque box would hide), and its frame as red,
    green and blue axes. Gazebo's view of it: each lidar's rays (--show sensors) from its
    minimum to its maximum range with the arc at the maximum, each camera's frustum (1 m
    deep at most), at their poses on their links; what sdformat's converter makes of the
    links (--show gazebo): one colour per link of the Gazebo model.
    A robot with no shape to draw (no visuals, or none that can be drawn) is an error
    [nothing-drawn]: no blank picture is written. Exit status: 0 written (errors
    that leave the shape as it is, such as a fault in an <inertial>, do not stop it), 1 the
    robot has errors that leave its shape or tree in doubt, or nothing to draw (nothing is
    written), 2 a file could not be read or written, a joint or position is wrong, or the
    command line is wrong.

    \b
    Examples:
      fishbot render robots/fishbot/urdf/fishbot/fishbot.urdf.xacro -o fishbot.png
      fishbot render arm.urdf -o arm.png --view side -j shoulder=45deg --size 1200x900
      fishbot render robot.urdf.xacro -o collision.png --collision
      fishbot render robot.urdf.xacro -o inertia.png --show mass,inertia
      fishbot render robot.urdf.xacro -o gazebo.png --show sensors,gazebo --view top
    """
    width, height = _size(size_text)
    show = _show(show_text)
    if file == "-" and args:
        raise click.UsageError("name:=value arguments are for a .xacro file, not standard input")
    values = xacro_args(args)
    positions = joint_positions(joint_items)
    packages = packages_option(package_items)
    read = inputs_read()
    config = nearest_config(file)
    refusal = "nothing written: fix the errors above first"
    result = posable_input(file, values, packages, refusal, config=config)
    assert result.analysis is not None
    try:
        kinematics = Kinematics(result.analysis)
        q = kinematics.configuration(positions)
        # The analysis finds the meshes (with the packages given), as check does.
        scene = build_scene(result.analysis, q, collision=collision, show=show)
    except (UnknownNameError, ArgumentError) as exc:
        raise click.BadParameter(exc.message, param_hint="--joint") from None
    except FishbotUrdfError as exc:
        stop_on(exc)
    findings = config.apply(scene.findings)
    emit_findings(findings)
    if any(finding.severity is Severity.ERROR for finding in findings):  # nothing-drawn
        click.echo(refusal, err=True)
        sys.exit(EXIT_INVALID)
    try:
        png = render_png(scene, view, width, height)
        if output == "-":
            to_stdout(png)
        else:
            # Never over what was read: the robot's files, its meshes, the configuration.
            inputs = [*read_files(file, result), *read]
            write_atomic(output, png, inputs=inputs)
    except FishbotUrdfError as exc:
        if exc.path is None:  # the picture's own bound: about the picture asked for
            exc.path = "<stdout>" if output == "-" else output
        stop_on(exc)
    sys.exit(EXIT_OK)
