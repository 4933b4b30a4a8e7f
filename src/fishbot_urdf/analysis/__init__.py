"""What every rule, drawing and mass computation needs of one robot, built once.

An `Analysis` holds the robot with its topology, its links and joints by name, each link's
parent joint, the joint loops, the rigid bodies simulators make of links welded by fixed
joints, the kinematic plan, the links' poses, the files its meshes name and what those files
hold, computed on first use. Build it with `analyse` and pass it on; functions that take a
robot take an analysis too.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import NamedTuple

from ..extensions import Reference, from_robot
from ..inputs import deadline
from ..model import Joint, JointType, Link, Material, Mesh, Robot, Vector3, Visual
from ..packages import PackageFinder
from ..spatial import Pose
from .drive import Drive, drives, wheels
from .gazebo import Block, Lumping, blocks, lumping
from .materials import visual_materials
from .meshcontents import MeshContents
from .meshpaths import MeshPaths
from .plan import Plan, build
from .poses import place
from .sensors import Sensor, sensors
from .topology import Topology, single_root, topology

__all__ = ["Analysis", "Body", "analyse", "of"]

_STEP = 4096  # links or joints looked at between two looks at the deadline


class Body(NamedTuple):
    """Links welded together by fixed joints, as one rigid body.

    Attributes:
        base: The link the body starts at (the child of a moving joint, or a root).
        members: Every link of the body with its pose in ``base``'s frame, ``base`` first.
        moved_by: The joint that moves the body; None for a root's body.
    """

    base: Link
    members: tuple[tuple[Link, Pose], ...]
    moved_by: Joint | None


@dataclass(frozen=True, eq=False)
class Analysis:
    """One robot, analysed. Immutable; what is costly is computed on first use.

    Attributes:
        robot: The robot.
        path: The file findings without a location are reported against.
        topology: How the links hang together (children, parents, roots, reachable).
        links: Each link by name (the first one, if a name is used twice).
        joints: Each joint by name (the first one, if a name is used twice).
        parent_joint: Each link's parent joint (the first in file order, if it has several).
        packages: Where the ``package://`` names of its meshes are found (None: as
            `fishbot_urdf.packages.find_package` finds them, with no folders given).
        meshes: What the files of its meshes (found by ``mesh_paths``) hold, each file read
            once for each kind of answer (see `fishbot_urdf.analysis.meshcontents`).
    """

    robot: Robot
    path: str
    topology: Topology
    links: Mapping[str, Link] = field(repr=False)
    joints: Mapping[str, Joint] = field(repr=False)
    parent_joint: Mapping[str, Joint] = field(repr=False)
    given_references: tuple[Reference, ...] | None = field(default=None, repr=False)
    packages: PackageFinder | None = field(default=None, repr=False)
    meshes: MeshContents = field(default_factory=MeshContents, init=False, repr=False)

    @property
    def root(self) -> str:
        """The root link.

        Raises:
            StructureError: There is no root, or several.
        """
        return single_root(self.robot, self.topology)

    @cached_property
    def loops(self) -> tuple[tuple[Joint, ...], ...]:
        """Every joint loop, once each, whether or not the root reaches it."""
        topo = self.topology
        if not topo.loop_from_root and len(topo.reachable) == len(topo.children):
            return ()  # the first root reaches every link, on no loop: a tree
        return _loops(self.robot, topo)

    @cached_property
    def bodies(self) -> tuple[Body, ...]:
        """The rigid bodies: links welded by fixed joints, in file order of their base."""
        return _bodies(self)

    @cached_property
    def references(self) -> tuple[Reference, ...]:
        """The names the robot's Gazebo, transmission and ros2_control elements give to its
        links and joints (with their places when the file's reader gave them)."""
        if self.given_references is not None:
            return self.given_references
        return from_robot(self.robot)

    @cached_property
    def gazebo_blocks(self) -> tuple[Block, ...]:
        """Its ``<gazebo>`` and ``<ros2_control>`` elements, parsed once, in file order."""
        return blocks(self.robot, self.references)

    @cached_property
    def gazebo_lumping(self) -> Lumping:
        """What sdformat's URDF converter does to the links before Gazebo sees them: which
        it lumps into which, which it leaves out for lack of mass.

        Raises:
            StructureError: There is no single root.
        """
        return lumping(self.gazebo_blocks, self.topology, self.links, self.joints, self.root)

    @cached_property
    def sensors(self) -> tuple[Sensor, ...]:
        """The sensors of its ``<gazebo>`` blocks, in file order: the link each is on, its
        pose there, and its rays' or cameras' settings as written."""
        return sensors(self.gazebo_blocks)

    @cached_property
    def drives(self) -> tuple[Drive, ...]:
        """The wheel pairs its differential drive plugins turn, in file order; with no such
        plugin, the two continuous wheel joints it has, if they are plain to see (see
        `fishbot_urdf.analysis.drive.wheels`)."""
        found = drives(self.gazebo_blocks)
        if found:
            return found
        pair = wheels(self.joints, self.links, self.zero_poses, self.mesh_bounds)
        return () if pair is None else (pair,)

    def mesh_bounds(self, mesh: Mesh) -> tuple[Vector3, Vector3] | None:
        """The box around ``mesh``'s file's vertices, in its own frame and unscaled; None
        when the file is not found or holds no finite box."""
        path = self.mesh_paths.get(mesh.filename)
        if not path.found or path.file is None:
            return None
        return self.meshes.bounds(path.file)

    @cached_property
    def _materials(self) -> Mapping[int, Material | None]:
        return visual_materials(self.robot)

    def material(self, visual: Visual) -> Material | None:
        """The material of one of the robot's visuals as urdfdom resolves its name (see
        `fishbot_urdf.analysis.materials`): its own when it names none."""
        return self._materials.get(id(visual), visual.material)

    @cached_property
    def mesh_paths(self) -> MeshPaths:
        """Where each of its mesh names leads, by the one rule of `fishbot_urdf.analysis.meshpaths`
        (relative names beside ``path``), looked up on first use."""
        return MeshPaths(self.path, self.packages or PackageFinder())

    @cached_property
    def plan(self) -> Plan:
        """The kinematic plan: link order, parents, joint origins and axes, the
        configuration's columns and the mimic joints' drivers, read by both evaluators."""
        return build(self.robot, self.topology, self.parent_joint, self.joints)

    @cached_property
    def zero_poses(self) -> Mapping[str, Pose]:
        """Every reached link's pose in its root's frame, every joint at zero."""
        plan = self.plan
        return dict(zip(plan.links, place(plan, [0.0] * len(plan.variables)), strict=True))


def analyse(
    robot: Robot,
    path: str | None = None,
    references: Iterable[Reference] | None = None,
    packages: Mapping[str, str | Path] | PackageFinder | None = None,
) -> Analysis:
    """Analyse ``robot`` (linear in its size).

    ``path`` names the file it came from (by default, where the robot element was read);
    ``references`` are the names its extension elements give, as the file's reader found
    them (by default, read again from the robot's extension elements, with no places);
    ``packages`` are where its meshes' ``package://`` names are found (folders by name, or
    a `fishbot_urdf.packages.PackageFinder`)."""
    if path is None:
        path = robot.source.path if robot.source else "<robot>"
    check = deadline()
    links: dict[str, Link] = {}
    for number, link in enumerate(robot.links):
        if not number % _STEP:
            check.check("analysing")
        links.setdefault(link.name, link)
    joints: dict[str, Joint] = {}
    parent_joint: dict[str, Joint] = {}
    for number, joint in enumerate(robot.joints):
        if not number % _STEP:
            check.check("analysing")
        joints.setdefault(joint.name, joint)
        if joint.child in links and joint.parent != joint.child:
            parent_joint.setdefault(joint.child, joint)
    given = None if references is None else tuple(references)
    finder = _finder(packages)
    return Analysis(robot, path, topology(robot), links, joints, parent_joint, given, finder)


def of(
    robot: Robot | Analysis, packages: Mapping[str, str | Path] | PackageFinder | None = None
) -> Analysis:
    """The analysis of ``robot``, built if a Robot is given; with ``packages`` other than
    those it was analysed with, a copy that finds its meshes' packages there."""
    if not isinstance(robot, Analysis):
        return analyse(robot, packages=packages)
    if packages is None or _same(robot.packages, packages):
        return robot
    return replace(robot, packages=_finder(packages))


def _finder(packages: Mapping[str, str | Path] | PackageFinder | None) -> PackageFinder | None:
    if packages is None:
        return None
    return packages if isinstance(packages, PackageFinder) else PackageFinder(packages)


def _same(finder: PackageFinder | None, packages: Mapping[str, str | Path] | PackageFinder) -> bool:
    """Whether ``packages`` find what ``finder`` finds."""
    if isinstance(packages, PackageFinder):
        return packages is finder
    if finder is None:
        return not packages
    return finder.environ is None and dict(finder.packages) == dict(packages)


def _bodies(analysis: Analysis) -> tuple[Body, ...]:
    fixed_below: dict[str, list[tuple[str, Pose]]] = {}
    for child, joint in analysis.parent_joint.items():
        if joint.type is JointType.FIXED:
            fixed_below.setdefault(joint.parent, []).append((child, Pose.of(joint.origin)))
    links = analysis.links
    found: list[Body] = []
    alone = Pose()
    check = deadline()
    for number, link in enumerate(analysis.robot.links):
        if not number % _STEP:
            check.check("analysing")
        moved_by = analysis.parent_joint.get(link.name)
        if moved_by is not None and moved_by.type is JointType.FIXED:
            continue  # part of its parent's body
        if link.name not in fixed_below:  # the common case: a body of one link
            found.append(Body(link, ((link, alone),), moved_by))
            continue
        members: list[tuple[Link, Pose]] = []
        stack = [(link.name, alone)]
        seen: set[str] = set()
        while stack:
            if not len(members) % _STEP:
                check.check("analysing")
            name, pose = stack.pop()
            if name in seen or name not in links:
                continue
            seen.add(name)
            members.append((links[name], pose))
            stack.extend((child, pose.then(o)) for child, o in fixed_below.get(name, ()))
        found.append(Body(link, tuple(members), moved_by))
    return tuple(found)


def _loops(robot: Robot, topo: Topology) -> tuple[tuple[Joint, ...], ...]:
    """Every joint loop, found once each by an iterative depth-first search over all links
    (in file order)."""
    state: dict[str, int] = {}  # 1 on the current path, 2 finished
    loops: list[tuple[Joint, ...]] = []
    check = deadline()
    steps = 0
    for start in (link.name for link in robot.links):
        if start in state:
            continue
        state[start] = 1
        path = [start]
        via: list[Joint] = []  # via[i] is the joint from path[i] to path[i + 1]
        pending = [iter(topo.children[start])]
        while pending:
            steps += 1
            if not steps % _STEP:
                check.check("analysing")
            joint = next(pending[-1], None)
            if joint is None:
                state[path.pop()] = 2
                pending.pop()
                if via:
                    via.pop()
                continue
            child = joint.child
            if state.get(child) == 1:  # back to a link on the current path: a loop
                loops.append((*via[path.index(child) :], joint))
            elif child not in state:
                state[child] = 1
                path.append(child)
                via.append(joint)
                pending.append(iter(topo.children[child]))
    return tuple(loops)
