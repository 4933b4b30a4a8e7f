"""The robot's ``<gazebo>`` and ``<ros2_control>`` blocks, read once: their elements, what
they refer to and where they are written, for the checks, the drawings and the converters."""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

from lxml import etree

from ..errors import FishbotUrdfError
from ..extensions import Reference
from ..model import Location, Robot
from ..xml.source import parse_xml

__all__ = ["Block", "blocks", "number", "place", "plugins", "text", "texts"]


@dataclass(frozen=True, slots=True)
class Block:
    """One top-level ``<gazebo>`` or ``<ros2_control>`` element.

    Attributes:
        element: The element, read again from the robot's text.
        reference: Its ``reference`` (None for a block about the whole robot).
        where: Where it is written, when the reader gave the place of one of its names.
    """

    element: etree._Element
    reference: str | None
    where: Location | None


def blocks(robot: Robot, references: tuple[Reference, ...]) -> tuple[Block, ...]:
    """Every ``<gazebo>`` and ``<ros2_control>`` element of ``robot``, in file order, placed
    by the places of ``references`` (the names they give)."""
    places = _places(references)
    found: list[Block] = []
    for text in robot.extras:
        if not text.startswith(("<gazebo", "<ros2_control")):
            continue
        try:
            element = parse_xml(text.encode("utf-8"))
        except FishbotUrdfError:  # the reader kept it, so it was well-formed once
            continue
        if element.tag not in ("gazebo", "ros2_control"):
            continue
        reference = element.get("reference") if element.tag == "gazebo" else None
        where = places.get(("<gazebo reference>", reference)) if reference is not None else None
        if where is None:
            where = _first_place(element, places)
        found.append(Block(element, reference, where))
    return tuple(found)


def plugins(block: Block) -> Iterator[etree._Element]:
    """The ``<plugin>`` elements with a ``filename`` in a ``<gazebo>`` block, sensors' too."""
    if block.element.tag == "gazebo":
        yield from (p for p in block.element.iter("plugin") if p.get("filename"))


def place(
    references: tuple[Reference, ...], block: Block, element: etree._Element
) -> Location | None:
    """Where ``element`` of ``block`` is written, as near as the places of ``references``
    say: a name inside it, else the block."""
    return _first_place(element, _places(references)) or block.where


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
