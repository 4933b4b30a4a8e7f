"""Names that elements URDF does not define give to the robot's links and joints.

Gazebo's ``<gazebo reference>``, ``<transmission>`` and ``<ros2_control>`` joints, and the
joint and frame names given to Gazebo's plugins (differential drive, camera, laser, depth
camera, joint state publisher) all name parts of the robot. A typo in any of them passes
every URDF reader and breaks the simulation later. `collect` lists them with their places.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from enum import Enum

from lxml import etree

from .errors import FishbotUrdfError
from .model import Location, Robot
from .xml.source import parse_xml

__all__ = [
    "Interface",
    "Reference",
    "Target",
    "collect",
    "controlled",
    "from_robot",
    "plugin_target",
    "simulated_in_gazebo",
]

Locate = Callable[[etree._Element], Location | None]
LocateAttribute = Callable[[Location, str], Location]

# What these tags name, inside a Gazebo <plugin> (ROS 1 and ROS 2 spellings).
_PLUGIN_JOINTS = frozenset(
    {
        "left_joint",
        "right_joint",
        "leftJoint",
        "rightJoint",
        "leftFrontJoint",
        "rightFrontJoint",
        "leftRearJoint",
        "rightRearJoint",
        "joint_name",
        "jointName",
    }
)
_PLUGIN_FRAMES = frozenset(
    {"robot_base_frame", "robotBaseFrame", "frame_name", "frameName", "bodyName", "body_name"}
)
# Frames every simulation has besides the robot's links (a p3d plugin's reference frame).
_WORLD_FRAMES = frozenset({"world", "map", "odom"})
# Extensions that hold references; every other one is passed over unread.
TAGS = frozenset({"gazebo", "transmission", "ros2_control"})


class Target(str, Enum):
    """What a reference must name."""

    LINK = "link"
    JOINT = "joint"
    LINK_OR_JOINT = "link or joint"


@dataclass(frozen=True, slots=True)
class Interface:
    """A ``<command_interface>`` or ``<state_interface>`` of a ``<ros2_control>`` joint."""

    kind: str  # "command" or "state"
    name: str
    source: Location | None = None


@dataclass(frozen=True, slots=True)
class Reference:
    """A name given to a link or joint of the robot by an element URDF does not define.

    Attributes:
        name: The name given.
        target: What it must name.
        context: Where it is given, as people read it (``<gazebo reference>``).
        source: Where the name is written.
        interfaces: For a ``<ros2_control>`` joint, its interfaces.
    """

    name: str
    target: Target
    context: str
    source: Location | None = None
    interfaces: tuple[Interface, ...] = ()


def collect(
    element: etree._Element, locate: Locate, attribute: LocateAttribute | None = None
) -> list[Reference]:
    """The references in one top-level extension element.

    ``locate`` is called on the element and on every element inside it, in document order
    (a `fishbot_urdf.xml.locator.Locator` needs that); ``attribute`` gives an attribute's place
    from its element's.
    """
    found: list[Reference] = []
    kind = element.tag
    control: Reference | None = None
    interfaces: list[Interface] = []
    for node in element.iter(etree.Element):
        at = locate(node)
        tag = node.tag
        if not isinstance(tag, str):
            continue
        parent = node.getparent()
        if node is element:
            name = node.get("reference")
            if kind == "gazebo" and name is not None:
                where = attribute(at, "reference") if attribute and at else at
                found.append(Reference(name, Target.LINK_OR_JOINT, "<gazebo reference>", where))
        elif kind in ("transmission", "ros2_control") and tag == "joint" and parent is element:
            name = node.get("name")
            if name is None:
                continue
            where = attribute(at, "name") if attribute and at else at
            if control is not None:
                found.append(_with(control, interfaces))
                control, interfaces = None, []
            if kind == "transmission":
                found.append(Reference(name, Target.JOINT, "<transmission> joint", where))
            else:
                control = Reference(name, Target.JOINT, "<ros2_control> joint", where)
        elif control is not None and tag in ("command_interface", "state_interface"):
            if parent is not None and parent.getparent() is element:
                kind_name = tag.removesuffix("_interface")
                interfaces.append(Interface(kind_name, node.get("name") or "", at))
        elif kind == "gazebo" and (tag in _PLUGIN_JOINTS or tag in _PLUGIN_FRAMES):
            if not any(a.tag == "plugin" for a in node.iterancestors()):
                continue
            target = Target.JOINT if tag in _PLUGIN_JOINTS else Target.LINK
            found.extend(
                Reference(name, target, f"plugin <{tag}>", at) for name in _names(node.text, target)
            )
    if control is not None:
        found.append(_with(control, interfaces))
    return found


def plugin_target(tag: str) -> Target | None:
    """What the text of element ``tag`` inside a Gazebo ``<plugin>`` names: a joint (or
    joints, comma-separated), a link, or nothing of the robot (None)."""
    if tag in _PLUGIN_JOINTS:
        return Target.JOINT
    if tag in _PLUGIN_FRAMES:
        return Target.LINK
    return None


def from_robot(robot: Robot) -> tuple[Reference, ...]:
    """The references in ``robot``'s extension elements, read again from their text (with no
    places: the reader of a file gives them with places)."""
    found: list[Reference] = []
    for text in robot.extras:
        if not text.startswith(tuple(f"<{tag}" for tag in TAGS)):
            continue
        try:
            element = parse_xml(text.encode("utf-8"))
        except FishbotUrdfError:  # the reader kept it, so it was well-formed once
            continue
        if element.tag in TAGS:
            found.extend(collect(element, lambda _node: None))
    return tuple(found)


def simulated_in_gazebo(robot: Robot) -> bool:
    """Whether ``robot`` is written for Gazebo: it has a ``<gazebo>`` element (a plugin, a
    link's friction or colour), or a ``<ros2_control>`` whose hardware is Gazebo's
    (gazebo_ros2_control, gz_ros2_control, ign_ros2_control)."""
    for text in robot.extras:
        if _GAZEBO.match(text):
            return True
        if text.startswith("<ros2_control") and _GAZEBO_HARDWARE.search(text):
            return True
    return False


def controlled(robot: Robot) -> bool:
    """Whether ``robot`` is written for ros2_control or ros_control: it has a
    ``<ros2_control>`` or ``<transmission>`` element."""
    return any(text.startswith(("<ros2_control", "<transmission")) for text in robot.extras)


_GAZEBO = re.compile(r"<gazebo[\s/>]")
# The hardware plugins of ros2_control that run the robot in Gazebo (classic, Ignition, Sim).
_GAZEBO_HARDWARE = re.compile(r"<plugin>\s*(?:gazebo|gz|ign)_ros2_control/")


def _with(control: Reference, interfaces: Iterable[Interface]) -> Reference:
    return Reference(
        control.name, control.target, control.context, control.source, tuple(interfaces)
    )


def _names(text: str | None, target: Target) -> Iterator[str]:
    """The names in a plugin element's text: comma-separated for joints (ROS 1's
    ``<jointName>a, b</jointName>``); a frame's leading ``/`` (ROS 1's global names) is not
    part of it, and a name with a namespace (``robot1/base_link``) cannot be judged."""
    for part in (text or "").split(",") if target is Target.JOINT else [text or ""]:
        name = part.strip()
        if target is Target.LINK:
            name = name.lstrip("/")
            if "/" in name:
                continue
        if name and "$" not in name and not (target is Target.LINK and name in _WORLD_FRAMES):
            yield name
