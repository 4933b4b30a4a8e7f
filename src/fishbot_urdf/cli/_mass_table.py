"""The mass table of `fishbot inertia ROBOT`: per link, and the whole robot."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..check import CheckResult
    from ..inertia import MassProperties
    from ..model import Inertial


def inertial_dict(inertial: Inertial) -> dict[str, Any]:
    tensor = inertial.inertia
    return {
        "mass": inertial.mass,
        "origin": {"xyz": list(inertial.origin.xyz), "rpy": list(inertial.origin.rpy)},
        "inertia": {f: getattr(tensor, f) for f in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")},
    }


def _vector(values: Sequence[float]) -> list[float]:
    return [float(v) for v in values]


def mass_table(result: CheckResult) -> dict[str, Any]:
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
            row.update(inertial_dict(link.inertial))
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
    topo = result.topology
    assert topo is not None
    table["total"] = {
        "frame": topo.root,
        # links in a joint loop are not placed, so not counted
        "left_out": [link.name for link in robot.links if link.name not in topo.reachable],
        "mass": total.mass,
        "com": _vector(total.com) if total.mass > 0 else None,
        "inertia": {
            f: getattr(total.inertia, f) for f in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
        },
        "principal_moments": _vector(total.principal_moments),
    }
    return table


def _g(value: float) -> str:
    text = f"{value:.4g}"
    return "0" if text in ("-0", "0") else text


def table_text(table: dict[str, Any]) -> str:
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
