"""The top of the reader: <robot> and the elements directly inside it."""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable

from lxml import etree

from ..catalog.reading import NO_ROBOT, ROBOT_NAME, ROBOT_VERSION
from ..diagnostics import Kind, Subject
from ..extensions import TAGS, collect
from ..inputs import deadline
from ..model import Joint, Link, Location, Material, Robot
from ._base import xml_text
from ._joints import JointReader

# urdfdom reads "MAJOR.MINOR" as two integers and supports only 1.0 ("1.00" and "01.0" too).
_VERSION = re.compile(r"\s*\+?([0-9]+)\.\+?([0-9]+)")


class Reader(JointReader):
    """Builds a Robot from the lxml tree, collecting findings as it goes."""

    def robot(self, el: etree._Element, children: Iterable[etree._Element]) -> Robot | None:
        """The robot of root element ``el``, whose ``children`` are handed out in order."""
        at = self.locator.locate(el)
        if el.tag != "robot":
            self.error(
                NO_ROBOT,
                f"the root element is <{el.tag}>, not <robot>",
                at,
                'a URDF file holds one <robot name="..."> element',
            )
            return None
        name = el.get("name")
        whole = self.subject = Subject(Kind.ROBOT, name or "")
        if not name:
            self.error(ROBOT_NAME, "<robot> has no name", at, 'write <robot name="my_robot">')
        version = el.get("version")
        parts = _VERSION.fullmatch(version) if version is not None else None
        if version is not None and (parts is None or (int(parts[1]), int(parts[2])) != (1, 0)):
            self.error(
                ROBOT_VERSION,
                f'<robot version="{version}"> is not a URDF version this tool knows',
                self.locator.attribute(at, "version"),
                'use version="1.0" or leave the attribute out',
            )
        links: list[Link] = []
        joints: list[Joint] = []
        materials: list[Material] = []
        extras: list[str] = []
        places: list[tuple[Location | None, ...]] = []
        locate = self.locator.locate
        until = deadline()
        for index, child in enumerate(children):
            if not index & 4095:
                until.check("reading the robot")
            self.subject = whole
            tag = child.tag
            if tag == "link":
                links.append(self.link(child, locate(child)))
            elif tag == "joint":
                joints.append(self.joint(child, locate(child)))
            elif tag == "material":
                materials.append(self.material(child, locate(child), whole))
            elif tag in TAGS:  # read for the names it gives to links and joints
                extras.append(xml_text(child))
                found: list[Location | None] = []
                self.references.extend(
                    collect(child, _recording(locate, found), self.locator.attribute)
                )
                places.extend([()] * (len(extras) - 1 - len(places)))
                places.append(tuple(found))
            elif isinstance(tag, str):
                extras.append(self.extra(child))
        return Robot(
            name or "",
            tuple(links),
            tuple(joints),
            tuple(materials),
            version,
            tuple(extras),
            at,
            tuple(places),
        )


def _recording(
    locate: Callable[[etree._Element], Location | None], found: list[Location | None]
) -> Callable[[etree._Element], Location | None]:
    """``locate``, keeping each place it gives in ``found``."""

    def recording(node: etree._Element) -> Location | None:
        at = locate(node)
        found.append(at)
        return at

    return recording
