"""Rules about names given to the robot's parts: by Gazebo, transmission and ros2_control
elements, by Gazebo's plugins, and by visuals naming a material."""

from __future__ import annotations

from collections.abc import Iterator

from ..analysis import Analysis
from ..catalog import Rule
from ..catalog.references import (
    CONTROL_INTERFACE,
    MATERIAL_CONFLICT,
    UNDEFINED_MATERIAL,
    UNKNOWN_REFERENCE,
)
from ..diagnostics import Diagnostic, Kind, Subject, shown_path
from ..extensions import Reference, Target
from ..model import JointType, Location, Material
from ..wording import closest, listing

__all__ = ["REPORTS", "references"]


_STANDARD_INTERFACES = ("position", "velocity", "acceleration", "effort")
_ONE_AXIS = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)


def references(analysis: Analysis) -> Iterator[Diagnostic]:
    """Every finding about names given to the robot's links, joints and materials."""
    for ref in analysis.references:
        yield from _reference(analysis, ref)
    yield from _materials(analysis)


def _dropped_with(analysis: Analysis, ref: Reference) -> str:
    """What Gazebo's converter drops with a ``<gazebo reference>`` block naming nothing: its
    sensors and plugins, said by name (empty for other references)."""
    if ref.context != "<gazebo reference>":
        return ""
    block = next(
        (b for b in analysis.gazebo_blocks if b.reference == ref.name and b.where == ref.source),
        None,
    )
    if block is None:
        return ""
    parts = [f"sensor {s.get('name')!r}" for s in block.element.iter("sensor")]
    parts += [f"plugin {p.get('name')!r}" for p in block.element.iter("plugin")]
    if not parts:
        return ": Gazebo's converter drops the block without a word"
    return f": Gazebo's converter drops the block without a word, and with it {', '.join(parts)}"


def _reference(analysis: Analysis, ref: Reference) -> Iterator[Diagnostic]:
    path, robot = analysis.path, analysis.robot
    subject = Subject(Kind.ROBOT, robot.name)
    names: list[str] = []
    if ref.target is not Target.JOINT:
        names.extend(analysis.links)
    if ref.target is not Target.LINK:
        names.extend(analysis.joints)
    if ref.name not in names:
        close = closest(ref.name, names)
        listed = listing(names, near=ref.name)
        hint = f"did you mean {close!r}?" if close else f"{ref.target.value}s: {listed}"
        yield UNKNOWN_REFERENCE.report(
            f"{ref.context} names {ref.target.value} {ref.name!r}, which the robot does not "
            f"have{_dropped_with(analysis, ref)}",
            ref.source,
            path=path,
            subject=subject,
            hint=hint,
        )
        return
    joint = analysis.joints.get(ref.name) if ref.context == "<ros2_control> joint" else None
    if joint is None:
        return
    if joint.type not in _ONE_AXIS:
        yield CONTROL_INTERFACE.report(
            f"{ref.context} {ref.name!r} is a {joint.type.value} joint",
            ref.source,
            path=path,
            subject=Subject(Kind.JOINT, joint.name),
            hint="ros2_control drives revolute, continuous and prismatic joints; "
            "leave this one out",
        )
        return
    for interface in ref.interfaces:
        if interface.name in _STANDARD_INTERFACES:
            continue
        close = closest(interface.name, _STANDARD_INTERFACES)
        if close is None:
            continue  # a custom interface (a motor's temperature, say)
        yield CONTROL_INTERFACE.report(
            f"{ref.context} {ref.name!r}: {interface.kind} interface {interface.name!r} is not "
            "a standard one",
            interface.source or ref.source,
            path=path,
            subject=Subject(Kind.JOINT, joint.name),
            hint=f"did you mean {close!r}? (standard: {', '.join(_STANDARD_INTERFACES)})",
        )


def _materials(analysis: Analysis) -> Iterator[Diagnostic]:
    """Materials as urdfdom resolves them: top-level ones first, then each visual's in file
    order; the first definition of a name is the one every visual gets."""
    path = analysis.path
    robot = analysis.robot
    first: dict[str, Material] = {}
    for top in robot.materials:
        if top.name and (top.color or top.texture):
            first.setdefault(top.name, top)
    for link in robot.links:
        for visual in link.visuals:
            if visual.material is None or not visual.material.name:
                continue
            material = visual.material
            defined = first.get(material.name)
            if defined is None:
                if material.color or material.texture:
                    first[material.name] = material
                    continue
                names = [m.name for m in first.values()]
                close = closest(material.name, names)
                hint = f"did you mean {close!r}? " if close else ""
                yield UNDEFINED_MATERIAL.report(
                    f"link {link.name!r}: material {material.name!r} is not defined",
                    material.source,
                    path=path,
                    subject=Subject(Kind.MATERIAL, material.name),
                    hint=hint + "define it at the top level with a <color>, or give the visual "
                    "its own <color>",
                )
            elif _differs(material, defined):
                yield MATERIAL_CONFLICT.report(
                    f"link {link.name!r}: material {material.name!r} is given "
                    f"{_look(material)} here, but {_look(defined)}{_at(defined.source)}",
                    material.source,
                    path=path,
                    subject=Subject(Kind.MATERIAL, material.name),
                    hint="urdfdom (RViz) uses the first; give this colour its own name",
                )


def _differs(material: Material, defined: Material) -> bool:
    if material.color is None and material.texture is None:
        return False  # only names the material: that is how it is shared
    return (material.color, material.texture) != (defined.color, defined.texture)


def _look(material: Material) -> str:
    if material.color is not None:
        return "rgba " + " ".join(f"{v:g}" for v in material.color)
    return f"texture {material.texture!r}" if material.texture else "no colour"


def _at(where: Location | None) -> str:
    return f" at {shown_path(where.path)}:{where.line}" if where is not None else " first"


REPORTS: tuple[Rule, ...] = (
    CONTROL_INTERFACE,
    MATERIAL_CONFLICT,
    UNDEFINED_MATERIAL,
    UNKNOWN_REFERENCE,
)
"""Every rule this module's check may report: the check runs only when one is selected."""
