"""A robot built in Python, made readable for the rules once its faults are reported: a
name that is None made "" (as the reader makes a missing one), a number that is not finite
made 0 (an axis, URDF's default). The rules compare and sort names and do arithmetic on
numbers; their findings about what was mended follow from the report (see
:mod:`fishbot_urdf.validation`)."""

from __future__ import annotations

import math
from dataclasses import fields, is_dataclass, replace
from typing import TypeVar

from ..model import Collision, Joint, Link, Material, Mesh, Robot, Visual

__all__ = ["finite", "readable"]


def readable(robot: Robot) -> Robot:
    """``robot`` with every name that is None made "", as the reader makes a missing one, so
    that the rules can read it (they compare and sort names). Its types must be right (see
    `values`)."""
    if robot.name is None:
        robot = replace(robot, name="")
    return replace(
        robot,
        links=tuple(map(_named_link, robot.links)),
        joints=tuple(map(_named_joint, robot.joints)),
        materials=tuple(map(_named, robot.materials)),
    )


def finite(robot: Robot) -> Robot:
    """``robot`` with every number that is not finite made 0 (an axis that is not finite
    made URDF's default, 1 0 0), so that the rules, which do arithmetic on them, can read
    it; the numbers were reported (see `values`), and the rules' findings about those links
    and joints follow from that report. Its types must be right."""
    made = _zeroed(robot)
    assert isinstance(made, Robot)
    joints = tuple(
        replace(j, axis=(1.0, 0.0, 0.0)) if _not_finite(given.axis) else j
        for j, given in zip(made.joints, robot.joints, strict=True)
    )
    return replace(made, joints=joints)


def _not_finite(axis: tuple[float, float, float] | None) -> bool:
    return axis is not None and not all(map(math.isfinite, axis))


def _zeroed(value: object) -> object:
    if isinstance(value, float):
        return value if math.isfinite(value) else 0.0
    if type(value) is tuple:  # (a place in a file is a named tuple: kept as it is)
        return tuple(map(_zeroed, value))
    if is_dataclass(value) and not isinstance(value, type):
        changed = {f.name: _zeroed(getattr(value, f.name)) for f in fields(value) if f.init}
        return replace(value, **changed)
    return value


def _named(item: _Named) -> _Named:
    """``item`` with its name "" if it was None."""
    return replace(item, name="") if item.name is None else item


def _named_link(link: Link) -> Link:
    shapes: tuple[Visual | Collision, ...] = (*link.visuals, *link.collisions)
    if link.name is not None and not any(
        (isinstance(s.geometry, Mesh) and s.geometry.filename is None)
        or (isinstance(s, Visual) and s.material is not None and s.material.name is None)
        for s in shapes
    ):
        return link  # nearly always
    visuals = []
    for visual in map(_named_shape, link.visuals):
        if visual.material is not None:
            visual = replace(visual, material=_named(visual.material))
        visuals.append(visual)
    collisions = tuple(map(_named_shape, link.collisions))
    return replace(_named(link), visuals=tuple(visuals), collisions=collisions)


def _named_shape(shape: _Shape) -> _Shape:
    geometry = shape.geometry
    if isinstance(geometry, Mesh) and geometry.filename is None:
        return replace(shape, geometry=replace(geometry, filename=""))
    return shape


def _named_joint(joint: Joint) -> Joint:
    names = (joint.name, joint.parent, joint.child)
    if None not in names and (joint.mimic is None or joint.mimic.joint is not None):
        return joint  # nearly always
    name, parent, child = (name or "" for name in names)
    mimic = joint.mimic
    if mimic is not None and mimic.joint is None:
        mimic = replace(mimic, joint="")
    return replace(joint, name=name, parent=parent, child=child, mimic=mimic)


_Named = TypeVar("_Named", Link, Joint, Material)
_Shape = TypeVar("_Shape", Visual, Collision)
