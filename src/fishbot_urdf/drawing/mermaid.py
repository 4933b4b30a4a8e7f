"""Robot -> a Mermaid flowchart, which GitHub and GitLab draw inside Markdown."""

from __future__ import annotations

from collections.abc import Iterator

from ..analysis import Analysis
from ..model import Robot, Vector3
from .layout import JOINT_COLORS, Drawing, drawing, joint_facts, link_facts

__all__ = ["to_mermaid"]

# Mermaid reads these characters as syntax even inside a quoted label: write them as its
# entity codes.
_ENTITIES = str.maketrans(
    {
        "#": "#35;",
        "%": "#37;",
        '"': "#quot;",
        "&": "#amp;",
        "<": "#lt;",
        ">": "#gt;",
        "|": "#124;",
        "`": "#96;",
    }
)


def to_mermaid(robot: Robot | Analysis, detail: bool = False) -> str:
    """The robot's kinematic tree as a Mermaid flowchart (`flowchart TD`).

    The same drawing as ``to_dot``: links as boxes, joints as rounded nodes, each joint's
    origin on the edge from its parent; links the root does not reach are dashed red, links
    a joint names but nobody defines dotted red. Wrap it in a ```mermaid block in Markdown.
    """
    return "".join(_lines(drawing(robot), detail))


def _text(text: str) -> str:
    return text.translate(_ENTITIES).replace("\n", "<br>")


def _lines(plan: Drawing, detail: bool) -> Iterator[str]:
    yield "flowchart TD\n"
    ids = {name: f"L{i}" for i, name in enumerate(plan.links)}
    for name in plan.links:
        link = plan.defined[name]
        label = name if not detail or link is None else "\n".join([name, *link_facts(link)])
        if link is None:
            label += "\n(not defined)"
        elif name in plan.unreachable:
            label += "\n(not reached from the root)"
        yield f'    {ids[name]}["{_text(label)}"]\n'
    for i, edge in enumerate(plan.edges):
        joint = edge.joint
        label = "\n".join([edge.name, *joint_facts(joint)]) if detail else edge.name
        # As written (urdf_to_graphviz's recovered rpy, with its -0, is DOT's to copy).
        xyz, rpy = _plain(joint.origin.xyz), _plain(joint.origin.rpy)
        yield f'    J{i}(["{_text(label)}"])\n'
        yield f'    {ids[edge.parent]} -->|"xyz: {xyz}<br>rpy: {rpy}"| J{i}\n'
        yield f"    J{i} --> {ids[edge.child]}\n"
    groups: dict[str, list[str]] = {}
    for i, edge in enumerate(plan.edges):
        groups.setdefault(edge.joint.type.value if detail else "joint", []).append(f"J{i}")
    for name in plan.links:
        if plan.defined[name] is None:
            groups.setdefault("undefined", []).append(ids[name])
        elif name in plan.unreachable:
            groups.setdefault("unreachable", []).append(ids[name])
    styles = {kind.value: f"stroke:{color},color:{color}" for kind, color in JOINT_COLORS.items()}
    styles["joint"] = "stroke:blue,color:blue"
    styles["unreachable"] = "stroke:red,color:red,stroke-dasharray:6 3"
    styles["undefined"] = "stroke:red,color:red,stroke-dasharray:2 2"
    for group, members in groups.items():
        yield f"    classDef {group} {styles[group]}\n"
        yield f"    class {','.join(members)} {group}\n"


def _plain(values: Vector3) -> str:
    """Numbers as %g writes them, with no negative zero."""
    return " ".join(f"{v + 0.0:g}" for v in values)
