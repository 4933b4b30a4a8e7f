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

from ..errors import FishbotUrdfError
from ._fill import fill_copy
from ._mass_table import inertial_dict, mass_table, table_text
from ._options import PACKAGE_HELP as _PACKAGE_HELP
from ._options import Number, Wrapped, text_or_json

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
                from ..diagnostics import closest

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
    the whole robot's mass, centre of mass and inertia at the zero configuration; with
    --fill -o OUT it writes a copy in which every link that has collision shapes but no
    <inertial> gets one. Exit status: 0 done, 1 the robot has errors, 2 a file could not be
    read or written, or the command line is wrong.

    \b
    Examples:
      fishbot inertia box --mass 0.01 --size 0.02 0.1 0.02
      fishbot inertia cylinder --mass 0.1 --radius 0.032 --length 0.04 --rpy 1.57079 0 0
      fishbot inertia sphere --mass 0.02 --radius 0.016 --format json
      fishbot inertia robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot inertia robot.urdf --format json
      fishbot inertia robot.urdf --fill --density 1000 -o robot_filled.urdf
      fishbot inertia robot.urdf --fill --mass base_link=1 --mass wheel=0.1 -o out.urdf

    \b
    Options for ROBOT (a URDF or xacro file, - for standard input):
      name:=value          xacro arguments
      --format text|json   a table, or JSON (--json is the same)
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
    from ..inertia import box_inertia

    _print(box_inertia(mass, *size, _origin(xyz, rpy)), fmt)


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
    from ..inertia import cylinder_inertia

    _print(cylinder_inertia(mass, radius, length, _origin(xyz, rpy)), fmt)


@inertia.command()
@click.option("--radius", type=_SIZE, required=True, help="Radius (m).")
@_shape_options
def sphere(radius: float, mass: float, xyz: Vector3, rpy: Vector3, fmt: str) -> None:
    """The <inertial> of a solid sphere, as <sphere radius="R"/>.

    \b
    Example:
      fishbot inertia sphere --mass 0.02 --radius 0.016
    """
    from ..inertia import sphere_inertia

    _print(sphere_inertia(mass, radius, _origin(xyz, rpy)), fmt)


def _origin(xyz: Vector3, rpy: Vector3) -> Any:
    from ..model import Origin

    if any(abs(angle) > 2 * math.pi for angle in rpy):
        turned = " ".join(f"{math.radians(a):.6g}" for a in rpy)
        click.echo(
            f"warning: --rpy is in radians; if {' '.join(f'{a:g}' for a in rpy)} are degrees, "
            f"write --rpy {turned}",
            err=True,
        )

    return Origin(xyz=tuple(xyz), rpy=tuple(rpy))  # type: ignore[arg-type]


def _print(inertial: Inertial, fmt: str) -> None:
    from ..write import inertial_xml
    from . import _to_stdout

    tensor = inertial.inertia
    if not all(math.isfinite(getattr(tensor, f)) for f in ("ixx", "iyy", "izz")):
        raise click.UsageError("the moments overflow: give the sizes in metres")

    if fmt == "json":
        text = json.dumps(inertial_dict(inertial), indent=2) + "\n"
    else:
        text = inertial_xml(inertial)
    _to_stdout(text.encode("utf-8"))


class _RobotCommand(click.Command):
    """The robot form, shown as `fishbot inertia ROBOT ...` (its name is only internal)."""

    def format_usage(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        parent = ctx.parent.command_path if ctx.parent else "fishbot inertia"
        formatter.write_usage(parent, "ROBOT [name:=value]... [OPTIONS]")


@inertia.command(cls=_RobotCommand, hidden=True)
@click.argument("file", type=click.Path(allow_dash=True))
@click.argument("args", nargs=-1, metavar="[name:=value]...")
@text_or_json("text: a table; json: the same numbers for machines.")
@click.option("--json", "as_json", is_flag=True, help="Same as --format json.")
@click.option("--fill", is_flag=True, help="Write a copy with the missing inertials (needs -o).")
@click.option("-o", "--output", metavar="OUT", help="Where --fill writes; - is standard output.")
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
@click.option("--package", "package_items", multiple=True, metavar="NAME=PATH", help=_PACKAGE_HELP)
def robot(
    file: str,
    args: Sequence[str],
    fmt: str,
    as_json: bool,
    fill: bool,
    output: str | None,
    density: float | None,
    masses: Sequence[str],
    package_items: Sequence[str],
) -> None:
    """The mass table of ROBOT, a URDF or xacro file (- reads a URDF from standard input).

    One line per link: mass, centre of mass, principal moments, and the `fishbot check`
    rules that concern it; then the robot's total mass, centre of mass and principal
    moments at the zero configuration. With --fill -o OUT, a copy in which each link with
    collision shapes and no <inertial> gets one. Exit status: 0 done, 1 the robot has
    errors or --fill left a link out, 2 a file could not be read or written, or the
    command line is wrong.

    \b
    Examples:
      fishbot inertia robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot inertia robot.urdf --json
      fishbot inertia robot.urdf --fill --density 1000 -o robot_filled.urdf
    """
    from . import (
        EXIT_INVALID,
        EXIT_OK,
        _check_input,
        _emit_findings,
        _fail,
        _packages,
        _status,
        _to_stdout,
        _xacro_args,
    )

    if any(":=" not in a for a in args):
        raise click.UsageError(f"unexpected argument {next(a for a in args if ':=' not in a)!r}")
    if fill and output is None:
        raise click.UsageError("--fill writes a copy: give -o OUT (the input is never changed)")
    if not fill and (output is not None or density is not None or masses):
        raise click.UsageError("-o, --density and --mass go with --fill")
    if fill and density is None and not masses:
        raise click.UsageError("--fill needs --density KG_PER_M3 or --mass LINK=KG")
    if fill and (as_json or fmt == "json"):
        raise click.UsageError("--fill writes a URDF: it takes no --json or --format")
    if file == "-" and args:
        raise click.UsageError("name:=value arguments are for a .xacro file, not standard input")
    values = _xacro_args(args)
    packages = _packages(package_items)
    try:
        result = _check_input(file, values, packages)
    except FishbotUrdfError as exc:
        _emit_findings([_fail(exc)])
        sys.exit(_status(exc))
    if fill:
        errors = [d for d in result.diagnostics if d.is_error]
        if result.robot is None or errors:  # the robot's own faults come first
            _emit_findings(errors or result.diagnostics)
            click.echo("nothing written: fix the errors above first", err=True)
            sys.exit(EXIT_INVALID)
        sys.exit(fill_copy(result, packages, output or "-", density, masses))
    _emit_findings(result.diagnostics)
    if result.robot is None:
        sys.exit(EXIT_INVALID)
    table = mass_table(result)
    if fmt == "json" or as_json:
        _to_stdout((json.dumps(table, indent=2) + "\n").encode("utf-8"))
    else:
        _to_stdout(table_text(table).encode("utf-8"))
    sys.exit(EXIT_INVALID if not result.ok else EXIT_OK)
