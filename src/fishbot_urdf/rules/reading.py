"""Rules the reader applies while it builds the model: the XML, the elements, the values.

These are data only; the reader (``fishbot_urdf.parse``) reports them as it reads.
"""

from __future__ import annotations

from ..diagnostics import Severity
from . import Consumer, Family, Rule

_SIMULATORS = (Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
_ALL = (Consumer.URDFDOM, *_SIMULATORS)
E, W = Severity.ERROR, Severity.WARNING

XML_SYNTAX = Rule(
    "xml-syntax",
    E,
    Family.XML,
    summary="The file is not well-formed XML, or declares entities.",
    consumers=(*_ALL, Consumer.XACRO, Consumer.XML_TOOLS),
    fatal=True,
)
NO_ROBOT = Rule(
    "no-robot", E, Family.URDF, summary="The root element is not <robot>.", consumers=_ALL
)
ROBOT_NAME = Rule("robot-name", E, Family.URDF, summary="<robot> has no name.", consumers=_ALL)
ROBOT_VERSION = Rule(
    "robot-version",
    E,
    Family.URDF,
    summary="<robot version> is not a URDF version urdfdom reads (1.0).",
)
MISSING_ATTRIBUTE = Rule(
    "missing-attribute",
    E,
    Family.URDF,
    summary="An element lacks an attribute it needs.",
    consumers=_ALL,
)
MISSING_ELEMENT = Rule(
    "missing-element",
    E,
    Family.URDF,
    summary="An element lacks a child it needs (<geometry>, <mass>, <parent>, ...).",
    consumers=_ALL,
)
BAD_NUMBER = Rule(
    "bad-number",
    E,
    Family.URDF,
    summary="A value is not a finite number as urdfdom reads numbers.",
    consumers=_ALL,
)
BAD_VECTOR = Rule(
    "bad-vector",
    E,
    Family.URDF,
    summary="A vector has the wrong count of numbers.",
    consumers=_ALL,
)
BAD_COLOR = Rule(
    "bad-color",
    E,
    Family.URDF,
    summary="A colour has a value outside 0..1.",
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO),
)
JOINT_TYPE = Rule(
    "joint-type",
    E,
    Family.URDF,
    summary="A joint has no type, or one URDF does not define.",
    consumers=_ALL,
)
UNKNOWN_GEOMETRY = Rule(
    "unknown-geometry",
    E,
    Family.URDF,
    summary="<geometry> holds something other than a box, cylinder, sphere or mesh.",
    consumers=_ALL,
)
UNKNOWN_ELEMENT = Rule(
    "unknown-element",
    W,
    Family.URDF,
    summary="An element stands where URDF gives it no meaning, and is ignored.",
    consumers=_ALL,
)
DUPLICATE_ELEMENT = Rule(
    "duplicate-element",
    W,
    Family.URDF,
    summary="A second element of a kind that may appear once (<inertial>, <origin>, a shape).",
    consumers=_ALL,
)
COLLISION_MATERIAL = Rule(
    "collision-material",
    W,
    Family.URDF,
    summary="<material> inside <collision> is ignored.",
    consumers=_ALL,
)
NEGATIVE_MASS = Rule("negative-mass", E, Family.URDF, summary="A mass is negative.", consumers=_ALL)
