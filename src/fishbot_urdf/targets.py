"""The programs a robot is checked for: a finding that harms only programs not targeted is a
warning, not an error.

A target names one program, or the programs every ROS robot meets:

- ``ros``: check_urdf, robot_state_publisher, RViz and MoveIt, which read a robot with
  urdfdom, and xacro (the default);
- ``check_urdf``: check_urdf alone: an error only where it refuses the file, so that the
  exit status is check_urdf's;
- ``gazebo``, ``mujoco``, ``drake``, ``pybullet``: the simulators;
- ``ros2_control``: the controller manager of ros2_control (and ros_control);
- ``all``: every program a rule names.

A robot with a ``<gazebo>`` element, or a ``<ros2_control>`` run by Gazebo, targets Gazebo
besides the default; one with a ``<ros2_control>`` or ``<transmission>``, ros2_control. A
rule that names no program (a file that cannot be read), and a fatal one, stays as it is.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import TYPE_CHECKING

from .catalog import Consumer, Family, all_rules
from .catalog.reading import ROBOT_NAME, ROBOT_VERSION
from .catalog.structure import (
    DUPLICATE_JOINT,
    DUPLICATE_LINK,
    DUPLICATE_MATERIAL,
    MISSING_LIMIT,
    MULTIPLE_ROOTS,
    NO_LINKS,
    NO_ROOT,
    UNDEFINED_LINK,
)
from .diagnostics import Diagnostic, Kind, Severity
from .errors import UnknownNameError
from .extensions import controlled, simulated_in_gazebo
from .model import JointType

if TYPE_CHECKING:
    from .analysis import Analysis
    from .model import Robot

__all__ = [
    "ALIASES",
    "DEFAULT",
    "TARGETS",
    "consumers_of",
    "refused",
    "retarget",
    "target_name",
    "targets_of",
    "urdfdom_refuses",
]

CHECK_URDF = "check_urdf"

TARGETS: Mapping[str, tuple[Consumer, ...]] = MappingProxyType(
    {
        "ros": (Consumer.URDFDOM, Consumer.XACRO),
        CHECK_URDF: (),  # what check_urdf refuses: see `urdfdom_refuses`
        "gazebo": (Consumer.GAZEBO,),
        "mujoco": (Consumer.MUJOCO,),
        "drake": (Consumer.DRAKE,),
        "pybullet": (Consumer.PYBULLET,),
        "ros2_control": (Consumer.ROS2_CONTROL,),
        "all": tuple(Consumer),
    }
)
"""Each target's name, and the consumers (see `fishbot_urdf.catalog.Consumer`) it stands for."""

ALIASES: Mapping[str, str] = MappingProxyType(
    {
        "urdfdom": "ros",
        "rviz": "ros",
        "rviz2": "ros",
        "robot_state_publisher": "ros",
        "moveit": "ros",
        "kdl": "ros",
        "gz": "gazebo",
        "gazebo_classic": "gazebo",
        "ignition": "gazebo",
        "gz_sim": "gazebo",
        "bullet": "pybullet",
        "pydrake": "drake",
        "mjcf": "mujoco",
        "ros_control": "ros2_control",
        "controller_manager": "ros2_control",
    }
)
"""Other names of the targets (written with ``-`` or ``_``, in any case)."""

DEFAULT = ("ros",)
"""The targets of a robot when none are given (with ``gazebo`` and ``ros2_control`` when it
is written for them)."""


def target_name(name: str) -> str:
    """The target ``name`` stands for (``RViz`` -> ``ros``, ``check-urdf`` -> ``check_urdf``).

    Raises:
        UnknownNameError: ``name`` is no target (the error names the closest).
    """
    plain = name.strip().lower().replace("-", "_")
    plain = ALIASES.get(plain, plain)
    if plain not in TARGETS:
        raise UnknownNameError("target", name, TARGETS)
    return plain


def targets_of(robot: Robot | None, given: Iterable[str] | None = None) -> tuple[str, ...]:
    """The targets a robot is checked for: ``given`` (names or aliases), else the default,
    with ``gazebo`` for a robot written for Gazebo and ``ros2_control`` for one written for
    it."""
    if given is not None:
        return tuple(dict.fromkeys(map(target_name, given)))
    if robot is None:
        return DEFAULT
    gazebo = ("gazebo",) if simulated_in_gazebo(robot) else ()
    control = ("ros2_control",) if controlled(robot) else ()
    return (*DEFAULT, *gazebo, *control)


def consumers_of(targets: Iterable[str]) -> frozenset[Consumer]:
    """The consumers the targets stand for."""
    return frozenset(c for name in targets for c in TARGETS[target_name(name)])


def retarget(
    findings: Iterable[Diagnostic], targets: Iterable[str], analysis: Analysis | None
) -> Iterator[Diagnostic]:
    """The findings, an error made a warning where none of the targets is harmed by it:
    its rule names consumers and none of them is targeted, and, for ``check_urdf``, urdfdom
    does not refuse the file for it."""
    names = tuple(targets)
    consumers = consumers_of(names)
    refusals = CHECK_URDF in names
    for finding in findings:
        rule = finding.definition
        if (
            finding.is_error
            and rule is not None
            and rule.consumers
            and not rule.fatal
            and consumers.isdisjoint(rule.consumers)
            and not (refusals and refused(finding, analysis))
        ):
            yield replace(finding, severity=Severity.WARNING)
        else:
            yield finding


# Faults for which urdfdom builds no robot from the file, whatever their severity here.
_REFUSED = frozenset(
    rule.id
    for rule in (
        ROBOT_NAME,
        ROBOT_VERSION,
        NO_LINKS,
        DUPLICATE_LINK,
        DUPLICATE_JOINT,
        DUPLICATE_MATERIAL,
        UNDEFINED_LINK,
        MULTIPLE_ROOTS,
        NO_ROOT,
        MISSING_LIMIT,
    )
)
_READING = frozenset(rule.id for rule in all_rules() if rule.family is Family.URDF)
_AXISLESS = (JointType.FIXED, JointType.FLOATING)


def refused(finding: Diagnostic, analysis: Analysis | None) -> bool:
    """Whether urdfdom (check_urdf) refuses the file for ``finding``: a fault of the robot
    element, of the names or of the tree, or an error in reading a joint (urdfdom drops
    nothing of a joint, and refuses the whole file for it; it logs a link's faults and keeps
    the link, and reads no fixed or floating joint's axis)."""
    rule = finding.rule
    if rule in _REFUSED:
        return True
    subject = finding.subject
    if rule not in _READING or not finding.is_error or subject is None:
        return False
    if subject.kind is not Kind.JOINT:
        return False
    joint = analysis.joints.get(subject.name) if analysis is not None else None
    axisless = joint is not None and joint.type in _AXISLESS
    return not (axisless and finding.element == "axis")


def urdfdom_refuses(findings: Iterable[Diagnostic], analysis: Analysis | None) -> bool:
    """Whether urdfdom (check_urdf) refuses the file for any of the findings (pass the
    silenced ones too)."""
    return any(refused(finding, analysis) for finding in findings)
