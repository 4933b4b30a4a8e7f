"""URDF -> MJCF, the model file MuJoCo reads: one body per link, every inertial as written.

Each link is a body placed by its joint's origin, so that every link's pose is a body's
pose in MuJoCo; a fixed joint is a body without a joint. Masses and inertias are the
robot's own: MuJoCo is told to compute none from the shapes (``inertiafromgeom="false"``),
so a moving link without mass stays without it, and MuJoCo refuses it rather than make one
up (an `mjcf-refused` finding says so before it does).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Iterable
from pathlib import Path
from typing import NamedTuple

from ..analysis import Analysis, of
from ..analysis.gazebo import number as setting
from ..analysis.mujoco import BASES, WORLD, Base, moves, mujoco_bodies, no_tree, principal
from ..analysis.plan import Step
from ..diagnostics import Diagnostic
from ..errors import ArgumentError, StructureError
from ..model import Collision, Joint, JointType, Link, Mesh, Robot, Visual
from ..output import Source, write_atomic
from ..rules._contents import hull_refused
from ..rules.mujoco import joining, refusal
from ..rules.shapes import sizeless
from ..spatial import quaternion
from ._actuators import Motor, actuator, motors
from ._geoms import COLLISION_GROUP, VISUAL_GROUP, Asset, Assets, geom, number, numbers, place
from ._mjcf_findings import converting, emptying, leaving_out
from .meshfolder import MeshFolder

__all__ = [
    "BASES",
    "COLLISION_GROUP",
    "VISUAL_GROUP",
    "Base",
    "Mjcf",
    "Motor",
    "export_mjcf",
    "mesh_folder",
    "motors",
    "to_mjcf",
    "write_mjcf",
]


class Mjcf(NamedTuple):
    """An MJCF document, and the findings of its conversion."""

    text: str
    """The document."""
    findings: tuple[Diagnostic, ...]
    """What the conversion changed, converted or left out (`mjcf-joined-inertial`,
    `mjcf-mesh-converted`, `mjcf-left-out`, `mjcf-empty-shape`), and the bodies MuJoCo will
    refuse (`mjcf-refused`)."""


def to_mjcf(robot: Robot | Analysis, *, base: Base = "auto", meshdir: str | None = None) -> str:
    """The MJCF of ``robot`` (see `export_mjcf`, which says what it left out)."""
    return export_mjcf(robot, base=base, meshdir=meshdir).text


def export_mjcf(
    robot: Robot | Analysis,
    *,
    base: Base = "auto",
    meshdir: str | None = None,
    driven: tuple[Motor, ...] | None = None,
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
      MuJoCo will refuse all the same, or a moving one without mass, an `mjcf-refused` one.
    - Joints: revolute -> hinge with ``range``, continuous -> hinge, prismatic -> slide with
      ``range``, fixed -> no joint, planar -> slides ``NAME.x`` and ``NAME.y`` then a hinge
      ``NAME.yaw`` about its axis, floating -> a free joint at the top level, else slides
      ``NAME.x``, ``NAME.y``, ``NAME.z`` and hinges ``NAME.yaw``, ``NAME.pitch``,
      ``NAME.roll`` (URDF's rpy: the same pose as `fishbot_urdf.link_poses` for the same
      numbers); ``<dynamics>`` damping and friction -> ``damping`` and ``frictionloss``; a
      mimic joint -> an ``<equality><joint>`` holding it at ``multiplier * leader + offset``.
    - Shapes: visuals as geoms of group 2 that collide with nothing, in their material's
      colour (``rgba``, the material resolved by name as urdfdom does), collisions as geoms
      of group 3 in MuJoCo's default colour (cylinders along the local z, as URDF's); a mesh
      only when its file is found and MuJoCo reads it as it is (a binary STL of 1 to 200,000
      triangles, or an OBJ, of at least 4 distinct vertices), named by its absolute path,
      or relative to ``meshdir``, which the model then names; else the shape is left out,
      with an `mjcf-left-out` finding (`write_mjcf` converts such meshes); a collision mesh
      with no volume to make a convex hull of is left out so too. A shape of no size (a box,
      cylinder or sphere with a size of 0 or less, a mesh scaled by 0), which MuJoCo
      refuses, is left out with an `mjcf-empty-shape` finding. A link's ``<gazebo
      reference>`` ``<mu1>`` and ``<mu2>`` (the smaller) are its collisions' friction.

    Args:
        robot: The robot, or its analysis.
        base: ``auto``: fixed when the root link is ``world`` (its children hang from the
            world by their joints), else free; ``fixed``: the root (or each child of
            ``world``) fixed to the world; ``floating``: free.
        meshdir: The folder mesh files are named relative to, or None for absolute names.
        driven: The joints to put actuators on (None: the robot's own, `motors`).

    Raises:
        StructureError: A link or joint name is used twice, or the links form a loop.
        ArgumentError: ``base`` is none of `BASES`.
    """
    if base not in BASES:
        raise ArgumentError(f"base {base!r} is none of {', '.join(BASES)}", name="base")
    analysis = of(robot)
    _refuse(analysis)
    writer = _Writer(analysis, base, meshdir, motors(analysis) if driven is None else driven)
    return Mjcf(writer.write(), tuple(writer.findings))


def mesh_folder(path: str | Path) -> Path:
    """The folder `write_mjcf` converts meshes into for a model written to ``path``:
    ``robot_meshes`` beside ``robot.xml``."""
    path = Path(path)
    return path.parent / f"{path.stem}_meshes"


def write_mjcf(
    robot: Robot | Analysis,
    path: str | Path,
    *,
    base: Base = "auto",
    meshes: str | Path | None = None,
    inputs: Iterable[Source] = (),
    driven: tuple[Motor, ...] | None = None,
) -> Mjcf:
    """Write the MJCF of ``robot`` to ``path``, converting the meshes MuJoCo cannot read.

    What `mujoco.MjModel.from_xml_path` loads: `export_mjcf`'s model, but for its meshes.
    A mesh MuJoCo reads as it is (a binary STL of 1 to 200,000 triangles, an OBJ) is named
    by its absolute path. Any other found (COLLADA, PLY, glTF, OFF, an ASCII STL, an STL of
    too many triangles) has its triangles, placed as RViz draws them (a COLLADA file's node
    transforms and ``<unit meter>`` applied, its ``<up_axis>`` not), written as a binary
    STL (an OBJ past 200,000 triangles) named after it in the folder ``meshes``, which the
    model's ``<compiler meshdir>`` names (relative to the model's folder), with an
    `mjcf-mesh-converted` finding; its ``<mesh scale>`` stays the asset's scale. A mesh
    that cannot be converted (holding no triangles, or fewer than 4 distinct vertices, which
    MuJoCo refuses; not read; COLLADA without pycollada, any format but STL without
    trimesh: the ``mesh`` extra) is left out, with an `mjcf-left-out` finding. Each file is
    written whole or not at all; a converted file that holds the same bytes already is left
    as it is, so writing twice gives the same files; other files in the folder are kept.

    Args:
        robot: The robot, or its analysis.
        path: The model file to write.
        base: As for `export_mjcf`.
        meshes: The folder converted meshes go to; None for `mesh_folder` of ``path``
            (``robot_meshes`` beside ``robot.xml``; none for a device or a pipe, such as
            ``/dev/null``: nothing is converted). Made only when a mesh is converted.
        inputs: The files the robot was read from, which nothing is written over; the
            robot's mesh files are added to them.
        driven: As for `export_mjcf`.

    Raises:
        InputError: ``path`` or a converted file would replace an input, the folder holds
            an input, or a file cannot be written.
        StructureError: As for `export_mjcf`.
        ArgumentError: As for `export_mjcf`.
    """
    if base not in BASES:
        raise ArgumentError(f"base {base!r} is none of {', '.join(BASES)}", name="base")
    analysis = of(robot)
    _refuse(analysis)
    path = Path(path)
    folder = Path(meshes) if meshes is not None else mesh_folder(path)
    sources = (*inputs, *analysis.mesh_paths.found(analysis.robot))
    # a device or a pipe (/dev/null) has no folder beside it to convert into
    device = meshes is None and path.exists() and not path.is_file()
    converter = None if device else MeshFolder(folder, inputs=sources)
    chosen = motors(analysis) if driven is None else driven
    writer = _Writer(analysis, base, None, chosen, converter)
    text = writer.write(None if device else os.path.relpath(folder, path.parent))
    write_atomic(path, text, inputs=sources)
    return Mjcf(text, tuple(writer.findings))


def _refuse(analysis: Analysis) -> None:
    """Stop on a robot MuJoCo cannot name or build as a tree."""
    why = no_tree(analysis)
    if why is not None:
        raise StructureError(f"robot {analysis.robot.name!r} has {why}")


class _Writer:
    def __init__(
        self,
        analysis: Analysis,
        base: Base,
        meshdir: str | None,
        driven: tuple[Motor, ...],
        folder: MeshFolder | None = None,
    ) -> None:
        self.analysis = analysis
        self.driven = driven
        self.made: set[str] = set()  # the names of the joints written
        self.friction = _friction(analysis)
        self.base = base
        self.meshdir = meshdir
        self.assets = Assets(analysis, meshdir, folder)
        self.equality = ET.Element("equality")
        self.bodies = mujoco_bodies(analysis, base)
        self.masses = self.bodies.masses
        self.findings = [
            joining(analysis, analysis.links[link], holder)
            for link, holder in self.bodies.joined.items()
        ]
        plan = analysis.plan
        self.steps = {plan.links[step.link]: step for step in plan.steps}

    def write(self, folder: str | None = None) -> str:
        """The model's text; ``folder`` is the mesh folder's name relative to the model's,
        which ``<compiler meshdir>`` gives when a mesh was converted into it."""
        analysis = self.analysis
        plan = analysis.plan
        model = ET.Element("mujoco", model=analysis.robot.name)
        compiler = ET.SubElement(
            model, "compiler", angle="radian", autolimits="true", inertiafromgeom="false"
        )
        if self.meshdir is not None:
            compiler.set("meshdir", self.meshdir)
        ET.SubElement(model, "option", integrator="implicitfast", cone="elliptic")
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
        actuators = ET.Element("actuator")
        for motor in self.driven:
            if motor.joint in self.made:
                actuators.append(actuator(motor, analysis.joints[motor.joint]))
        if len(actuators):
            model.append(actuators)
        if not len(self.assets.element):
            model.remove(self.assets.element)
        if folder is not None and self.assets.converted:
            compiler.set("meshdir", folder)
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
            name = None
            if isinstance(shape.geometry, Mesh):
                asset = self.assets.mesh(shape.geometry)
                if not visual and asset.name is not None and asset.facts is not None:
                    flat = hull_refused(asset.facts)  # (a visual collides with nothing)
                    if flat is not None:
                        asset = Asset(None, why=flat, hint=_FLAT_HINT)
                if asset.name is None:
                    self.findings.append(
                        leaving_out(self.analysis, link, shape.geometry, kind, asset)
                    )
                    continue
                if asset.converted is not None:
                    self.findings.append(
                        converting(self.analysis, link, shape.geometry, kind, asset)
                    )
                name = asset.name
            rgba = None
            if isinstance(shape, Visual):
                material = self.analysis.material(shape)
                rgba = None if material is None else material.color
            found = geom(shape.geometry, shape.origin, visual=visual, mesh=name, rgba=rgba)
            friction = None if visual else self.friction.get(link.name)
            if friction is not None:
                found.set("friction", f"{number(friction)} 0.005 0.0001")
                # as Gazebo, whatever the floor's: MuJoCo takes the greater of two geoms'
                # frictions, or the one of the greater priority
                found.set("priority", "1")
            body.append(found)

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
            return [self._joint(joint, self._part(joint, p), t, a, False) for p, t, a in parts]
        if kind is JointType.PLANAR:
            along, across = step.plane or ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
            return [
                self._joint(joint, self._part(joint, "x"), "slide", along, False),
                self._joint(joint, self._part(joint, "y"), "slide", across, False),
                self._joint(joint, self._part(joint, "yaw"), "hinge", step.axis, False),
            ]
        kind_name = "slide" if kind is JointType.PRISMATIC else "hinge"
        limited = kind is not JointType.CONTINUOUS
        return [self._joint(joint, joint.name, kind_name, step.axis, limited)]

    def _part(self, joint: Joint, part: str) -> str:
        """The name of one part of a planar or floating joint: ``NAME.part``, with ``_``
        added until no joint of the robot, nor one written, has it (MJCF refuses a name
        twice)."""
        name = f"{joint.name}.{part}"
        while name in self.analysis.joints or name in self.made:
            name += "_"
        return name

    def _joint(
        self,
        joint: Joint,
        name: str,
        kind: str,
        axis: tuple[float, float, float],
        limited: bool,
    ) -> ET.Element:
        element = ET.Element("joint", name=name, type=kind, axis=numbers(axis))
        self.made.add(name)
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


def _friction(analysis: Analysis) -> dict[str, float]:
    """Each link's friction as its ``<gazebo reference>`` blocks give it (``<mu1>`` and
    ``<mu2>``, the last of each written, 1 when one is not: Gazebo's default): MuJoCo's is
    the same in every direction, so the smaller, in which the link slides."""
    given: dict[str, dict[str, float]] = {}
    for block in analysis.gazebo_blocks:
        if block.reference is None:
            continue
        for tag in ("mu1", "mu2"):
            mu = setting(block.element, tag)
            if mu is not None and mu >= 0:
                given.setdefault(block.reference, {})[tag] = mu
    return {link: min(mus.get("mu1", 1.0), mus.get("mu2", 1.0)) for link, mus in given.items()}


_FLAT_HINT = "collide with a thin box, or give the mesh its thickness"
_ONE_NUMBER = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)
