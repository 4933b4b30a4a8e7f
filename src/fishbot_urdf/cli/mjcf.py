"""`fishbot mjcf`: the MJCF of a robot, the model file MuJoCo loads."""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import Literal

import click

from ..catalog.physics import (
    INERTIA_NOT_POSITIVE,
    INERTIA_TRIANGLE,
    MASSLESS_LINK,
    MISSING_INERTIAL,
    MJCF_REFUSED,
)
from ..catalog.reading import NEGATIVE_MASS
from ..errors import FishbotUrdfError
from ..export.mjcf import export_mjcf, write_mjcf
from ..lint import check_again
from ._checking import nearest_config, posable_input, read_files
from ._common import (
    EXIT_INVALID,
    EXIT_OK,
    base_options,
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
@output_option("the MJCF")
@base_options(
    "Fix the root link to the world (the default for a robot whose root is `world`).",
    "Let the root link move freely (the default for any other robot).",
)
@package_option()
@limit_options()
def mjcf(
    file: str,
    args: Sequence[str],
    output: str,
    base: str | None,
    package_items: Sequence[str],
) -> None:
    """The MJCF of FILE (URDF or xacro): the model file MuJoCo loads, with no mass made up.

    One body per link, placed by its joint's origin, so that each link's pose is its body's;
    every <inertial> as written (MuJoCo computes none from the shapes; one MuJoCo refuses
    on a link fixed to its parent joins the parent's body, mjcf-joined-inertial); revolute and
    continuous joints as hinges, prismatic as slides, with their limits, damping and
    friction; planar and floating joints as slides and hinges; mimic joints held to their
    leader by equality constraints. Visuals are geoms of group 2 that collide with nothing, in
    their material's colour, collisions geoms of group 3. Meshes MuJoCo reads (binary STL,
    OBJ) are named by their absolute paths; with -o FILE, any other (COLLADA, PLY, glTF,
    ASCII STL) is converted to a binary STL in a folder beside it named after it
    (robot.xml: robot_meshes/, mjcf-mesh-converted); one not converted (to standard output,
    or when it cannot be) or whose file is not found is left out (mjcf-left-out).
    A robot whose root link is `world` hangs from the world by its joints, any other floats
    (a free joint), unless --fixed-base or --floating-base says otherwise. ARGS are
    name:=value values for a xacro file's <xacro:arg>. Findings about the robot are printed
    as check prints them, and so are the inertials MuJoCo refuses (massless-link,
    missing-inertial, negative-mass, inertia-not-positive, inertia-triangle, judged for
    MuJoCo); the MJCF is written all the same. Exit status: 0 written, 1 written but MuJoCo
    will refuse it (mjcf-refused: a moving body without mass, an inertia no solid has), or
    the robot has errors that leave its tree in doubt (nothing is written), 2 a file could
    not be read or written, or the command line is wrong.

    \b
    Examples:
      fishbot mjcf robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot mjcf robot.urdf -o robot.xml
      fishbot mjcf robot.urdf.xacro --fixed-base -o build/robot.xml
      fishbot mjcf robot.urdf.xacro --package my_description=src/my_description
    """
    if file == "-" and args:
        raise click.UsageError("name:=value arguments are for a .xacro file, not standard input")
    values = xacro_args(args)
    read = inputs_read()
    config = nearest_config(file)
    result = posable_input(file, values, packages_option(package_items), config=config)
    assert result.analysis is not None
    try:
        held = "fixed" if base == "fixed" else _AUTO[base]
        if output == "-":
            made = export_mjcf(result.analysis, base=held)
            to_stdout(made.text.encode("utf-8", "surrogateescape"))
        else:
            # never over what was read: the robot, its includes, its meshes, the configuration
            inputs = [*read_files(file, result), *read]
            made = write_mjcf(result.analysis, output, base=held, inputs=inputs)
    except FishbotUrdfError as exc:
        stop_on(exc)
    # what MuJoCo refuses of the inertials as written (of the rules the configuration applies)
    refusals = [rule for rule in _REFUSALS if config.applies(rule)]
    if refusals:
        targets = (*result.targets, "mujoco")
        emit_findings(check_again(result, config.updated(select=refusals, targets=targets)))
    changes = [d for d in made.findings if config.applies(d.rule)]
    emit_findings(changes)
    sys.exit(EXIT_INVALID if any(d.rule == MJCF_REFUSED.id for d in changes) else EXIT_OK)


_AUTO: dict[str | None, Literal["auto", "floating"]] = {None: "auto", "floating": "floating"}
_REFUSALS = tuple(
    rule.id
    for rule in (
        MASSLESS_LINK,
        MISSING_INERTIAL,
        NEGATIVE_MASS,
        INERTIA_NOT_POSITIVE,
        INERTIA_TRIANGLE,
    )
)
