"""URDF -> MJCF, the model file MuJoCo reads: one body per link, every inertial as written.

Each link is a body placed by its joint's origin, so that every link's pose is a body's
pose in MuJoCo; a fixed joint is a body without a joint. Masses and inertias are the
robot's own: MuJoCo is told to compute none from the shapes (``inertiafromgeom="false"``),
so a moving link without mass stays without it, and MuJoCo refuses it rather than make one
up (an `mjcf-refused` finding says so before it does).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import NamedTuple

from ..analysis import Analysis, of
from ..analysis.mujoco import BASES, WORLD, Base, moves, mujoco_bodies, no_tree, principal
from ..analysis.plan import Step
from ..diagnostics import Diagnostic
from ..errors import ArgumentError, StructureError
from ..model import Collision, Joint, JointType, Link, Mesh, Robot, Visual
from ..rules.mujoco import joining, refusal
from ..rules.shapes import sizeless
from ..spatial import quaternion
from ._geoms import Assets, geom, number, numbers, place
from ._mjcf_findings import emptying, leaving_out, unreadable

__all__ = ["BASES", "Mjcf", "export_mjcf", "to_mjcf"]


class Mjcf(NamedTuple):
    """An MJCF document, and the findings of its conversion."""

    text: str
    """The document."""
    findings: tuple[Diagnostic, ...]
    """What the conversion changed or left out (`mjcf-joined-inertial`, `mjcf-left-out`,
    `mjcf-empty-shape`), and the bodies MuJoCo will refuse (`mjcf-refused`)."""


def to_mjcf(robot: Robot | Analysis, *, base: Base = "auto", meshdir: str | None = None) -> str:
    """The MJCF of ``robot`` (see `export_mjcf`, which says what it left out)."""
    return export_mjcf(robot, base=base, meshdir=meshdir).text


def export_mjcf(
    robot: Robot | Analysis, *, base: Base = "auto", meshdir: str | None = None
) -> Mjcf:
    """The MJCF of ``robot``: what ``mujoco.MjModel.from_xml_string`` loads.

    Lengths in metres, angles in radians (``<compiler angle="radian">``), masses in kg,
    inertias in kg*m^2, all as written in the URDF, each number written so that it reads
    back to the same double.

    - Links: one body each, named as the link, placed by its joint's ``<origin>``; its
      ``<inertial>`` as an ``<inertial>`` at its origin (its principal moments and axes in
      the body's frame); no ``<inertial>``, or a mass of 0, none (MuJoCo computes none). An
      inertia MuJoCo refuses on a body (not positive semi-definite, or breaking A + B >= C)
      joins, summed exactly, the body of the link it is fixed to (its parent, else the first
      child on a fixed joint that takes it), with an `mjcf-joined-inertial` finding; a body
      MuJoCo will refuse all the same, or a moving one that, with the bodies fixed to it,
      has no mass or no inertia about some axis, an `mjcf-refused` one (the findings
      `fishbot_urdf.rules.mujoco` foretells, which ``fishbot check --target mujoco`` runs).
    - Joints: revolute -> hinge with ``range``, continuous -> hinge, prismatic -> slide with
      ``range``, fixed -> no joint, planar -> slides ``NAME.x`` and ``NAME.y`` then a hinge
      ``NAME.yaw`` about its axis, floating -> a free joint at the top level, else slides
      ``NAME.x``, ``NAME.y``, ``NAME.z`` and hinges ``NAME.yaw``, ``NAME.pitch``,
      ``NAME.roll`` (URDF's rpy: the same pose as `fishbot_urdf.link_poses` for the same
      numbers); ``<dynamics>`` damping and friction -> ``damping`` and ``frictionloss``; a
      mimic joint -> an ``<equality><joint>`` holding it at ``multiplier * leader + offset``.
    - Shapes: visuals as geoms of group 2 that collide with nothing, collisions as geoms of
      group 3 (cylinders along the local z, as URDF's); a mesh only when its file is found
      and is STL or OBJ (named by its absolute path, or relative to ``meshdir``, which the
      model then names), and MuJoCo can read it (a binary STL of at most 200000
      triangles, a file with one, and, for a collision, one with a volume to hull), else
      the shape is left out, with an `mjcf-left-out` finding; a
      shape of no size (a box, cylinder or sphere with a size of 0 or less, a mesh scaled by
      0), which MuJoCo refuses, is left out with an `mjcf-empty-shape` one.

    Args:
        robot: The robot, or its analysis.
        base: ``auto``: fixed when the root link is ``world`` (its children hang from the
            world by their joints), else free; ``fixed``: the root (or each child of
            ``world``) fixed to the world; ``floating``: free.
        meshdir: The folder mesh files are named relative to, or None for absolute names.

    Raises:
        StructureError: A link or joint name is used twice, or the links form a loop.
        ArgumentError: ``base`` is none of `BASES`.
    """
    if base not in BASES:
        raise ArgumentError(f"base {base!r} is none of {', '.join(BASES)}", name="base")
    analysis = of(robot)
    why = no_tree(analysis)
    if why is not None:
        raise StructureError(f"robot {analysis.robot.name!r} has {why}")
    writer = _Writer(analysis, base, meshdir)
    return Mjcf(writer.write(), tuple(writer.findings))


class _Writer:
    def __init__(self, analysis: Analysis, base: Base, meshdir: str | None) -> None:
        self.analysis = analysis
        self.base = base
        self.meshdir = meshdir
        self.assets = Assets(analysis, meshdir)
        self.equality = ET.Element("equality")
        self.bodies = mujoco_bodies(analysis, base)
        self.masses = self.bodies.masses
        self.findings = [
            joining(analysis, analysis.links[link], holder)
            for link, holder in self.bodies.joined.items()
        ]
        plan = analysis.plan
        self.steps = {plan.links[step.link]: step for step in plan.steps}

    def write(self) -> str:
        analysis = self.analysis
        plan = analysis.plan
        model = ET.Element("mujoco", model=analysis.robot.name)
        compiler = ET.SubElement(
            model, "compiler", angle="radian", autolimits="true", inertiafromgeom="false"
        )
        if self.meshdir is not None:
            compiler.set("meshdir", self.meshdir)
        ET.SubElement(model, "option", integrator="implicitfast")
        model.append(self.assets.element)
        world = ET.SubElement(model, "worldbody")
        bodies: dict[str, ET.Element] = {}
        for root in plan.roots:
            if root == WORLD:
                bodies[root] = world
                self._shapes(world, analysis.links[root])
            else:
                body = bodies[root] = self._body(world, analysis.links[root])
                if root in self.bodies.moving:
                    ET.SubElement(body, "freejoint")
        for step in plan.steps:
            parent, link = plan.links[step.parent], plan.links[step.link]
            body = self._body(bodies[parent], analysis.links[link])
            place(body, step.joint.origin)
            joints = self._joints(step, top=parent == WORLD)
            body[:0] = joints
            bodies[link] = body
        self.findings += [refusal(analysis, link, why) for link, why in self.bodies.refusals]
        for joint in analysis.robot.joints:
            self._mimic(joint)
        if len(self.equality):
            model.append(self.equality)
        if not len(self.assets.element):
            model.remove(self.assets.element)
        ET.indent(model)
        return ET.tostring(model, encoding="unicode") + "\n"

    def _body(self, parent: ET.Element, link: Link) -> ET.Element:
        body = ET.SubElement(parent, "body", name=link.name)
        mass = self.masses.get(link.name)
        if mass is not None:
            element = ET.SubElement(body, "inertial", mass=number(mass.mass))
            element.set("pos", numbers(mass.centre) if any(mass.centre) else "0 0 0")
            (xx, xy, xz), (_, yy, yz), (_, _, zz) = mass.tensor
            if xy == 0.0 and xz == 0.0 and yz == 0.0:
                element.set("diaginertia", numbers((xx, yy, zz)))
            else:
                # the principal axes, found here: MuJoCo's `fullinertia` refuses an inertia
                # with a moment of 0 (a point mass), which a body may have
                moments, axes = principal(mass.tensor)
                x, y, z, w = quaternion(axes)
                element.set("quat", numbers((w, x, y, z)))
                element.set("diaginertia", numbers(moments))
        self._shapes(body, link)
        return body

    def _shapes(self, body: ET.Element, link: Link) -> None:
        shapes: list[Visual | Collision] = [*link.visuals, *link.collisions]
        for shape in shapes:
            visual = isinstance(shape, Visual)
            kind = "visual" if visual else "collision"
            empty = sizeless(shape.geometry)
            if empty is not None:
                self.findings.append(emptying(self.analysis, link, shape.geometry, kind, empty))
                continue
            if isinstance(shape.geometry, Mesh):
                why = unreadable(self.analysis, shape.geometry, collides=not visual)
                if why is not None:
                    self.findings.append(
                        leaving_out(self.analysis, link, shape.geometry, kind, why)
                    )
                    continue
            found = geom(self.assets, shape.geometry, shape.origin, visual=visual)
            if found is not None:
                body.append(found)
            elif isinstance(shape.geometry, Mesh):
                self.findings.append(leaving_out(self.analysis, link, shape.geometry, kind))

    def _joints(self, step: Step, *, top: bool) -> list[ET.Element]:
        joint, kind = step.joint, step.kind
        if not moves(kind, top=top, base=self.base):
            return []
        if kind is JointType.FIXED:  # a child of the world, floating
            return [ET.Element("freejoint")]
        if kind is JointType.FLOATING:
            if top:
                return [ET.Element("freejoint", name=joint.name)]
            parts = [("x", "slide", (1.0, 0.0, 0.0)), ("y", "slide", (0.0, 1.0, 0.0))]
            parts += [("z", "slide", (0.0, 0.0, 1.0)), ("yaw", "hinge", (0.0, 0.0, 1.0))]
            parts += [("pitch", "hinge", (0.0, 1.0, 0.0)), ("roll", "hinge", (1.0, 0.0, 0.0))]
            return [self._joint(joint, f"{joint.name}.{p}", t, a, False) for p, t, a in parts]
        if kind is JointType.PLANAR:
            along, across = step.plane or ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
            return [
                self._joint(joint, f"{joint.name}.x", "slide", along, False),
                self._joint(joint, f"{joint.name}.y", "slide", across, False),
                self._joint(joint, f"{joint.name}.yaw", "hinge", step.axis, False),
            ]
        kind_name = "slide" if kind is JointType.PRISMATIC else "hinge"
        limited = kind is not JointType.CONTINUOUS
        return [self._joint(joint, joint.name, kind_name, step.axis, limited)]

    def _joint(
        self,
        joint: Joint,
        name: str,
        kind: str,
        axis: tuple[float, float, float],
        limited: bool,
    ) -> ET.Element:
        element = ET.Element("joint", name=name, type=kind, axis=numbers(axis))
        if limited and joint.limit is not None:
            element.set("range", numbers((joint.limit.lower, joint.limit.upper)))
        if joint.dynamics is not None:
            if joint.dynamics.damping:
                element.set("damping", number(joint.dynamics.damping))
            if joint.dynamics.friction:
                element.set("frictionloss", number(joint.dynamics.friction))
        return element

    def _mimic(self, joint: Joint) -> None:
        """An equality constraint for a mimic joint that moves the link it places."""
        plan = self.analysis.plan
        follows = plan.mimics.get(joint.name)
        if follows is None:
            return
        step = self.steps.get(joint.child)
        if step is None or step.joint is not joint or step.kind not in _ONE_NUMBER:
            return
        element = ET.SubElement(self.equality, "joint", joint1=joint.name)
        if follows.leader is None or follows.leader not in plan.columns:
            element.set("polycoef", numbers((follows.offset, 0.0, 0.0, 0.0, 0.0)))
            return
        element.set("joint2", follows.leader)
        element.set("polycoef", numbers((follows.offset, follows.multiplier, 0.0, 0.0, 0.0)))


_ONE_NUMBER = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)
