"""`fishbot inertia`: the <inertial> of a box, cylinder or sphere, a robot's mass table, and
inertials filled in from collision shapes."""

from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from ..diagnostics import Diagnostic, Severity
from ..errors import FishbotUrdfError
from ._options import PACKAGE_HELP as _PACKAGE_HELP
from ._options import Number, Wrapped, text_or_json

if TYPE_CHECKING:
    from ..check import CheckResult
    from ..inertia import MassProperties
    from ..model import Inertial, Link, Mesh, Vector3

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


def _inertial_dict(inertial: Inertial) -> dict[str, Any]:
    tensor = inertial.inertia
    return {
        "mass": inertial.mass,
        "origin": {"xyz": list(inertial.origin.xyz), "rpy": list(inertial.origin.rpy)},
        "inertia": {f: getattr(tensor, f) for f in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")},
    }


def _print(inertial: Inertial, fmt: str) -> None:
    from ..write import inertial_xml
    from . import _to_stdout

    tensor = inertial.inertia
    if not all(math.isfinite(getattr(tensor, f)) for f in ("ixx", "iyy", "izz")):
        raise click.UsageError("the moments overflow: give the sizes in metres")

    if fmt == "json":
        text = json.dumps(_inertial_dict(inertial), indent=2) + "\n"
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
        _stdin_urdf,
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
    data: bytes | None = None
    try:
        if file == "-":  # read once: it is checked, then filled
            from ..check import check_file

            data = _stdin_urdf()
            result = check_file(data, path="<stdin>")
        else:
            result = _check_input(file, values, packages)
        if fill and data is None and result.robot is not None:
            data = _urdf_bytes(file, values, packages)
    except FishbotUrdfError as exc:
        _emit_findings([_fail(exc)])
        sys.exit(_status(exc))
    if fill:
        errors = [d for d in result.diagnostics if d.is_error]
        if result.robot is None or errors:  # the robot's own faults come first
            _emit_findings(errors or result.diagnostics)
            click.echo("nothing written: fix the errors above first", err=True)
            sys.exit(EXIT_INVALID)
        sys.exit(_fill(result, data or b"", packages, output or "-", density, masses))
    _emit_findings(result.diagnostics)
    if result.robot is None:
        sys.exit(EXIT_INVALID)
    table = _table(result)
    if fmt == "json" or as_json:
        _to_stdout((json.dumps(table, indent=2) + "\n").encode("utf-8"))
    else:
        _to_stdout(_text(table).encode("utf-8"))
    sys.exit(EXIT_INVALID if not result.ok else EXIT_OK)


def _vector(values: Sequence[float]) -> list[float]:
    return [float(v) for v in values]


def _table(result: CheckResult) -> dict[str, Any]:
    from ..inertia import mass_properties, principal_moments

    robot = result.robot
    assert robot is not None
    rows: list[dict[str, Any]] = []
    for link in robot.links:
        findings = sorted(
            {d.rule for d in result.diagnostics if d.message.startswith(f"link {link.name!r}")}
        )
        row: dict[str, Any] = {"link": link.name, "findings": findings}
        if link.inertial is not None:
            row.update(_inertial_dict(link.inertial))
            row["principal_moments"] = _vector(principal_moments(link.inertial.inertia))
        rows.append(row)
    table: dict[str, Any] = {
        "robot": robot.name,
        "ok": result.ok,
        "links": rows,
        "total": None,
        "diagnostics": [d.to_dict() for d in result.diagnostics],
    }
    try:
        total: MassProperties = mass_properties(robot)
    except ValueError as exc:
        table["total_error"] = str(exc)
        return table
    from ..kinematics import link_poses

    children = {joint.child for joint in robot.joints}
    placed = link_poses(robot)
    table["total"] = {
        "frame": next(link.name for link in robot.links if link.name not in children),
        "mass": total.mass,
        "com": _vector(total.com) if total.mass > 0 else None,
        # links in a joint loop are not placed, so not counted
        "left_out": [link.name for link in robot.links if link.name not in placed],
        "inertia": {
            f: getattr(total.inertia, f) for f in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
        },
        "principal_moments": _vector(total.principal_moments),
    }
    return table


def _g(value: float) -> str:
    text = f"{value:.4g}"
    return "0" if text in ("-0", "0") else text


def _text(table: dict[str, Any]) -> str:
    header = ("link", "mass kg", "com x y z (m)", "principal moments (kg*m^2)", "checks")
    lines: list[tuple[str, ...]] = [header]
    for row in table["links"]:
        checks = ", ".join(row["findings"]) or "ok"
        if "mass" not in row:
            lines.append((row["link"], "-", "-", "-", checks))
            continue
        com = " ".join(_g(v) for v in row["origin"]["xyz"])
        moments = " ".join(_g(v) for v in row["principal_moments"])
        lines.append((row["link"], _g(row["mass"]), com, moments, checks))
    widths = [max(len(line[k]) for line in lines) for k in range(len(header))]
    out = [
        "  ".join(cell.ljust(w) for cell, w in zip(line, widths, strict=True)).rstrip()
        for line in lines
    ]
    total = table["total"]
    if total is None:
        out.append(f"total: {table['total_error']}")
    elif total["com"] is None:
        out.append("total: 0 kg (no link has a mass)")
    else:
        out.append(
            f"total: {_g(total['mass'])} kg; centre of mass "
            f"{' '.join(_g(v) for v in total['com'])} m in {total['frame']}; principal moments "
            f"about it {' '.join(_g(v) for v in total['principal_moments'])} kg*m^2 "
            "(zero configuration)"
        )
    if total is not None and total["left_out"]:
        listed = ", ".join(total["left_out"])
        out.append(f"left out of the total, not reached from the root: {listed}")
    return "\n".join(out) + "\n"


def _fill(
    result: CheckResult,
    data: bytes,
    packages: dict[str, str],
    output: str,
    density: float | None,
    masses: Sequence[str],
) -> int:
    from ..diagnostics import closest
    from ..inertia import link_inertial
    from ..output import write_atomic
    from ..packages import resolve_package_uri
    from ..write import add_inertials
    from . import EXIT_INVALID, EXIT_OK, _emit_findings, _fail, _status, _to_stdout

    robot = result.robot
    assert robot is not None
    links = {link.name: link for link in robot.links}
    wanted = _link_masses(masses, links, closest)

    def resolve(mesh: Mesh) -> Path:
        near = mesh.source.path if mesh.source else result.path
        return resolve_package_uri(mesh.filename, near=near, packages=packages)

    todo = [link for link in robot.links if link.collisions and link.inertial is None]
    for name in wanted:
        if links[name].inertial is not None:
            raise click.BadParameter(
                f"link {name!r} already has an <inertial>", param_hint="--mass"
            )
        if not links[name].collisions:
            raise click.BadParameter(
                f"link {name!r} has no <collision> shape to compute an inertia from",
                param_hint="--mass",
            )
    computed: dict[str, Inertial] = {}
    skipped: list[Diagnostic] = []
    for link in todo:
        mass = wanted.get(link.name)
        if mass is None and density is None:
            skipped.append(_skip(link, f"give --mass {link.name}=KG or --density"))
            continue
        try:
            computed[link.name] = link_inertial(
                link, mass=mass, density=None if mass is not None else density, resolve=resolve
            )
        except (TypeError, ValueError) as exc:
            skipped.append(_skip(link, str(exc)))
        except FishbotUrdfError as exc:  # a mesh not found, or trimesh missing
            hint = getattr(exc, "hint", None)
            skipped.append(_skip(link, exc.message + (f"; {hint}" if hint else "")))
    _emit_findings(skipped)
    if skipped and not computed:
        click.echo("nothing written: no link could be filled", err=True)
        return EXIT_INVALID
    try:
        text = add_inertials(data, computed, path=result.path)
        if output == "-":
            _to_stdout(text.encode("utf-8"))
        else:
            write_atomic(output, text, inputs=result.files)
    except FishbotUrdfError as exc:
        _emit_findings([_fail(exc)])
        return _status(exc)
    where = "the URDF to standard output" if output == "-" else output
    if computed:
        count = f"{len(computed)} link" + ("s" if len(computed) > 1 else "")
        names = ", ".join(f"{n} ({computed[n].mass:g} kg)" for n in computed)
        said = f"<inertial> added to {count}: {names}"
    else:
        said = "no link needed an <inertial>"
    click.echo(f"Wrote {where}: {said}", err=True)
    return EXIT_INVALID if skipped else EXIT_OK


def _skip(link: Link, why: str) -> Diagnostic:
    where = link.source
    return Diagnostic(
        "fill-skipped",
        Severity.ERROR,
        f"link {link.name!r}: no <inertial> added ({why})",
        where.path if where else "<input>",
        where.line if where else None,
        where.column if where else None,
    )


def _link_masses(items: Sequence[str], links: dict[str, Link], closest: Any) -> dict[str, float]:
    wanted: dict[str, float] = {}
    for item in items:
        name, sep, kg = item.partition("=")
        try:
            mass = float(kg)
        except ValueError:
            mass = -1.0
        if not sep or not name or not mass > 0 or not math.isfinite(mass):
            raise click.BadParameter(f"{item!r} is not LINK=KG with KG > 0", param_hint="--mass")
        if name in wanted:
            raise click.BadParameter(f"link {name!r} is given twice", param_hint="--mass")
        if name not in links:
            guess = closest(name, links)
            hint = f"; did you mean {guess!r}?" if guess else ""
            raise click.BadParameter(f"no link {name!r}{hint}", param_hint="--mass")
        wanted[name] = mass
    return wanted


def _urdf_bytes(file: str, values: dict[str, str], packages: dict[str, str]) -> bytes:
    """The URDF text of FILE: the file itself, or the expansion of a xacro file."""
    from ..errors import InputError
    from ..parse import is_xacro_path

    if is_xacro_path(file):
        from ..expand import expand

        return expand(file, args=values, packages=packages).text.encode("utf-8")
    try:
        with open(file, "rb") as handle:
            return handle.read()
    except OSError as exc:
        raise InputError(f"cannot read {file}: {exc.strerror}", path=file) from exc
