"""How a robot's links hang together, as urdfdom builds it: the first fact the analysis
derives, in time linear in the robot's size."""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import StructureError
from ..model import Joint, Robot

__all__ = ["Topology", "single_root", "topology"]


@dataclass(frozen=True, slots=True)
class Topology:
    """How the links hang together, as urdfdom builds it, whatever the robot's faults.

    Attributes:
        children: For each link name, the joints whose parent it is, ordered by joint name
            (urdfdom keeps joints in a map keyed by name, so that is check_urdf's order).
        parents: For each link name, every joint whose child it is, in file order.
        roots: Links that are no joint's child, in file order.
        reachable: Links reachable from ``roots[0]`` (empty when there is no root).
        loop_from_root: True when a joint loop can be reached from ``roots[0]``: its tree
            never ends (check_urdf prints it until it crashes).
    """

    children: dict[str, tuple[Joint, ...]]
    parents: dict[str, tuple[Joint, ...]]
    roots: tuple[str, ...]
    reachable: frozenset[str]
    loop_from_root: bool = False

    @property
    def root(self) -> str | None:
        """The single root, or None when there is none or more than one."""
        return self.roots[0] if len(self.roots) == 1 else None


def topology(robot: Robot) -> Topology:
    """Analyse the joint structure of ``robot`` in time linear in its size."""
    names = [link.name for link in robot.links]
    known = set(names)
    children: dict[str, list[Joint]] = {name: [] for name in names}
    parents: dict[str, list[Joint]] = {name: [] for name in names}
    for joint in robot.joints:
        # A joint from a link to itself is no edge of the tree (check reports it).
        if joint.parent in known and joint.child in known and joint.parent != joint.child:
            children[joint.parent].append(joint)
            parents[joint.child].append(joint)
    sorted_children = {
        name: tuple(sorted(joints, key=_joint_name)) if len(joints) > 1 else tuple(joints)
        for name, joints in children.items()
    }
    roots = tuple(dict.fromkeys(name for name in names if not parents[name]))
    reachable, loop = _reach(roots[0], sorted_children) if roots else (set(), False)
    return Topology(
        children=sorted_children,
        parents={name: tuple(joints) for name, joints in parents.items()},
        roots=roots,
        reachable=frozenset(reachable),
        loop_from_root=loop,
    )


def _reach(top: str, children: dict[str, tuple[Joint, ...]]) -> tuple[set[str], bool]:
    """The links reachable from ``top``, and whether a joint loop is among them: one
    iterative depth-first search, a link being on the current path or finished."""
    on_path = {top}
    reached = {top}
    loop = False
    pending = [iter(children[top])]
    path = [top]
    while pending:
        joint = next(pending[-1], None)
        if joint is None:
            pending.pop()
            on_path.discard(path.pop())
            continue
        child = joint.child
        if child in on_path:
            loop = True
        elif child not in reached:
            reached.add(child)
            on_path.add(child)
            path.append(child)
            pending.append(iter(children[child]))
    return reached, loop


def _joint_name(joint: Joint) -> str:
    return joint.name


def single_root(robot: Robot, topo: Topology) -> str:
    """The one root link of ``robot``.

    Raises:
        StructureError: There is no root, or more than one.
    """
    if topo.root is None:
        found = (
            f"{len(topo.roots)}: {', '.join(repr(r) for r in topo.roots)}"
            if topo.roots
            else "none (every link is some joint's child)"
        )
        raise StructureError(
            f"robot {robot.name!r} needs one root link, and has {found}", roots=topo.roots
        )
    return topo.root
