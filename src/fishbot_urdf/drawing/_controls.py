"""The viewer page's controls: which values each may hold (a slider's range, a number
within it, a checkbox's true or false, a button's press), and the log line of a value
dropped."""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any

from ..model import JointType
from ._serving import shown

__all__ = ["Input", "dropped", "position", "slider_range"]

_log = logging.getLogger("fishbot_urdf.drawing.viewer")  # the viewer's one channel

_SLACK = 1e-9  # a slider's end, reached in steps of (high - low) / 1000, may miss by a rounding


@dataclass(frozen=True, slots=True)
class Input:
    """A control on the page: a joint's slider (``low`` .. ``high``), or, with ``toggle``,
    a checkbox, or, with ``button``, a button (whose one value is true: pressed)."""

    label: str
    low: float = 0.0
    high: float = 0.0
    toggle: bool = False
    button: bool = False

    @property
    def title(self) -> str:
        """How a log line names it."""
        kind = "checkbox" if self.toggle else "button" if self.button else "joint"
        return f"{kind} {self.label!r}"


def position(value: Any, low: float, high: float) -> float | None:
    """``value`` as a slider's position: a finite number (no bool, no text such as "nan")
    within ``low`` .. ``high`` (less a rounding error, taken in), else None."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    try:
        number = float(value)
    except OverflowError:  # an int beyond any float
        return None
    if not (math.isfinite(number) and low - _SLACK <= number <= high + _SLACK):
        return None
    return min(max(number, low), high)


def dropped(label: str, value: Any, low: float, high: float) -> None:
    _log.warning(
        "joint %r: dropped %s sent by the page (not a number within %g .. %g)",
        label,
        shown.repr(value),
        low,
        high,
    )


def slider_range(analysis: Any, variable: str) -> tuple[float, float]:
    """A slider's range: the joint's limits, else a turn each way (or a metre, sliding)."""
    joint = analysis.joints.get(variable)
    if (
        joint is not None
        and joint.limit is not None
        and joint.type
        in (
            JointType.REVOLUTE,
            JointType.PRISMATIC,
        )
        and joint.limit.lower < joint.limit.upper
    ):
        return joint.limit.lower, joint.limit.upper
    if joint is not None and joint.type is JointType.PRISMATIC:
        return -1.0, 1.0
    part = variable.rsplit(".", 1)[-1]
    return (-1.0, 1.0) if part in ("x", "y", "z") else (-math.pi, math.pi)
