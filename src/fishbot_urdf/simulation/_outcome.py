"""What one simulation of a robot gave: the numbers measured, each against what the robot's
description says it should be, and the findings."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from ..diagnostics import Diagnostic

__all__ = ["Measure", "Outcome", "Trial"]

Trial = Literal["drive", "hold", "drop"]
"""What was done: a wheeled robot dropped on the floor and driven; a robot held by its root
at a configuration; a robot dropped on the floor and left to stand."""


@dataclass(frozen=True, slots=True)
class Measure:
    """One number measured in the simulation.

    Attributes:
        name: What it is (``straight speed``).
        value: Its value.
        expected: What the robot's description and the commands say it should be (None
            where nothing is expected, only a bound).
        unit: Its unit (``m/s``).
        ok: Whether it is within the tolerance of ``expected`` or the bound.
        about: The link or joint it is measured on ("" for the whole robot).
        most: The most it may be, for a number held to a bound rather than to ``expected``.
    """

    name: str
    value: float
    expected: float | None
    unit: str
    ok: bool
    about: str = ""
    most: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return {
            "name": self.name,
            "about": self.about,
            "value": self.value,
            "expected": self.expected,
            "at_most": self.most,
            "unit": self.unit,
            "ok": self.ok,
        }


@dataclass(frozen=True, slots=True)
class Outcome:
    """A simulation's outcome.

    Attributes:
        robot: The robot's name.
        trial: What was done to it.
        seconds: How long it was simulated (s of simulated time).
        steps: How many steps MuJoCo took.
        measures: The numbers measured, in the order they were.
        findings: What went wrong (the ``sim-*`` rules), and what the conversion to MJCF
            changed or left out, each located in the robot's files.
        stopped: Why nothing was simulated ("" when it was): the findings say where.
    """

    robot: str
    trial: Trial
    seconds: float
    steps: int
    measures: tuple[Measure, ...]
    findings: tuple[Diagnostic, ...]
    stopped: str = ""

    @property
    def ok(self) -> bool:
        """Whether nothing went wrong that is an error."""
        return not any(d.is_error for d in self.findings)
