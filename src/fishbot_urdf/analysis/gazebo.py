"""The robot's ``<gazebo>`` and ``<ros2_control>`` blocks, read once: their elements, what
they refer to and where they are written, for the checks, the drawings and the converters."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

from lxml import etree

from ..errors import FishbotUrdfError
from ..extensions import Reference
from ..model import Joint, JointType, Link, Location, Robot
from ..spatial import Pose
from ..xml.source import parse_xml
from .topology import Topology

__all__ = [
    "Block",
    "Landing",
    "Lumping",
    "blocks",
    "lumping",
    "number",
    "place",
    "plugins",
    "text",
    "texts",
]


@dataclass(frozen=True, slots=True)
class Block:
    """One top-level ``<gazebo>`` or ``<ros2_control>`` element.

    Attributes:
        element: The element, read again from the robot's text.
        reference: Its ``reference`` (None for a block about the whole robot).
        where: Where it is written, when the reader gave places.
        places: Where each element in it is written, in document order (empty when the
            reader gave no places).
    """

    element: etree._Element
    reference: str | None
    where: Location | None
    places: tuple[Location | None, ...] = ()

    def place_of(self, element: etree._Element) -> Location | None:
        """Where ``element`` (inside this block) is written, if the reader said."""
        if not self.places:
            return None
        for index, node in enumerate(self.element.iter(etree.Element)):
            if node is element:
                return self.places[index] if index < len(self.places) else None
        return None


def blocks(robot: Robot, references: tuple[Reference, ...]) -> tuple[Block, ...]:
    """Every ``<gazebo>`` and ``<ros2_control>`` element of ``robot``, in file order, placed
    by the places of ``references`` (the names they give)."""
    places = _places(references)
    # each <gazebo reference> gives one reference, in file order: the k-th block naming a
    # part is placed at the k-th reference to it
    named: dict[str, list[Location]] = {}
    for ref in references:
        if ref.context == "<gazebo reference>" and ref.source is not None:
            named.setdefault(ref.name, []).append(ref.source)
    seen: dict[str, int] = {}
    found: list[Block] = []
    for index, text in enumerate(robot.extras):
        if not text.startswith(("<gazebo", "<ros2_control")):
            continue
        try:
            element = parse_xml(text.encode("utf-8"))
        except FishbotUrdfError:  # the reader kept it, so it was well-formed once
            continue
        if element.tag not in ("gazebo", "ros2_control"):
            continue
        reference = element.get("reference") if element.tag == "gazebo" else None
        given = robot.extra_places[index] if index < len(robot.extra_places) else ()
        where = None
        if reference is not None:
            count = seen[reference] = seen.get(reference, -1) + 1
            at = named.get(reference, [])
            where = at[count] if count < len(at) else None
        if where is None and given:
            where = given[0]
        if where is None:
            where = _first_place(element, places)
        found.append(Block(element, reference, where, given))
    return tuple(found)


def plugins(block: Block) -> Iterator[etree._Element]:
    """The ``<plugin>`` elements with a ``filename`` in a ``<gazebo>`` block, sensors' too."""
    if block.element.tag == "gazebo":
        yield from (p for p in block.element.iter("plugin") if p.get("filename"))


def place(
    references: tuple[Reference, ...], block: Block, element: etree._Element
) -> Location | None:
    """Where ``element`` of ``block`` is written: its own place when the reader gave it,
    else as near as the places of ``references`` say (a name inside it), else the block."""
    return block.place_of(element) or _first_place(element, _places(references)) or block.where


def number(element: etree._Element, path: str) -> float | None:
    """The number at ``path`` under ``element`` (``range/min``), None when it is not written
    or is no finite number (a xacro expression left unexpanded)."""
    found = element.find(path)
    if found is None or found.text is None:
        return None
    try:
        value = float(found.text.strip())
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def text(element: etree._Element, tag: str) -> str | None:
    """The stripped text of ``element``'s first ``<tag>`` child, if written."""
    found = element.find(tag)
    if found is None or found.text is None:
        return None
    return found.text.strip() or None


def texts(element: etree._Element, tag: str) -> list[str]:
    """The stripped texts of every ``<tag>`` child of ``element``, in order."""
    return [(child.text or "").strip() for child in element.findall(tag)]


def _places(references: tuple[Reference, ...]) -> dict[tuple[str, str | None], Location]:
    places: dict[tuple[str, str | None], Location] = {}
    for ref in references:
        if ref.source is not None:
            places.setdefault((ref.context, ref.name), ref.source)
    return places


def _first_place(
    element: etree._Element, places: dict[tuple[str, str | None], Location]
) -> Location | None:
    for node in element.iter(etree.Element):
        if not isinstance(node.tag, str):
            continue
        key = (f"plugin <{node.tag}>", (node.text or "").strip().lstrip("/"))
        if key in places:
            return places[key]
    return None


@dataclass(frozen=True, slots=True)
class Landing:
    """Where sdformat's converter puts one link of the robot.

    Attributes:
        link: The link of the SDF model it becomes part of: itself when it stays a link,
            the first link up that no lumped fixed joint holds when it is lumped.
        pose: Its frame in ``link``'s frame (identity when it stays a link).
        joint: The fixed joint that lumps it into the link above it (None when it stays a
            link); the joints above that one lump that link in turn.
    """

    link: str
    pose: Pose
    joint: Joint | None = None


@dataclass(frozen=True, slots=True)
class Lumping:
    """What sdformat's URDF converter (sdformat 12, `ign sdf -p`) does to the robot's links
    before Gazebo sees them.

    Attributes:
        landings: Each link the root reaches, by name, and where it lands.
        dropped: For each link the converter stops at for lack of mass, the links lost
            with it, in tree order: a link it keeps with no mass (lumped parts' included)
            is lost with everything below it; below a lumped link with no mass of its own,
            every link that is not lumped into the same link is lost (the converter does
            not go on down the tree from it). Links lost below such a link are not keys of
            their own.
        preserved: Fixed joints kept as joints (``<preserveFixedJoint>`` on the joint).
        revolute: Fixed joints written as revolute joints held at 0
            (``<disableFixedJointLumping>`` on the joint, without ``preserveFixedJoint``).
        ignored: ``<gazebo reference>`` blocks with ``preserveFixedJoint`` or
            ``disableFixedJointLumping`` whose reference is no fixed joint, by reference
            (the converter reads them only on a fixed joint's name; on a link they do
            nothing).
    """

    landings: Mapping[str, Landing]
    dropped: Mapping[str, tuple[str, ...]]
    preserved: frozenset[str]
    revolute: frozenset[str]
    ignored: Mapping[str, Block]

    def lumped(self, link: str) -> bool:
        """True when ``link`` is merged into another link."""
        landing = self.landings.get(link)
        return landing is not None and landing.link != link

    def lost(self) -> frozenset[str]:
        """Every link the converter leaves out."""
        return frozenset(name for names in self.dropped.values() for name in names)


def _flag(block: Block, tag: str) -> bool:
    """The converter's reading of a ``<tag>`` switch in ``block`` (its ``value`` attribute,
    else its text; true, yes or 1, in any case)."""
    found = block.element.find(tag)
    if found is None:
        return False
    value = found.get("value")
    if value is None:
        value = found.text or ""
    value = value.strip()
    return value.lower() in ("true", "yes") or value == "1"


def lumping(
    blocks: tuple[Block, ...],
    topology: Topology,
    links: Mapping[str, Link],
    joints: Mapping[str, Joint],
    root: str,
) -> Lumping:
    """Where sdformat's converter puts each link reached from ``root``: fixed joints lumped
    unless a ``<gazebo reference>`` on the joint keeps them, links whose lumped mass is 0
    (within 1e-6 kg) or who have none left out with all below them."""
    preserved: set[str] = set()
    revolute: set[str] = set()
    ignored: dict[str, Block] = {}
    for block in blocks:
        if block.element.tag != "gazebo" or block.reference is None:
            continue
        keep, disable = _flag(block, "preserveFixedJoint"), _flag(block, "disableFixedJointLumping")
        if not (keep or disable):
            continue
        joint = joints.get(block.reference)
        if joint is None or joint.type is not JointType.FIXED:
            ignored.setdefault(block.reference, block)
        elif keep:
            preserved.add(joint.name)
        else:
            revolute.add(joint.name)
    revolute -= preserved

    def lumped(joint: Joint) -> bool:
        return (
            joint.type is JointType.FIXED
            and joint.parent != "world"
            and joint.name not in preserved
            and joint.name not in revolute
        )

    landings: dict[str, Landing] = {root: Landing(root, Pose())}
    parents: dict[str, Joint] = {}
    order = [root]
    stack = [root]
    while stack:
        name = stack.pop()
        here = landings[name]
        below = [j for j in topology.children.get(name, ()) if j.child not in landings]
        for joint in below:
            if lumped(joint):
                landing = Landing(here.link, here.pose.then(Pose.of(joint.origin)), joint)
            else:
                landing = Landing(joint.child, Pose())
            landings[joint.child] = landing
            parents[joint.child] = joint
            order.append(joint.child)
        stack.extend(j.child for j in reversed(below))
    # each link's mass with the masses lumped into it: the converter lumps a link's fixed
    # subtree into it before lumping it into its parent
    mass: dict[str, float] = {}
    for name in reversed(order):
        inertial = links[name].inertial if name in links else None
        if inertial is not None:
            mass[name] = mass.get(name, 0.0) + inertial.mass
        joint = parents.get(name)
        if name in mass and joint is not None and lumped(joint):
            mass[joint.parent] = mass.get(joint.parent, 0.0) + mass[name]
    dropped: dict[str, tuple[str, ...]] = {}
    lost: set[str] = set()
    # links walked below a lumped link with no mass: lost, or lumped with no mass into the
    # same link (masses are summed upwards), so that what they would lose is lost already;
    # each link is walked once, not once for each massless link above it
    walked: set[str] = set()
    for name in order:  # from the root outwards: the first link it stops at holds the rest
        if name in lost or name in walked or name == "world":
            continue
        held = landings[name].link
        weight = mass.get(name)
        if weight is not None and abs(weight) > 1e-6:
            continue
        # the converter goes no further down the tree than a link with no mass; one it
        # lumped has already given its fixed subtree to the link it lumped into
        subtree = [name]
        for link in subtree:  # the tree the landings were found on (a loop is walked once)
            subtree.extend(
                j.child for j in topology.children.get(link, ()) if parents.get(j.child) is j
            )
        gone = tuple(n for n in subtree if held == name or landings[n].link != held)
        if held != name:
            walked.update(subtree)
        if gone:
            lost.update(gone)
            dropped[name] = gone
    return Lumping(landings, dropped, frozenset(preserved), frozenset(revolute), ignored)
