"""Joint positions as a caller names them (``-j NAME=VALUE``, a mapping given to the
kinematics, a slider set in the viewer): what a name names, and whether a value is one its
joint takes. Every front end and both evaluators ask here, so each refusal is worded once.
"""

from __future__ import annotations

import math
import reprlib
from collections.abc import Collection, Mapping
from typing import Any

from ..analysis import Analysis
from ..errors import ArgumentError, FishbotUrdfError, UnknownNameError
from ..model import Joint, JointType
from ..wording import listing

__all__ = ["MOVING", "check_joint", "check_value", "check_variables", "not_a_variable"]

MOVING = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)
"""The joints whose position is one number."""

_LIMITED = (JointType.REVOLUTE, JointType.PRISMATIC)  # a continuous joint's limits bound no angle
_SLACK = 1e-9  # a limit reached by a rounding is within it

_shown = reprlib.Repr()
_shown.maxstring = _shown.maxother = 40  # a value a caller gave, named short and on one line


def check_value(joint: Joint | None, name: str, value: Any) -> float:
    """``value`` as the position of ``name`` (a joint, or a part of one: ``slide.x``): a
    finite number (no bool, no text), within ``joint``'s limits when it is a revolute or
    prismatic joint that has them.

    Raises:
        ArgumentError: The value is not a finite number, or is outside the joint's limits.
    """
    number = _number(value)
    if number is None:
        number_given = isinstance(value, (int, float)) and not isinstance(value, bool)
        shown = repr(float(value)) if number_given else _shown.repr(value)  # nan, not np.nan
        raise ArgumentError(f"joint {name!r}: position {shown} is not a finite number", name=name)
    limit = joint.limit if joint is not None else None
    if (
        joint is not None
        and limit is not None
        and joint.type in _LIMITED
        and not limit.lower - _SLACK <= number <= limit.upper + _SLACK
    ):
        raise ArgumentError(
            f"joint {name!r}: position {number:g} is outside its limits "
            f"{limit.lower:g} .. {limit.upper:g}",
            name=name,
        )
    return number


def _number(value: Any) -> float | None:
    """``value`` as a finite float, or None: no bool, no text, nothing that is not a number."""
    if isinstance(value, (bool, str, bytes)):
        return None
    try:
        number = float(value)
    except (TypeError, ValueError, OverflowError):  # None, an int beyond any float
        return None
    return number if math.isfinite(number) else None


def check_joint(analysis: Analysis, name: str, value: Any) -> float:
    """``value`` as the position of the joint ``name``, which must be a revolute, continuous
    or prismatic joint (a mimic joint too: given its own position, it follows no leader).

    Raises:
        UnknownNameError: The robot has no joint of that name (the error names the closest).
        ArgumentError: The joint's position is not one number (fixed, planar, floating), or
            the value is not a finite number or is outside the joint's limits.
    """
    joint = analysis.joints.get(name)
    if joint is None:
        raise UnknownNameError("joint", name, analysis.joints)
    if joint.type not in MOVING:
        raise ArgumentError(
            f"joint {name!r} is {joint.type.value}: it takes no position", name=name
        )
    return check_value(joint, name, value)


def check_variables(
    analysis: Analysis, positions: Mapping[str, Any], variables: Collection[str]
) -> None:
    """Refuse a name in ``positions`` that is none of ``variables`` (the configuration's
    entries: `fishbot_urdf.analysis.plan.Plan.variables`, or those a viewer has sliders for),
    saying what it names (see `not_a_variable`)."""
    for name in positions:
        if name not in variables:
            raise not_a_variable(analysis, name, variables)


def not_a_variable(analysis: Analysis, name: str, variables: Collection[str]) -> FishbotUrdfError:
    """The error for a position named ``name``, none of ``variables``: an ArgumentError for a
    joint that has no position of its own (fixed; planar or floating, whose position is
    ``JOINT.x`` ...; a mimic joint, which follows another; a joint that places no link), an
    UnknownNameError (naming the closest) for no joint at all."""
    joint = analysis.joints.get(name)
    if joint is None:
        return UnknownNameError("joint", name, variables)
    if joint.type is JointType.FIXED:
        moving = f"moving joints: {listing(variables)}" if variables else "no joint moves"
        return ArgumentError(f"joint {name!r} is fixed: it takes no position ({moving})", name=name)
    parts = [v for v in variables if v.startswith(name + ".")]
    if parts:
        listed = ", ".join(parts[:-1]) + " and " + parts[-1]
        return ArgumentError(
            f"joint {name!r} is {joint.type.value}: its position is {listed}", name=name
        )
    follows = analysis.plan.mimics.get(name)
    if follows is not None and follows.leader is not None:
        return ArgumentError(
            f"joint {name!r} mimics {follows.leader!r} and follows it: "
            f"set {follows.leader!r} instead",
            name=name,
        )
    if follows is not None:
        return ArgumentError(
            f"joint {name!r} mimics a joint whose position is not one number: it stays at "
            f"its offset, {follows.offset:g}",
            name=name,
        )
    owner = analysis.parent_joint.get(joint.child)
    if owner is not None and owner is not joint:
        return ArgumentError(
            f"joint {name!r} places no link: link {joint.child!r} hangs from joint "
            f"{owner.name!r}, its first parent joint",
            name=name,
        )
    return UnknownNameError("joint", name, variables)
