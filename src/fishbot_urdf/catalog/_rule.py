"""What a rule is: its id, severity, family, documentation and consumers."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, fields
from enum import Enum
from typing import TYPE_CHECKING, Any

from ..diagnostics import Diagnostic, Severity, Subject, diagnostic

if TYPE_CHECKING:
    from ..model import Location

__all__ = ["Consumer", "Family", "Rule"]


class Family(str, Enum):
    """Groups of rules, selectable by name (``--select physics``)."""

    XML = "xml"
    URDF = "urdf"
    STRUCTURE = "structure"
    JOINTS = "joints"
    REFERENCES = "references"
    MESHES = "meshes"
    PHYSICS = "physics"
    GAZEBO = "gazebo"
    XACRO = "xacro"
    SETUP = "setup"
    LINT = "lint"


class Consumer(str, Enum):
    """Programs that read robot descriptions, and refuse or misread what a rule finds."""

    URDFDOM = "urdfdom"  # check_urdf, robot_state_publisher, RViz, MoveIt, KDL
    XACRO = "xacro"
    GAZEBO = "gazebo"
    MUJOCO = "mujoco"
    DRAKE = "drake"
    PYBULLET = "pybullet"
    ROS2_CONTROL = "ros2_control"  # its controller manager, and ros_control's
    XML_TOOLS = "xml-tools"  # strict XML readers: lxml, Python's xml, yourdfpy, urchin

    @property
    def label(self) -> str:
        """How the consumer is named to people."""
        return _LABELS[self]


_LABELS = {
    Consumer.URDFDOM: "urdfdom (check_urdf, robot_state_publisher, RViz, MoveIt)",
    Consumer.XACRO: "xacro",
    Consumer.GAZEBO: "Gazebo",
    Consumer.MUJOCO: "MuJoCo",
    Consumer.DRAKE: "Drake",
    Consumer.PYBULLET: "PyBullet",
    Consumer.ROS2_CONTROL: "ros2_control (and ros_control)",
    Consumer.XML_TOOLS: "strict XML readers (lxml, Python's xml, yourdfpy, urchin)",
}


# Compared and hashed by identity: each rule is made once, and a dict keyed by rules (the
# CLI's hints) then hashes no text.
@dataclass(frozen=True, slots=True, eq=False)
class Rule:
    """One kind of finding.

    Attributes:
        id: Stable id, shown in brackets after each finding (``undefined-link``).
        severity: Its default severity.
        family: The group it belongs to.
        summary: One line: what it finds.
        explanation: Why it matters and what to do, a few sentences.
        bad: A small input that has the fault.
        good: The same input, fixed.
        consumers: The programs that refuse or misread what it finds.
        language: What ``bad`` and ``good`` are: ``urdf``, ``xacro`` or ``shell``.
        fatal: The input cannot be read past it; it cannot be turned off.
    """

    id: str
    severity: Severity
    family: Family
    summary: str
    explanation: str = ""
    bad: str = ""
    good: str = ""
    consumers: tuple[Consumer, ...] = (Consumer.URDFDOM,)
    language: str = "urdf"
    fatal: bool = False

    def __post_init__(self) -> None:
        _MADE.setdefault(self.id, self)

    def __reduce__(self) -> tuple[Any, ...]:
        # A catalogued rule comes back from another process as the same object (findings
        # made in worker processes keep their rule).
        if _MADE.get(self.id) is self:
            return (_made, (self.id,))
        return (Rule, tuple(getattr(self, f.name) for f in fields(self)))

    def report(
        self,
        message: str,
        where: Location | None,
        *,
        path: str,
        subject: Subject | None = None,
        hint: str | None = None,
        severity: Severity | None = None,
        data: Mapping[str, Any] | None = None,
        follows: Iterable[str] = (),
        element: str | None = None,
    ) -> Diagnostic:
        """A finding of this rule at ``where`` (or about the whole file ``path``), at its
        default severity unless ``severity`` says otherwise. ``data`` holds the facts behind
        it (a `Facts`), ``follows`` the ids of rules whose findings it follows from, ``element``
        the element of the subject it is about (see `Diagnostic`)."""
        return diagnostic(
            self.id,
            severity or self.severity,
            message,
            where,
            path=path,
            hint=hint,
            subject=subject,
            data=data,
            definition=self,
            follows=follows,
            element=element,
        )

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of every field."""
        return {
            "id": self.id,
            "severity": self.severity.value,
            "family": self.family.value,
            "summary": self.summary,
            "explanation": self.explanation,
            "bad": self.bad,
            "good": self.good,
            "consumers": [c.value for c in self.consumers],
            "language": self.language,
            "fatal": self.fatal,
        }


_MADE: dict[str, Rule] = {}


def _made(rule_id: str) -> Rule:
    return _MADE[rule_id]
