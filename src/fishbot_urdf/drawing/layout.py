"""What a drawing of a robot's link tree shows, and in which order: the plan that the DOT
and the Mermaid texts are both written from."""

from __future__ import annotations

from dataclasses import dataclass

from ..analysis import Analysis, of
from ..model import Joint, JointType, Link, Robot, Vector3

__all__ = ["JOINT_COLORS", "Drawing", "Edge", "drawing", "joint_facts", "link_facts", "numbers"]

#: Joint colours of the detailed drawing (names both Graphviz and CSS know).
JOINT_COLORS = {
    JointType.REVOLUTE: "blue",
    JointType.CONTINUOUS: "darkgreen",
    JointType.PRISMATIC: "darkorange",
    JointType.FIXED: "dimgray",
    JointType.FLOATING: "purple",
    JointType.PLANAR: "brown",
}


@dataclass(frozen=True, slots=True)
class Edge:
    """One joint as drawn: its parent and child link, and its DOT node id."""

    parent: str
    child: str
    joint: Joint
    node: str

    @property
    def name(self) -> str:
        """The joint's name (the node's label)."""
        return self.joint.name


@dataclass(frozen=True, slots=True)
class Drawing:
    """What a drawing shows, in drawing order, worked out once from the robot.

    Attributes:
        links: Link names in urdf_to_graphviz's order (depth-first from the root, children
            by joint name), then the other trees and the links only loops reach.
        edges: The joints in the same depth-first order.
        defined: For each link name, its Link, or None when a joint names a missing link.
        unreachable: Links the root does not reach (all of them when there is no root).
    """

    links: tuple[str, ...]
    edges: tuple[Edge, ...]
    defined: dict[str, Link | None]
    unreachable: frozenset[str]


def drawing(robot: Robot | Analysis) -> Drawing:
    """Work out what to draw and in which order, in time linear in the robot's size.

    Every link and joint is drawn, so a faulty robot can be looked at too: a joint naming a
    link that does not exist draws that link (``defined`` None), a joint named twice between
    the same links once (the later one), joints from a link in joint-name order.
    """
    analysis = of(robot)
    model = analysis.robot
    defined: dict[str, Link | None] = {}
    for link in model.links:
        defined[link.name] = link  # a name given twice keeps its place and its last link
    # parent -> child -> joint name -> joint, each in the order first met
    adjacency: dict[str, dict[str, dict[str, Joint]]] = {}
    for joint in sorted(model.joints, key=_joint_name):
        defined.setdefault(joint.parent, None)
        defined.setdefault(joint.child, None)
        adjacency.setdefault(joint.parent, {}).setdefault(joint.child, {})[joint.name] = joint
    children: dict[str, list[tuple[str, str, Joint]]] = {name: [] for name in defined}
    parents: dict[str, int] = dict.fromkeys(defined, 0)
    for parent, keyed in adjacency.items():
        for child, joints in keyed.items():
            for key, joint in joints.items():
                children[parent].append((child, key, joint))
                parents[child] += 1
    # As in urdfdom's tree: a joint from a missing link or from the link itself is no parent.
    roots = list(analysis.topology.roots)
    # The root's tree first, then the other trees, then links only loops reach.
    starts = [*roots, *(n for n, count in parents.items() if not count), *defined]
    links: list[str] = []
    order: list[tuple[str, str, str, Joint]] = []
    seen: set[str] = set()
    reached: frozenset[str] | None = None
    for start in starts:
        if start in seen:
            continue
        seen.add(start)
        links.append(start)
        stack = [(start, iter(children[start]))]
        while stack:
            parent, below = stack[-1]
            for child, key, joint in below:
                order.append((parent, child, key, joint))
                if child not in seen:
                    seen.add(child)
                    links.append(child)
                    stack.append((child, iter(children[child])))
                    break
            else:
                stack.pop()
        if reached is None:
            reached = frozenset(links) if roots else frozenset()
    taken = set(defined)
    edges = []
    for parent, child, key, joint in order:
        node = key
        count = 0
        while node in taken:  # a joint named like a link (or a duplicate joint name)
            count += 1
            node = f"{key} (joint)" if count == 1 else f"{key} (joint {count})"
        taken.add(node)
        edges.append(Edge(parent, child, joint, node))
    return Drawing(
        links=tuple(links),
        edges=tuple(edges),
        defined=defined,
        unreachable=frozenset(links) - (reached or frozenset()),
    )


def _joint_name(joint: Joint) -> str:
    return joint.name


def numbers(values: Vector3) -> str:
    # C++ iostream's default for a double is printf's %g: 6 significant digits.
    return " ".join(f"{v:g}" for v in values)


def link_facts(link: Link) -> list[str]:
    visuals, collisions = len(link.visuals), len(link.collisions)
    facts = [
        f"{visuals} visual{'' if visuals == 1 else 's'}, "
        f"{collisions} collision{'' if collisions == 1 else 's'}"
    ]
    facts.append("no inertial" if link.inertial is None else f"mass {link.inertial.mass:g} kg")
    return facts


def joint_facts(joint: Joint) -> list[str]:
    facts = [joint.type.value]
    if joint.type.uses_axis:
        facts.append(f"axis {numbers(joint.axis)}")
    limit = joint.limit
    if limit is not None:
        span = f"{limit.lower:g} .. {limit.upper:g}, " if joint.type.needs_limit else ""
        facts.append(f"limit {span}effort {limit.effort:g}, velocity {limit.velocity:g}")
    if joint.mimic is not None:
        mimic = joint.mimic
        facts.append(f"mimic {mimic.joint} x{mimic.multiplier:g} {mimic.offset:+g}")
    return facts
