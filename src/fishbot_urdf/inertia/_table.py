"""A robot's mass table: each link's mass, centre of mass and principal moments, with the
rules that concern it, and the whole robot's."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from ..analysis import Analysis, of
from ..diagnostics import Diagnostic, Kind, escape_controls
from ..errors import StructureError
from ..model import Inertial, Robot, Vector3
from ._robot import mass_properties
from ._solids import MassProperties, principal_moments

__all__ = ["LinkMass", "MassTable", "inertial_dict", "mass_table"]

_FIELDS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def inertial_dict(inertial: Inertial) -> dict[str, Any]:
    """An inertial's numbers, JSON-ready: mass (kg), origin (m, rad), inertia (kg*m^2)."""
    tensor = inertial.inertia
    return {
        "mass": inertial.mass,
        "origin": {"xyz": list(inertial.origin.xyz), "rpy": list(inertial.origin.rpy)},
        "inertia": {f: getattr(tensor, f) for f in _FIELDS},
    }


@dataclass(frozen=True, slots=True)
class LinkMass:
    """One line of the table.

    Attributes:
        link: The link's name.
        inertial: Its inertial, if it has one.
        principal_moments: The inertia's eigenvalues, smallest first (kg*m^2).
        rules: The ids of the rules that found something about the link, sorted.
    """

    link: str
    inertial: Inertial | None
    principal_moments: Vector3 | None
    rules: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class MassTable:
    """The mass table of a robot at one configuration (every joint at zero, unless given).

    Attributes:
        robot: The robot's name.
        links: One line per link, in file order.
        total: The whole robot's mass properties in ``frame``, or None (see ``problem``).
        frame: The root link, whose frame ``total`` is given in.
        left_out: Links left out of the total: no root reaches them.
        problem: Why there is no total (no single root), or None.
        positions: The joint positions given (rad or m), by name; the rest were at zero.
    """

    robot: str
    links: tuple[LinkMass, ...]
    total: MassProperties | None
    frame: str | None
    left_out: tuple[str, ...]
    problem: str | None
    positions: tuple[tuple[str, float], ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """The table, JSON-ready."""
        rows: list[dict[str, Any]] = []
        for line in self.links:
            row: dict[str, Any] = {"link": line.link, "rules": list(line.rules)}
            if line.inertial is not None and line.principal_moments is not None:
                row.update(inertial_dict(line.inertial))
                row["principal_moments"] = list(line.principal_moments)
            rows.append(row)
        total = self.total
        return {
            "robot": self.robot,
            "links": rows,
            "total": None
            if total is None
            else {
                "frame": self.frame,
                "left_out": list(self.left_out),
                "mass": total.mass,
                "com": list(total.com) if total.mass > 0 else None,
                "inertia": {f: getattr(total.inertia, f) for f in _FIELDS},
                "principal_moments": list(total.principal_moments),
            },
            "problem": self.problem,
            "positions": dict(self.positions),
        }

    def to_text(self) -> str:
        """The table as aligned text, then a line for the whole robot; control characters in
        names are written visibly (:func:`fishbot_urdf.diagnostics.escape_controls`)."""
        header = (
            "link",
            "mass kg",
            "com x y z (m, link frame)",
            "principal moments (kg*m^2)",
            "checks",
        )
        lines: list[tuple[str, ...]] = [header]
        for line in self.links:
            checks = ", ".join(line.rules) or "ok"
            if line.inertial is None or line.principal_moments is None:
                lines.append((escape_controls(line.link), "-", "-", "-", checks))
                continue
            com = " ".join(_g(v) for v in line.inertial.origin.xyz)
            moments = " ".join(_g(v) for v in line.principal_moments)
            lines.append((escape_controls(line.link), _g(line.inertial.mass), com, moments, checks))
        widths = [max(len(line[k]) for line in lines) for k in range(len(header))]
        out = [
            "  ".join(cell.ljust(w) for cell, w in zip(line, widths, strict=True)).rstrip()
            for line in lines
        ]
        total = self.total
        if total is None:
            out.append(f"total: {self.problem}")
        elif total.mass <= 0:
            out.append("total: 0 kg (no link has a mass)")
        else:
            out.append(
                f"total: {_g(total.mass)} kg; centre of mass "
                f"{' '.join(_g(v) for v in total.com)} m in {self.frame}; principal moments "
                f"about it {' '.join(_g(v) for v in total.principal_moments)} kg*m^2 "
                f"({self._configuration()})"
            )
        if total is not None and self.left_out:
            out.append(
                f"left out of the total, not reached from the root: {', '.join(self.left_out)}"
            )
        return "\n".join(escape_controls(line) for line in out) + "\n"

    def _configuration(self) -> str:
        if not self.positions:
            return "zero configuration"
        given = ", ".join(f"{name}={_g(value)}" for name, value in self.positions)
        return f"joints at {given}, the rest at zero"


def _g(value: float) -> str:
    text = f"{value:.4g}"
    return "0" if text in ("-0", "0") else text


def mass_table(
    robot: Robot | Analysis,
    diagnostics: Iterable[Diagnostic] = (),
    positions: Mapping[str, float] | None = None,
) -> MassTable:
    """The mass table of ``robot`` with its joints at ``positions``.

    Positions are in rad or m (the rest at zero, mimic joints following); each line lists
    the rules of ``diagnostics`` (its findings, from `check_file`) whose subject is that
    link. Each link's centre of mass is in its own frame; the total's is in the root
    link's.

    Raises:
        UnknownNameError: ``positions`` names a joint that does not exist.
        ArgumentError: ``positions`` names a joint that does not move, or a position outside
            its limits.
    """
    analysis = of(robot)
    model = analysis.robot
    concerning: dict[str, set[str]] = {}
    for finding in diagnostics:
        subject = finding.subject
        if subject is not None and subject.kind is Kind.LINK:
            concerning.setdefault(subject.name, set()).add(finding.rule)
    lines = tuple(
        LinkMass(
            link.name,
            link.inertial,
            principal_moments(link.inertial.inertia) if link.inertial else None,
            tuple(sorted(concerning.get(link.name, ()))),
        )
        for link in model.links
    )
    given = tuple((positions or {}).items())
    try:
        total = mass_properties(analysis, positions)
    except StructureError as exc:
        return MassTable(model.name, lines, None, None, (), exc.message, given)
    i = total.inertia
    numbers = (total.mass, *total.com, i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz)
    if not all(math.isfinite(n) for n in (*numbers, *total.principal_moments)):
        problem = (
            "no total: the links' masses and inertias add up beyond the largest number a "
            "float holds (about 1.8e308)"
        )
        return MassTable(model.name, lines, None, None, (), problem, given)
    topo = analysis.topology
    # links in a joint loop are not placed, so not counted
    left_out = tuple(link.name for link in model.links if link.name not in topo.reachable)
    return MassTable(model.name, lines, total, topo.root, left_out, None, given)
