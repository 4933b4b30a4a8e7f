"""`fishbot inertia ROBOT --fill`: the copy with the missing inertials (-o OUT), or, without
-o, what to write in each link and where (a call of the robot's own inertia macro)."""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import click

from ..config import Config
from ..diagnostics import escape_controls
from ..errors import ArgumentError, FishbotUrdfError, UnknownNameError
from ..inertia import (
    Filling,
    fill_inertials,
    shared_inertials,
    suggest_inertials,
    xacro_suggestions,
)
from ..inputs import allowing_reads
from ..output import write_atomic
from ..parsing import is_xacro_path
from ..write import add_inertials
from ._common import EXIT_INVALID, EXIT_OK, EXIT_USAGE, emit_findings, fail, stop_on, to_stdout

if TYPE_CHECKING:
    from ..inertia import InertialSuggestion, SharedInertial
    from ..lint import CheckResult
    from ..location import Location
    from ..output import Source

__all__ = ["link_masses", "suggest", "write_copy"]


def link_masses(items: Sequence[str]) -> dict[str, float]:
    """``--mass LINK=KG`` values as a mapping."""
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
        wanted[name] = mass
    return wanted


def _filling(result: CheckResult, density: float | None, masses: dict[str, float]) -> Filling:
    assert result.analysis is not None  # (its mesh_paths find the meshes, as check found them)
    try:
        return fill_inertials(result.analysis, density=density, masses=masses)
    except (ArgumentError, UnknownNameError) as exc:  # a --mass naming a wrong link
        raise click.BadParameter(exc.message, param_hint="--mass") from None


def write_copy(
    result: CheckResult,
    output: str,
    density: float | None,
    masses: dict[str, float],
    inputs: Sequence[Source],
) -> int:
    """Write the copy with the missing inertials (never over one of ``inputs``); the exit
    status."""
    filling = _filling(result, density, masses)
    emit_findings(filling.skipped)
    computed = filling.inertials
    if filling.skipped and not computed:
        click.echo("nothing written: no link could be filled", err=True)
        return EXIT_INVALID
    try:
        text = add_inertials(result.data, computed, path=result.path)
        if output == "-":
            to_stdout(text.encode("utf-8", "surrogateescape"))
        else:
            write_atomic(output, text, inputs=inputs)
    except FishbotUrdfError as exc:
        emit_findings([fail(exc)])
        return EXIT_USAGE
    where = "the URDF to standard output" if output == "-" else output
    if computed:
        count = f"{len(computed)} link" + ("s" if len(computed) > 1 else "")
        names = ", ".join(f"{n} ({computed[n].mass:g} kg)" for n in computed)
        said = f"<inertial> added to {count}: {names}"
    else:
        said = "no link needed an <inertial>"
    click.echo(escape_controls(f"Wrote {where}: {said}"), err=True)
    return EXIT_INVALID if filling.skipped else EXIT_OK


def suggest(
    file: str,
    result: CheckResult,
    fmt: str,
    density: float | None,
    masses: dict[str, float],
    values: Mapping[str, str],
    packages: Mapping[str, str],
    config: Config,
) -> int:
    """Print what to write in each link without an <inertial>, and where; the exit status.

    A xacro robot's own inertia macros are found by expanding it again and calling them
    (see `inertia_macros`): a link whose one collision one of them can describe gets its
    call, any other link the <inertial> itself."""
    filling = _filling(result, density, masses)
    emit_findings(filling.skipped)
    analysis = result.analysis
    assert analysis is not None
    suggestions = suggest_inertials(analysis, filling.inertials)
    if filling.inertials and file != "-" and is_xacro_path(file):
        try:
            with allowing_reads(config.allow_read):
                suggestions = xacro_suggestions(file, analysis, filling.inertials, values, packages)
        except FishbotUrdfError as exc:
            stop_on(exc)
    # Links one line of a macro's body makes get one note, and one call for them all.
    shared = shared_inertials(suggestions)
    if fmt == "json":
        report = {
            "ok": not filling.skipped,
            "suggestions": [s.to_dict() for s in suggestions],
            "shared": [s.to_dict() for s in shared],
            "diagnostics": [d.to_dict() for d in filling.skipped],
        }
        to_stdout((json.dumps(report, indent=2) + "\n").encode("utf-8", "surrogateescape"))
    else:
        xacro = file != "-" and is_xacro_path(file)
        by_link = {s.link: group for group in shared for s in group.suggestions}
        blocks = []
        for suggestion in suggestions:
            group = by_link.get(suggestion.link)
            if group is None:
                blocks.append(_block(suggestion, xacro))
            elif group.suggestions[0] is suggestion:
                blocks.append(_shared_block(group))
        text = "".join(blocks)
        to_stdout(text.encode("utf-8", "surrogateescape"))
        if not suggestions and not filling.skipped:
            click.echo("no link needs an <inertial>", err=True)
    return EXIT_INVALID if filling.skipped else EXIT_OK


def _block(suggestion: InertialSuggestion, xacro: bool) -> str:
    """One suggestion: a GCC-style note on the link, then what to write, indented."""
    where = suggestion.source
    place = "" if where is None else f"{_site(where)}: "
    at = "inside the <link>"
    if suggestion.line is not None:
        at = f"at line {suggestion.line}, {at}"
    calls = suggestion.made_by
    if calls:
        name, site = calls[0]
        at += f", in the body of macro {name} (called at {_site(site)})"
    mass = f"{suggestion.inertial.mass:.6g} kg"
    head = f"{place}note: link '{suggestion.link}' has no <inertial>; for {mass}, write {at}:"
    lines = [escape_controls(head)]
    lines += ["  " + escape_controls(line) for line in suggestion.text.splitlines()]
    written = suggestion.written_text
    if written is not None:
        lines.append("  or, with the sizes as the macro's body writes them, to fit every call:")
        lines.append("  " + escape_controls(written.rstrip("\n")))
    if xacro and suggestion.plain_because:
        lines.append(escape_controls(f"  (written out: {suggestion.plain_because})"))
    return "\n".join(lines) + "\n"


def _shared_block(group: SharedInertial) -> str:
    """A note on the <link> a macro's body writes once for several links: the one call
    that fits every call of the macro, and what each call gives its mass."""
    where = group.source
    place = "" if where is None else f"{_site(where)}: "
    names = ", ".join(f"'{s.link}'" for s in group.suggestions)
    at = "inside the <link>"
    if group.line is not None:
        at = f"at line {group.line}, {at}"
    sites = ", ".join(dict.fromkeys(_site(s.made_by[0][1]) for s in group.suggestions))
    once = ", once, to fit every call" if group.fits else ""
    head = (
        f"{place}note: links {names} have no <inertial>; the body of macro "
        f"{group.macro_name} makes each of them (called at {sites}): write {at}{once}:"
    )
    lines = [head]  # (escaped as a whole, below)
    if not group.fits:
        lines.append(
            "  no one call fits every call: the sizes differ from call to call, and the "
            "macro's body does not write them; each link's own call fits its call only:"
        )
        lines += [f"  {s.link}: {s.text.rstrip()}" for s in group.suggestions]
        return "\n".join(escape_controls(line) for line in lines) + "\n"
    lines.append("  " + group.text.rstrip("\n"))
    calls = group.calls()
    one = ", as each call gives it:"
    if group.one_site:  # one call, written once in another macro's body, makes them all
        outer = calls[0]["outer"]
        name = "another macro" if outer is None else f"macro {outer[0]}"
        masses = "; ".join(
            f"{c['link']} {c['mass']:.6g} kg"
            + (f" at {_site(c['outer'][1])}" if c["outer"] else "")
            for c in calls
        )
        one = (
            f"; the call at {_site(calls[0]['call'])} that gives it is written once in the "
            f"body of {name}, for all of its calls: give each link its mass through them "
            f"({masses})"
        )
    if group.parameter is not None:
        lines.append(f"  its mass is {group.macro_name}'s parameter {group.parameter}{one}")
    elif group.added is not None:
        masses = ", ".join(f"{c['mass']:.6g} kg" for c in calls)
        maker = group.suggestions[0].maker
        params = ""
        if maker is not None and maker.source is not None and not maker.optional:
            # (its params as written are known only when none has a default)
            written = " ".join((*maker.params, group.added))
            params = f' (at {_site(maker.source)}: params="{written}")'
        lines.append(
            f"  {group.macro_name} has no parameter for the mass, and the links' masses "
            f"differ ({masses}): add {group.added} to its params{params}"
            + (one if group.one_site else ", and give it in each call:")
        )
    else:
        lines.append(f"  (every link is {calls[0]['mass']:.6g} kg)")
    if (group.parameter is not None or group.added is not None) and not group.one_site:
        for call in calls:
            site = _site(call["call"])
            given = call["argument"]
            said = f"    {call['link']} ({call['mass']:.6g} kg): the call at {site}"
            if given is None:
                said += " gives none"
            else:
                value = call["value"]
                said += f' gives {group.parameter}="{given}"' + (
                    f" ({value:.6g})" if value is not None and given != f"{value:g}" else ""
                )
            said += f"; write {call['write']} there" if call["write"] else ", as it should"
            lines.append(said)
    return "\n".join(escape_controls(line) for line in lines) + "\n"


def _site(site: Location) -> str:
    return f"{site.path}:{site.line}:{site.column}"
