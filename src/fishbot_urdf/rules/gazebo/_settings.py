"""Values in ``<gazebo>`` blocks that sdformat 12 refuses: a setting its URDF converter reads
as a number that is none (it crashes), and a value its reader refuses for its element's type
or bounds (it refuses the file)."""

from __future__ import annotations

from collections.abc import Iterator

from ...analysis import Analysis
from ...analysis.gazebo import Block, Lumping
from ...analysis.sdformat import (
    NUMBERS,
    SETTINGS,
    TEXTS,
    WHOLE,
    Description,
    Node,
    allowed,
    bounds,
    children,
    describe,
    refusal,
    refusals,
    stod,
    stoi,
)
from ...catalog.gazebo import GAZEBO_SETTING
from ...diagnostics import Diagnostic, Kind, Subject
from ...errors import FishbotUrdfError
from ...model import JointType

__all__ = ["settings"]

_CRASH = "sdformat's URDF converter crashes on it (std::invalid_argument), so Gazebo cannot load it"
_REFUSED = "sdformat's reader refuses the robot, so Gazebo cannot load it"
_Found = list[tuple[Node, str]]


def settings(analysis: Analysis, block: Block) -> Iterator[Diagnostic]:
    """A finding for each value of ``block`` that sdformat crashes on or refuses."""
    if block.element.tag != "gazebo":
        return
    try:
        lumping = analysis.gazebo_lumping
    except FishbotUrdfError:  # no single root: the structure rules' finding, and urdfdom's
        return  # refusal before the converter reads a block
    reference = block.reference
    head = f"<gazebo reference={reference!r}>" if reference is not None else "<gazebo>"
    lands = _lands(analysis, lumping, reference)
    subject = _subject(analysis, reference)
    for child in block.element:
        if isinstance(child.tag, str):
            for element, message in _setting(child, lands):
                yield GAZEBO_SETTING.report(
                    f"{head}: {message}",
                    block.place_of(element) or block.where,
                    path=analysis.path,
                    subject=subject,
                )


def _setting(child: Node, lands: frozenset[str]) -> _Found:
    """The refused values of one element of a block whose elements the converter writes into
    the SDF elements ``lands`` names (``link.sdf``, ``collision.sdf``, ...)."""
    tag, value = child.tag, _key_value(child)
    if tag in NUMBERS or tag in WHOLE:
        path = NUMBERS[tag] if tag in NUMBERS else WHOLE[tag]
        number = stod(value) if tag in NUMBERS else stoi(value)
        what = "a number" if tag in NUMBERS else "a whole number"
        if number is None:
            return [(child, f"<{tag}> is {value!r}, not {what}: {_CRASH} (write {what})")]
        described = describe(*path) if path[0] in lands else None
        why = bounds(described, number) if described is not None else None
        if described is None or why is None:
            return []
        return [(child, f"<{tag}> {value!r} {why}: {_REFUSED} (write {allowed(described)})")]
    if tag in TEXTS:
        described = describe(*TEXTS[tag]) if TEXTS[tag][0] in lands and value else None
        why = refusal(described, value) if described is not None else None
        if described is None or why is None:
            return []
        return [(child, f"<{tag}> {value!r} {why}: {_REFUSED} (write {allowed(described)})")]
    if tag in SETTINGS:
        return []  # a flag or a name, which the converter never refuses
    if tag in ("collision", "visual"):
        parent = describe(f"{tag}.sdf") if f"{tag}.sdf" in lands else None
        if parent is None:
            return []
        return [found for blob in child for found in _below(blob, parent)]
    for file in ("link.sdf", "joint.sdf", "model.sdf"):
        parent = describe(file) if file in lands else None
        if parent is not None:
            return _below(child, parent)
    return []


def _below(element: Node, parent: Description) -> _Found:
    """The refused values at and below ``element``, which the converter copies into an
    element of ``parent`` (none in an element the reader does not know, which it copies as
    it is)."""
    if not isinstance(element.tag, str):
        return []
    known = {d["name"]: d for d in reversed(children(parent))}
    if element.tag not in known:
        return []
    found: _Found = []
    for refused in refusals(element, known[element.tag]):
        node = refused.element
        text = (node.text or "").strip()
        shown = f"<{node.tag}> {text!r}" if text else f"<{node.tag}>"
        found.append((node, f"{shown} {refused.why}: {_REFUSED} (write {refused.allowed})"))
    return found


def _key_value(element: Node) -> str:
    """A setting's text as the converter reads it: its ``value`` attribute, else its text."""
    value = element.get("value")
    if value is None:
        value = element.text if element.text is not None and not len(element) else ""
    return str(value).strip()


def _lands(analysis: Analysis, lumping: Lumping, reference: str | None) -> frozenset[str]:
    """The SDF elements the converter writes the block's elements into: the model's for a
    block with no reference; a kept link's (and its collisions' and visuals', when it has
    some) or a joint's it writes; none for a name it drops or does not know."""
    if reference is None:
        return frozenset({"model.sdf"})
    lost = {name for names in lumping.dropped.values() for name in names} | set(lumping.dropped)
    link = analysis.links.get(reference)
    if link is not None:
        if reference not in lumping.landings or reference in lost:
            return frozenset()
        shapes = {"collision.sdf"} if link.collisions else set()
        shapes |= {"visual.sdf"} if link.visuals else set()
        return frozenset({"link.sdf", *shapes})
    joint = analysis.joints.get(reference)
    if joint is None or joint.child in lost or joint.child not in lumping.landings:
        return frozenset()
    if joint.type == JointType.FIXED and reference not in lumping.preserved | lumping.revolute:
        return frozenset()
    return frozenset({"joint.sdf"})


def _subject(analysis: Analysis, reference: str | None) -> Subject:
    if reference is not None and reference in analysis.links:
        return Subject(Kind.LINK, reference)
    if reference is not None and reference in analysis.joints:
        return Subject(Kind.JOINT, reference)
    return Subject(Kind.ROBOT, analysis.robot.name)
