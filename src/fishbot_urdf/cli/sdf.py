"""`fishbot sdf`: the SDF sdformat's URDF converter makes of a robot, as `ign sdf -p` prints it."""

from __future__ import annotations

import sys
from collections.abc import Sequence

import click

from ..catalog import conversion, rules_in
from ..catalog.references import UNKNOWN_REFERENCE
from ..errors import ConversionError, FishbotUrdfError
from ..export.sdf import to_sdf
from ..lint import check_again
from ..output import write_atomic
from ._checking import nearest_config, posable_input, read_files
from ._common import (
    EXIT_OK,
    emit_findings,
    inputs_read,
    limit_options,
    output_option,
    package_option,
    packages_option,
    stop_on,
    to_stdout,
    xacro_args,
)


@click.command()
@click.argument("file", type=click.Path(allow_dash=True))
@click.argument("args", nargs=-1, metavar="[name:=value]...")
@output_option("the SDF")
@package_option()
@limit_options()
def sdf(file: str, args: Sequence[str], output: str, package_items: Sequence[str]) -> None:
    """The SDF of FILE (URDF or xacro) as Gazebo's converter makes it: what `ign sdf -p` prints.

    Written as sdformat 12 (Gazebo Fortress) converts URDF: each link on a fixed joint is
    lumped into its parent (masses, centres of mass and inertias summed, its visuals and
    collisions renamed PARENT_fixed_joint_lump__NAME_visual), a link without mass is left
    out with everything below it, floating and planar joints are left out (their links
    stay), and package:// mesh names become model://. <gazebo> blocks become what the
    converter makes of them (settings as SDF elements, sensors and plugins copied, those
    of a lumped link moved to the link it went into, poses and plugin frames with them;
    preserveFixedJoint and disableFixedJointLumping keep a fixed joint). ARGS are
    name:=value values for a xacro file's <xacro:arg>. Findings about the robot are printed
    as check prints them, and so is what the conversion loses (the gazebo-dropped-link,
    gazebo-lumped-link, gazebo-lumping-flag, gazebo-mimic, gazebo-model-path and
    gazebo-plugin-link rules, and unknown-reference for a <gazebo reference> block it
    drops, judged for Gazebo); the SDF is written all the same. Exit status: 0 written, 1
    the robot has errors that leave its tree in doubt or cannot be converted (nothing is
    written), 2 a file could not be read or written, or the command line is wrong.

    \b
    Examples:
      fishbot sdf robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot sdf robot.urdf -o robot.sdf
      fishbot sdf robot.urdf.xacro use_gpu:=false -o build/robot.sdf
      fishbot sdf robot.urdf.xacro --package my_description=src/my_description
    """
    if file == "-" and args:
        raise click.UsageError("name:=value arguments are for a .xacro file, not standard input")
    values = xacro_args(args)
    read = inputs_read()
    config = nearest_config(file)
    result = posable_input(file, values, packages_option(package_items), config=config)
    assert result.analysis is not None
    try:
        text = to_sdf(result.analysis)
        if output == "-":
            to_stdout(text.encode("utf-8", "surrogateescape"))
        else:
            # never over what was read: the robot, its includes, its meshes, the configuration
            write_atomic(output, text, inputs=[*read_files(file, result), *read])
    except FishbotUrdfError as exc:
        if isinstance(exc, ConversionError) and exc.path is None:  # about the robot read
            exc.path = result.analysis.path
        stop_on(exc)
    # what the SDF lacks that the robot says, judged for Gazebo, which reads the SDF (of the
    # rules the configuration applies)
    losses = [rule for rule in _LOSSES if config.applies(rule)]
    if losses:
        targets = (*result.targets, "gazebo")
        emit_findings(check_again(result, config.updated(select=losses, targets=targets)))
    sys.exit(EXIT_OK)


# the conversion's rules, and a <gazebo reference> to nothing, a block the converter drops
_LOSSES = (*(rule.id for rule in rules_in(conversion)), UNKNOWN_REFERENCE.id)
