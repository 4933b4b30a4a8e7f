"""`fishbot inertia ROBOT --fill`: a copy with the inertials computed from collision shapes."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from ..diagnostics import Diagnostic, Severity
from ..errors import FishbotUrdfError

if TYPE_CHECKING:
    from ..check import CheckResult
    from ..model import Inertial, Link, Mesh


def fill_copy(
    result: CheckResult,
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
        text = add_inertials(result.data, computed, path=result.path)
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
