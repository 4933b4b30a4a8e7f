"""The closed vocabularies a finding and its rule are told in: how bad it is, what kind of
thing it is about, the family of its rule and the programs that rule matters to."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

__all__ = ["Consumer", "Family", "Kind", "Severity", "Subject"]


class Severity(str, Enum):
    """How bad a finding is: errors make a robot invalid, warnings do not (unless strict)."""

    ERROR = "error"
    WARNING = "warning"
    NOTE = "note"


class Kind(str, Enum):
    """What kind of thing a finding is about."""

    ROBOT = "robot"
    LINK = "link"
    JOINT = "joint"
    MATERIAL = "material"
    FILE = "file"
    COMMENT = "comment"


@dataclass(frozen=True, slots=True)
class Subject:
    """The thing a finding is about: a link, a joint, a material, the robot or a file.

    ``str(subject)`` is how messages name it: ``link 'base_link'``.
    """

    kind: Kind
    name: str

    def __str__(self) -> str:
        return f"{self.kind.value} {self.name!r}"


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
    SIMULATION = "simulation"
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
