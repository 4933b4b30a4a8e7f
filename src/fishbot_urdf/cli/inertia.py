"""`fishbot inertia`: the <inertial> of a box, cylinder or sphere, a robot's mass table, and
inertials filled in from collision shapes."""

from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import click

from ..catalog.physics import MISSING_INERTIAL, MJCF_JOINED_INERTIAL, MJCF_REFUSED
from ..errors import ArgumentError, FishbotUrdfError, InertiaUnderflowError, UnknownNameError
from ..inertia import (
    box_inertia,
    cylinder_inertia,
    inertial_dict,
    mass_table,
    sphere_inertia,
)
from ..model import Origin
from ..wording import closest
from ..write import inertial_xml, rounded
from ._checking import check_input, nearest_config, read_files
from ._common import (
    EXIT_INVALID,
    EXIT_OK,
    Number,
    Wrapped,
    emit_findings,
    format_option,
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
from ._filling import link_masses, suggest, write_copy

if TYPE_CHECKING:
    from ..model import Inertial, Vector3

_SHAPES = ("box", "cylinder", "sphere")


class _ShapeOrRobot(click.Group):
    """`fishbot inertia box ...` runs a shape; `fishbot inertia FILE ...` the robot table."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        first = args[0] if args else None
        if first is None or first in self.commands or first in ("-h", "--help"):
            return super().parse_args(ctx, args)
        if not any(a in _SHAPES for a in args) or first == "-" or not first.startswith("-"):
            if not first.startswith("-") and _looks_like_a_shape(first):
                guess = closest(first, _SHAPES)
                hint = f"did you mean {guess!r}? " if guess else ""
                raise click.UsageError(
                    f"no shape or file {first!r} ({hint}shapes: {', '.join(_SHAPES)})", ctx
                )
            args = ["robot", *args]  # options may come before the file, as for check
        return super().parse_args(ctx, args)


def _looks_like_a_shape(word: str) -> bool:
    """A bare word that names no file: a mistyped shape (`cube`, `cylnder`)."""
    return word.isalpha() and not os.path.exists(word)


@click.group(cls=_ShapeOrRobot, no_args_is_help=True)
def inertia() -> None:
    """Inertia: an <inertial> block for a solid shape, or a robot's mass table.

    `fishbot inertia box|cylinder|sphere` prints the <inertial> of a uniform solid, the
    same numbers as the fishbot's common_inertia.xacro. `fishbot inertia ROBOT` prints each
    link's mass, centre of mass and principal moments with the checks that concern it, and
    the whole robot's mass, centre of mass and inertia at the zero configuration. With
    --fill, for every link that has collision shapes but no <inertial>, it says what to
    write and at which line of which file (a call of a xacro robot's own inertia macro, or
    the <inertial>); with --fill -o OUT it writes a copy in which each gets one. Exit
    status: 0 done, 1 the robot has errors, 2 a file could not be read or written, or the
    command line is wrong.

    \b
    Examples:
      fishbot inertia box --mass 0.01 --size 0.02 0.1 0.02
      fishbot inertia cylinder --mass 0.1 --radius 0.032 --length 0.04 --rpy 1.57079 0 0
      fishbot inertia sphere --mass 0.02 --radius 0.016 --format json
      fishbot inertia robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot inertia robot.urdf --format json
      fishbot inertia arm.urdf -j shoulder=90deg -j elbow=-0.5
      fishbot inertia robot.urdf.xacro --fill --mass base_link=1
      fishbot inertia robot.urdf --fill --density 1000 -o robot_filled.urdf
      fishbot inertia robot.urdf --fill --mass base_link=1 --mass wheel=0.1 -o out.urdf

    \b
    Options for ROBOT (a URDF or xacro file, - for standard input):
      name:=value          xacro arguments
      --format text|json   a table, or JSON
      --fill               what to write in each link without an <inertial>, and where
      --fill -o OUT        write a copy with the missing inertials (- is stdout)
      --density KG_PER_M3  the density of every filled link
      --mass LINK=KG       the mass of one filled link (repeatable)
      --package NAME=PATH  where a ROS package is, for $(find NAME)
    """


def _triple(name: str, metavar: str, text: str) -> Callable[[Wrapped], Wrapped]:
    return click.option(
        name, nargs=3, type=Number(), default=(0.0, 0.0, 0.0), metavar=metavar, help=text
    )


def _shape_options(func: Any) -> Any:
    options = [
        click.option(
            "--mass",
            required=True,
            type=_MASS,
            help="Mass in kg.",
        ),
        _triple("--xyz", "X Y Z", "Centre of the solid in the link (m): its <origin> xyz."),
        _triple("--rpy", "R P Y", "Rotation of the solid in the link (rad): its <origin> rpy."),
        click.option(
            "--format",
            "fmt",
            type=click.Choice(["xml", "json"]),
            default="xml",
            show_default=True,
            help="xml: the <inertial> element to paste; json: the numbers.",
        ),
    ]
    for option in reversed(options):
        func = option(func)
    return func


_SIZE = Number(positive=True)
_MASS = Number(positive=True)


@inertia.command()
@click.option("--size", nargs=3, type=_SIZE, required=True, metavar="X Y Z", help="Sides (m).")
@_shape_options
def box(size: Vector3, mass: float, xyz: Vector3, rpy: Vector3, fmt: str) -> None:
    """The <inertial> of a solid box with sides X Y Z (m), as <box size="X Y Z"/>.

    \b
    Example:
      fishbot inertia box --mass 0.01 --size 0.02 0.1 0.02
    """
    origin = _origin(xyz, rpy)
    _print(lambda: box_inertia(mass, *size, origin), fmt)


@inertia.command()
@click.option("--radius", type=_SIZE, required=True, help="Radius (m).")
@click.option("--length", type=_SIZE, required=True, help="Length along z (m).")
@_shape_options
def cylinder(
    radius: float, length: float, mass: float, xyz: Vector3, rpy: Vector3, fmt: str
) -> None:
    """The <inertial> of a solid cylinder along its z axis, as <cylinder radius length/>.

    A wheel's cylinder is usually turned by its origin (rpy 1.57079 0 0 lays it along y):
    give the same --rpy, so that the inertia turns with it.

    \b
    Example:
      fishbot inertia cylinder --mass 0.1 --radius 0.032 --length 0.04 --rpy 1.57079 0 0
    """
    origin = _origin(xyz, rpy)
    _print(lambda: cylinder_inertia(mass, radius, length, origin), fmt)


@inertia.command()
@click.option("--radius", type=_SIZE, required=True, help="Radius (m).")
@_shape_options
def sphere(radius: float, mass: float, xyz: Vector3, rpy: Vector3, fmt: str) -> None:
    """The <inertial> of a solid sphere, as <sphere radius="R"/>.

    \b
    Example:
      fishbot inertia sphere --mass 0.02 --radius 0.016
    """
    origin = _origin(xyz, rpy)
    _print(lambda: sphere_inertia(mass, radius, origin), fmt)


def _origin(xyz: Vector3, rpy: Vector3) -> Any:
    if any(abs(angle) > 2 * math.pi for angle in rpy):
        turned = " ".join(f"{math.radians(a):.6g}" for a in rpy)
        click.echo(
            f"warning: --rpy is in radians; if {' '.join(f'{a:g}' for a in rpy)} are degrees, "
            f"write --rpy {turned}",
            err=True,
        )

    return Origin(xyz=tuple(xyz), rpy=tuple(rpy))  # type: ignore[arg-type]


def _print(make: Callable[[], Inertial], fmt: str) -> None:
    """Print the inertial ``make`` gives; one too large or too small for floats is a bad
    value on the command line (exit 2), as a size of 0 is."""
    try:
        inertial = make()
    except InertiaUnderflowError as exc:
        raise click.UsageError(exc.message) from None
    tensor = inertial.inertia
    if not all(math.isfinite(getattr(tensor, f)) for f in ("ixx", "iyy", "izz")):
        raise click.UsageError("the moments overflow: give the sizes in metres")

    if fmt == "json":
        text = json.dumps(inertial_dict(rounded(inertial)), indent=2) + "\n"
    else:
        text = inertial_xml(inertial)
    to_stdout(text.encode("utf-8", "surrogateescape"))


class _RobotContext(click.Context):
    """The robot form's context: its path is `fishbot inertia`, as the user typed it (a
    file follows, not `robot`), so that a usage error's hint is a command that works."""

    @property
    def command_path(self) -> str:
        return self.parent.command_path if self.parent else "fishbot inertia"


class _RobotCommand(click.Command):
    """The robot form, shown as `fishbot inertia ROBOT ...` (its name is only internal)."""

    context_class = _RobotContext

    def format_usage(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        formatter.write_usage(ctx.command_path, "ROBOT [name:=value]... [OPTIONS]")


@inertia.command(cls=_RobotCommand, hidden=True)
@click.argument("file", type=click.Path(allow_dash=True))
@click.argument("args", nargs=-1, metavar="[name:=value]...")
@format_option(("text", "json"), "text: a table; json: the same numbers for programs.")
@click.option(
    "--fill",
    is_flag=True,
    help="Say what to write in each link without an <inertial>, and where (a call of the "
    "robot's own inertia macro, or the <inertial>); with -o, write a copy with them.",
)
@click.option(
    "-o", "--output", metavar="OUT", help="With --fill: write the filled copy there (- is stdout)."
)
@click.option(
    "--density",
    type=_MASS,
    help="With --fill: the density of every filled link (kg/m^3; water 1000, PLA 1240).",
)
@click.option(
    "--mass",
    "masses",
    multiple=True,
    metavar="LINK=KG",
    help="With --fill: the mass of one link (repeatable); it wins over --density.",
)
@joint_option()
@package_option()
@limit_options()
def robot(
    file: str,
    args: Sequence[str],
    fmt: str,
    fill: bool,
    output: str | None,
    density: float | None,
    masses: Sequence[str],
    joint_items: Sequence[str],
    package_items: Sequence[str],
) -> None:
    """The mass table of ROBOT, a URDF or xacro file (- reads a URDF from standard input).

    One line per link: mass, centre of mass (in the link's own frame), principal moments,
    and the `fishbot check` rules that concern it; then the robot's total mass, centre of
    mass (in the root link's frame) and principal moments, with every joint at zero or
    where -j puts it.

    With --fill (and --density or --mass), for each link with collision shapes and no
    <inertial>: FILE:LINE:COL of its <link> (in a macro's body, with the call that made
    it), the line to write at, and what to write there: for a xacro robot that includes
    box/cylinder/sphere inertia macros (found by calling them, whatever their names), the
    call of its own macro with the mass and the collision's sizes; else the <inertial>.
    --format json gives the same. With --fill -o OUT, a copy in which each such link gets
    its <inertial>. Exit status: 0 done, 1 the robot has errors or --fill left a link out,
    2 a file could not be read or written, or the command line is wrong.

    \b
    Examples:
      fishbot inertia robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot inertia robot.urdf --format json
      fishbot inertia arm.urdf -j shoulder=90deg -j elbow=-0.5
      fishbot inertia robot.urdf.xacro --fill --mass base_link=1
        (prints, e.g.:
         base.urdf.xacro:24:5: note: link 'base_link' has no <inertial>; for 1 kg, write
         at line 25, inside the <link>, in the body of macro base_xacro (called at ...):
           <xacro:cylinder_inertia m="1" r="0.1" h="0.12"/>)
      fishbot inertia robot.urdf --fill --density 1000 -o robot_filled.urdf
    """
    if any(":=" not in a for a in args):
        raise click.UsageError(f"unexpected argument {next(a for a in args if ':=' not in a)!r}")
    if not fill and (output is not None or density is not None or masses):
        raise click.UsageError("-o, --density and --mass go with --fill")
    if fill and density is None and not masses:
        raise click.UsageError("--fill needs --density KG_PER_M3 or --mass LINK=KG")
    if fill and joint_items:
        raise click.UsageError("--fill writes each link's own inertial: it takes no --joint")
    if fill and output is not None and fmt == "json":
        raise click.UsageError("--fill -o writes a URDF: it takes no --format")
    if file == "-" and args:
        raise click.UsageError("name:=value arguments are for a .xacro file, not standard input")
    values = xacro_args(args)
    packages = packages_option(package_items)
    positions = joint_positions(joint_items)
    read = inputs_read()
    config = nearest_config(file)
    if config.targets is None:  # masses and inertias are the simulators': checked for them
        # (but what MuJoCo refuses of the model `fishbot mjcf` writes, its free base among
        # it, is for `--target mujoco` to ask)
        config = config.updated(targets=["all"], ignore=_CONVERSION)
    try:
        result = check_input(file, values, packages, config)
    except FishbotUrdfError as exc:
        stop_on(exc)
    if fill:
        # The robot's own faults come first; a missing inertial is what --fill writes (and
        # what MuJoCo refuses of a link without one: a fault of the robot's own is reported
        # by the other rules too).
        errors = [d for d in result.diagnostics if d.is_error and d.rule not in _FILLED]
        if result.analysis is None or errors:
            emit_findings(errors or result.diagnostics)
            said = "nothing written" if output is not None else "nothing to suggest"
            click.echo(f"{said}: fix the errors above first", err=True)
            sys.exit(EXIT_INVALID)
        wanted = link_masses(masses)
        if output is None:  # what to write in the robot's own files, and where
            sys.exit(suggest(file, result, fmt, density, wanted, values, packages, config))
        # The copy is never written over anything read (the mesh files listed here are
        # those the filling opens, by the same analysis: no package.xml is read after).
        inputs = [*read_files(file, result), *read]
        sys.exit(write_copy(result, output, density, wanted, inputs))
    emit_findings(result.diagnostics)
    if result.analysis is None:
        sys.exit(EXIT_INVALID)

    try:
        table = mass_table(result.analysis, result.diagnostics, positions)
    except (ArgumentError, UnknownNameError) as exc:
        raise click.BadParameter(exc.message, param_hint="--joint") from None
    if fmt == "json":
        report = {
            "ok": result.ok,
            **table.to_dict(),
            "diagnostics": [d.to_dict() for d in result.diagnostics],
        }
        to_stdout((json.dumps(report, indent=2) + "\n").encode("utf-8", "surrogateescape"))
    else:
        to_stdout(table.to_text().encode("utf-8", "surrogateescape"))
    sys.exit(EXIT_INVALID if not result.ok else EXIT_OK)


_FILLED = (MISSING_INERTIAL.id, MJCF_REFUSED.id)
_CONVERSION = (MJCF_REFUSED.id, MJCF_JOINED_INERTIAL.id)
