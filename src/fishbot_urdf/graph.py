"""Tree queries over a robot's topology (built by `fishbot_urdf.analysis`): the root, subtrees,
chains, check_urdf's tree text, and networkx export.

Nothing here recurses per tree level, so a 10 000-deep chain is fine. networkx is imported
only by ``to_networkx``.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from .analysis import Analysis
from .analysis.topology import Topology, single_root, topology
from .errors import StructureError, UnknownNameError
from .model import Joint, Robot

if TYPE_CHECKING:
    import networkx as nx


__all__ = [
    "Topology",
    "chain",
    "leaves",
    "root",
    "subtree",
    "to_networkx",
    "topology",
    "tree_text",
]


def _parts(robot: Robot | Analysis) -> tuple[Robot, Topology]:
    """The robot and its topology, from a robot or its analysis."""
    if isinstance(robot, Robot):
        return robot, topology(robot)
    return robot.robot, robot.topology


def root(robot: Robot | Analysis) -> str:
    """The name of the root link (the one link that is no joint's child).

    Raises:
        StructureError: There is no root, or more than one.
    """
    return single_root(*_parts(robot))


def tree_text(robot: Robot | Analysis) -> Iterator[str]:
    """Yield check_urdf's output for a robot with one root, piece by piece.

    Join the pieces to get it all. It is written whatever else is wrong with the robot.

    The pieces are the header and one line per link, each ending in a newline; a link
    appears once for every path to it, as in check_urdf.

    Raises:
        StructureError: There is no single root, or a joint loop is reached from it (the
            tree would never end).
    """
    model, topo = _parts(robot)
    top = single_root(model, topo)
    if topo.loop_from_root:
        raise StructureError(f"robot {model.name!r} has a joint loop below its root")
    return _tree_lines(model, topo, top)


def _tree_lines(robot: Robot, topo: Topology, top: str) -> Iterator[str]:
    yield f"robot name is: {robot.name}\n"
    yield "---------- Successfully Parsed XML ---------------\n"
    yield f"root Link: {top} has {len(topo.children[top])} child(ren)\n"
    # Depth-first, children by joint name, with an explicit stack of (joints, next index).
    # Each line's indentation is made for it and dropped: keeping one string per depth
    # would hold depth^2 / 2 spaces (30,000 links deep: 1.8 GB).
    stack: list[tuple[tuple[Joint, ...], int]] = [(topo.children[top], 0)]
    while stack:
        joints, index = stack[-1]
        if index == len(joints):
            stack.pop()
            continue
        stack[-1] = (joints, index + 1)
        child = joints[index].child
        yield f"{'    ' * len(stack)}child({index + 1}):  {child}\n"
        grandchildren = topo.children[child]
        if grandchildren:
            stack.append((grandchildren, 0))


def _known(topo: Topology, name: str) -> None:
    if name not in topo.children:
        raise UnknownNameError("link", name, topo.children)


def subtree(robot: Robot | Analysis, link: str) -> list[str]:
    """``link`` and every link below it, depth-first with children ordered by joint name.

    Raises:
        UnknownNameError: The robot has no link ``link``.
    """
    _, topo = _parts(robot)
    _known(topo, link)
    order: list[str] = []
    seen: set[str] = set()
    stack = [link]
    while stack:
        name = stack.pop()
        if name in seen:
            continue
        seen.add(name)
        order.append(name)
        stack.extend(j.child for j in reversed(topo.children[name]))
    return order


def leaves(robot: Robot | Analysis) -> list[str]:
    """Links that are no joint's parent, in file order."""
    model, topo = _parts(robot)
    return [link.name for link in model.links if not topo.children[link.name]]


def chain(robot: Robot | Analysis, start: str, end: str) -> list[str]:
    """The links on the path from ``start`` to ``end`` (both included).

    The path goes up from ``start`` to the nearest common ancestor and down to ``end``.

    Raises:
        UnknownNameError: A link name is not in the robot.
        StructureError: The two links are not connected.
    """
    _, topo = _parts(robot)
    for name in (start, end):
        _known(topo, name)

    def ancestors(name: str) -> list[str]:
        path = [name]
        seen = {name}
        while topo.parents[path[-1]]:
            up = topo.parents[path[-1]][0].parent
            if up in seen:
                break
            seen.add(up)
            path.append(up)
        return path

    up_from_start = ancestors(start)
    up_from_end = ancestors(end)
    index = {name: i for i, name in enumerate(up_from_start)}
    for j, name in enumerate(up_from_end):
        if name in index:
            return up_from_start[: index[name] + 1] + list(reversed(up_from_end[:j]))
    raise StructureError(f"links {start!r} and {end!r} are not connected")


def to_networkx(robot: Robot | Analysis) -> nx.MultiDiGraph[str]:
    """A MultiDiGraph with a node per link and an edge parent -> child per joint.

    Node attributes: ``link`` (the Link). Edges are keyed by joint name, with attributes
    ``joint`` (the Joint) and ``type`` (the JointType value):
    ``graph.edges["base_link", "imu_link", "imu_joint"]["joint"]``. Links come in file
    order and each link's out-edges in joint-name order, which is urdfdom's order of
    children, so a depth-first search visits the tree as check_urdf prints it. The graph
    attribute ``name`` is the robot's name.

    Nothing is dropped, so a faulty robot can be inspected too: a joint naming a link that
    does not exist adds a node without a ``link`` attribute, and two joints between the
    same links are two edges.
    """
    import networkx as nx  # ~200 ms to import: only when asked for

    model = robot if isinstance(robot, Robot) else robot.robot
    graph: nx.MultiDiGraph[str] = nx.MultiDiGraph(name=model.name)
    for link in model.links:
        graph.add_node(link.name, link=link)
    for joint in sorted(model.joints, key=lambda joint: joint.name):
        graph.add_edge(
            joint.parent, joint.child, key=joint.name, joint=joint, type=joint.type.value
        )
    return graph
