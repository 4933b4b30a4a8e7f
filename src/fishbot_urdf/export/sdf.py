"""URDF -> SDF as sdformat's converter writes it (sdformat 12, Gazebo Fortress: what
`ign sdf -p robot.urdf` prints), from the analysis of the robot.

The converter lumps every link hung on a fixed joint into its parent (inertials summed as
ODE sums them, visuals and collisions carried over and renamed, `<gazebo>` blocks moved),
leaves out each link that then has no mass, with everything below it, and writes the rest
as links and joints of one model, in its own order and number format, `<gazebo>` blocks
turned into SDF; sdformat's reader then completes and prints that document.
"""

from __future__ import annotations

import math

from ..analysis import Analysis, of
from ..errors import ConversionError, StructureError
from ..model import (
    Joint,
    JointType,
    Link,
    Origin,
    Robot,
)
from ..spatial import urdfdom_quaternion
from ._elements import Shape, colours, inertial, limits, number, numbers, pose, shape
from ._gazebo import Extensions
from ._lumping import Mass, Placement, euler, lump, reach
from ._reader import Element, printed, read

__all__ = ["to_sdf"]

_TYPES = {  # URDF joint type -> SDF's; floating and planar joints are left out
    JointType.REVOLUTE: "revolute",
    JointType.CONTINUOUS: "revolute",
    JointType.PRISMATIC: "prismatic",
    JointType.FIXED: "fixed",
}


def to_sdf(robot: Robot | Analysis) -> str:
    """The SDF that sdformat 12's URDF converter makes of ``robot``, as `ign sdf -p` prints it.

    SDF version 1.9, numbers as the converter prints them (16 significant digits, a zero as
    ``0``): masses in kg, lengths in metres, angles in radians, inertias in kg*m^2.

    Links on fixed joints are lumped into their parents (unless a ``<gazebo reference>`` on
    the joint has ``preserveFixedJoint``, which keeps it, or ``disableFixedJointLumping``,
    which makes it a revolute joint held at 0); a link left without mass (none, or within
    1e-6 kg of 0) is left out with all below it; ``package://`` mesh names become
    ``model://``. ``<gazebo>`` blocks become what the converter makes of them: the settings
    it knows (``material``, ``mu1``, ``kp``, ``turnGravityOff``, ``selfCollide``,
    ``provideFeedback``, ``stopErp``, ``static``, ...) as SDF elements of the link, its
    collisions and visuals, the joint or the model, everything else (sensors, plugins)
    copied in. A lumped link's blocks go with it: its sensors' poses become poses in the
    link it is lumped into (printed with 6 digits, as the converter prints them), and
    plugins whose ``bodyName`` or ``frameName`` names it name that link instead, with
    ``xyzOffset`` and ``rpyOffset`` carried through the fixed joint. Blocks on names that
    are no link or joint the SDF keeps are left out.

    What the conversion loses (links left out, lumped links' sensors and names, mimic
    joints, ...) is said by the rules of the ``gazebo`` family, as `fishbot sdf` says it:
    ``check(robot, config=Config(select=("gazebo",), targets=("gazebo",)))``.

    Raises:
        StructureError: The robot has no single root or has a joint loop (sdformat's
            URDF reader refuses it).
        ConversionError: sdformat's reader refuses the robot (a revolute or prismatic
            joint without limits; links lumped into one that weigh 0 kg together; a value
            in a ``<gazebo>`` block not of its SDF element's type or out of its bounds, a
            required one empty), or its converter stops on a ``<gazebo>`` setting that is
            no number where it reads one.
    """
    analysis = of(robot)
    root = analysis.root
    _refuse_what_urdfdom_refuses(analysis)
    model = _Model(analysis)
    model.reduce(root)
    document = Element("model", attributes=[("name", analysis.robot.name)])
    if root == "world":
        for joint in analysis.topology.children[root]:
            document.children += model.emit(joint.child)
    else:
        document.children += model.emit(root)
    model.extensions.model(document)
    lines = printed(read(document), "  ")
    return "\n".join(["<sdf version='1.9'>", *lines, "</sdf>", ""])


def _refuse_what_urdfdom_refuses(analysis: Analysis) -> None:
    """Stop on a robot whose tree urdfdom (the converter's reader) would not build."""
    robot, topology = analysis.robot, analysis.topology
    why = None
    if len(analysis.links) != len(robot.links) or len(analysis.joints) != len(robot.joints):
        why = "a link or joint name used twice"
    elif analysis.loops:
        why = "a joint loop"
    elif any(len(joints) > 1 for joints in topology.parents.values()):
        why = "a link that is the child of several joints"
    elif any(j.parent not in analysis.links or j.child not in analysis.links for j in robot.joints):
        why = "a joint between links it does not define"
    if why is not None:
        raise StructureError(f"robot {robot.name!r} has {why}: sdformat's reader refuses it")
    for joint in robot.joints:
        if joint.limit is None and joint.type in (JointType.REVOLUTE, JointType.PRISMATIC):
            raise ConversionError(
                f"joint {joint.name!r} is {joint.type.value} and has no <limit>: sdformat's "
                "reader refuses it",
                target="sdf",
                subject=joint.name,
            )


class _Model:
    """The converter's state: each link's inertial and shapes, each moving joint's parent
    and placement, as lumping changes them. (The bodies `Analysis.bodies` fuses are the
    same links, but the converter's order of lumping, over the topology's children in joint
    name order, decides the shapes' names and order, and its arithmetic the last digits.)"""

    def __init__(self, analysis: Analysis) -> None:
        self.analysis = analysis
        self.kept = analysis.gazebo_lumping.preserved | analysis.gazebo_lumping.revolute
        self.extensions = Extensions(
            (block.reference or "", block.element, block.place_of)
            for block in analysis.gazebo_blocks
            if block.element.tag == "gazebo"
        )
        self.mass: dict[str, Mass | None] = {}
        self.visuals: dict[str, list[Shape]] = {}
        self.collisions: dict[str, list[Shape]] = {}
        for link in analysis.links.values():
            self.mass[link.name] = _mass(link)
            self.visuals[link.name] = [
                Shape(v.name or "", _placement(v.origin), v.geometry, analysis.material(v))
                for v in link.visuals
            ]
            self.collisions[link.name] = [
                Shape(c.name or "", _placement(c.origin), c.geometry) for c in link.collisions
            ]
        self.parent: dict[str, str] = {}  # a moving joint's parent, once lumping moved it
        self.placement: dict[str, Placement] = {
            j.name: _placement(j.origin) for j in analysis.joints.values()
        }

    def _above(self, link: str) -> Joint | None:
        """The joint ``link`` hangs from (between links the robot defines), if any."""
        parents = self.analysis.topology.parents.get(link)
        return parents[0] if parents else None

    def _reduced(self, joint: Joint) -> bool:
        """Whether the converter lumps ``joint`` (fixed, and no block keeps it)."""
        return joint.type is JointType.FIXED and joint.name not in self.kept

    def _lumped(self, joint: Joint | None) -> bool:
        return joint is not None and self._reduced(joint) and joint.parent != "world"

    def reduce(self, root: str) -> None:
        """Lump every link on a fixed joint into its parent, in ReduceFixedJoints' order: a
        link's fixed subtree into it, then it into its parent, then on below its moving
        joints (with a stack of its own: a chain of links may be deeper than Python's)."""
        children = self.analysis.topology.children
        stack = [(root, False)]
        while stack:
            link, lumping = stack.pop()
            if not lumping:
                stack.append((link, True))
                fixed = [j for j in children[link] if self._reduced(j)]
                stack.extend((j.child, False) for j in reversed(fixed))
                continue
            above = self._above(link)
            if above is not None and self._lumped(above):
                self._lump(link, above)
            moving = [j for j in children[link] if not self._reduced(j)]
            stack.extend((j.child, False) for j in reversed(moving))

    def _lump(self, link: str, joint: Joint) -> None:
        parent, at = joint.parent, self.placement[joint.name]
        self.extensions.lump(link, parent, at)
        mass = self.mass[link]
        if mass is not None:
            self.mass[parent] = lump(self.mass[parent], mass, at)
        for shapes in (self.visuals, self.collisions):
            shapes[parent] += [
                s._replace(name=s.name or link, placement=reach([at], s.placement))
                for s in shapes[link]
            ]
        for below in self.analysis.topology.children[link]:
            if self._reduced(below):
                continue
            # the joint now hangs from the first link up that no fixed joint holds
            holder, up = link, self._above(link)
            while up is not None and self._lumped(up):
                self.placement[below.name] = reach(
                    [self.placement[up.name]], self.placement[below.name]
                )
                holder = up.parent
                up = self._above(holder)
            self.parent[below.name] = holder

    def emit(self, top: str) -> list[Element]:
        """The elements of ``top`` and below, in CreateSDF's order."""
        found: list[Element] = []
        stack = [top]
        while stack:
            link = stack.pop()
            mass = self.mass[link]
            if link != "world" and (mass is None or abs(mass.mass) <= 1e-6):
                continue  # no mass: left out, and everything below it
            above = self._above(link)
            if not self._lumped(above):
                if above is not None and above.type in _TYPES:
                    found.append(self._joint(above))
                found.append(self._link(link, above, mass))
            stack.extend(j.child for j in reversed(self.analysis.topology.children[link]))
        return found

    def _joint(self, joint: Joint) -> Element:
        kind = _TYPES[joint.type]
        parent = self.parent.get(joint.name, joint.parent)
        at = self.placement[joint.name]
        relative = "__model__" if parent == "world" else parent
        element = Element(
            "joint",
            attributes=[("name", joint.name), ("type", kind)],
            children=[
                Element("pose", pose(at.xyz, euler(at.rotation)), [("relative_to", relative)]),
                Element("parent", parent),
                Element("child", joint.child),
            ],
        )
        if joint.name in self.analysis.gazebo_lumping.revolute:
            element.attributes[1] = ("type", "revolute")
            zero = [Element("lower", "0"), Element("upper", "0")]
            still = [Element("damping", "0"), Element("friction", "0")]
            element.append(
                Element(
                    "axis",
                    children=[Element("limit", children=zero), Element("dynamics", children=still)],
                )
            )
        elif kind != "fixed":
            dynamics = []
            if joint.dynamics is not None:
                dynamics.append(Element("damping", number(joint.dynamics.damping)))
                dynamics.append(Element("friction", number(joint.dynamics.friction)))
            axis = [
                Element("xyz", numbers(joint.axis)),
                Element("limit", children=limits(joint)),
                Element("dynamics", children=dynamics),
            ]
            element.append(Element("axis", children=axis))
        self.extensions.joint(element, joint.name)
        return element

    def _link(self, name: str, above: Joint | None, mass: Mass | None) -> Element:
        element = Element("link", attributes=[("name", name)])
        if above is not None:
            element.append(Element("pose", attributes=[("relative_to", above.name)]))
        if mass is not None:
            if not all(map(math.isfinite, mass.frame.xyz)):
                # ODE's sum of parts weighing 0 kg together divides by 0
                raise ConversionError(
                    f"link {name!r}: the links lumped into it weigh 0 kg together, so its "
                    "centre of mass is not a number, which sdformat's reader refuses",
                    target="sdf",
                    subject=name,
                )
            element.append(inertial(mass))
        for count, item in enumerate(self.collisions[name]):
            collision = element.append(shape("collision", name, count, item))
            self.extensions.collision(collision, name)
        for count, item in enumerate(self.visuals[name]):
            visual = element.append(shape("visual", name, count, item))
            self.extensions.visual(visual, name)
            if item.material is not None:
                material = visual.find("material") or visual.append(Element("material"))
                if material.find("diffuse") is None and material.find("ambient") is None:
                    diffuse, ambient = colours(item.material)
                    material.put("diffuse", diffuse)
                    material.put("ambient", ambient)
        self.extensions.link(element, name)
        return element


def _mass(link: Link) -> Mass | None:
    inertial = link.inertial
    if inertial is None:
        return None
    i = inertial.inertia
    frame = _placement(inertial.origin)
    return Mass(inertial.mass, frame, (i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz))


def _placement(origin: Origin) -> Placement:
    return Placement(origin.xyz, urdfdom_quaternion(origin.rpy))
