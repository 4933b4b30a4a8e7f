"""The URDF data model: frozen dataclasses that mirror the URDF 1.0 tags (no I/O, no numpy)."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

from .errors import UnknownNameError
from .location import Location as Location

Vector3 = tuple[float, float, float]
Rgba = tuple[float, float, float, float]

ZERO3: Vector3 = (0.0, 0.0, 0.0)
DEFAULT_AXIS: Vector3 = (1.0, 0.0, 0.0)


def _source() -> Location | None:
    # Locations never take part in equality: a robot written out and read back is equal.
    return field(default=None, compare=False, repr=False)


class JointType(str, Enum):
    """The six URDF joint types."""

    REVOLUTE = "revolute"
    CONTINUOUS = "continuous"
    PRISMATIC = "prismatic"
    FIXED = "fixed"
    FLOATING = "floating"
    PLANAR = "planar"

    @property
    def needs_limit(self) -> bool:
        """Revolute and prismatic joints must carry a <limit>."""
        return self in (JointType.REVOLUTE, JointType.PRISMATIC)

    @property
    def uses_axis(self) -> bool:
        """Joints whose motion is defined by their axis."""
        return self in (
            JointType.REVOLUTE,
            JointType.CONTINUOUS,
            JointType.PRISMATIC,
            JointType.PLANAR,
        )


@dataclass(frozen=True, slots=True)
class Origin:
    """A pose: translation ``xyz`` (metres), then fixed-axis roll, pitch, yaw ``rpy`` (radians)."""

    xyz: Vector3 = ZERO3
    rpy: Vector3 = ZERO3
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Box:
    """A box centred on its origin; ``size`` is x, y, z in metres."""

    size: Vector3
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Cylinder:
    """A cylinder along its z axis, centred on its origin (metres)."""

    radius: float
    length: float
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Sphere:
    """A sphere centred on its origin (metres)."""

    radius: float
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Mesh:
    """A mesh file (``package://``, ``file://`` or a path), optionally scaled per axis."""

    filename: str
    scale: Vector3 | None = None
    source: Location | None = _source()


Geometry = Box | Cylinder | Sphere | Mesh
"""Any shape a ``<geometry>`` holds."""


@dataclass(frozen=True, slots=True)
class Material:
    """A material: a name, and optionally a colour (RGBA in 0..1) and a texture file."""

    name: str
    color: Rgba | None = None
    texture: str | None = None
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Visual:
    """What a link looks like."""

    geometry: Geometry
    origin: Origin = Origin()
    material: Material | None = None
    name: str | None = None
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Collision:
    """The shape a link collides with."""

    geometry: Geometry
    origin: Origin = Origin()
    name: str | None = None
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Inertia:
    """The six independent entries of the symmetric 3x3 inertia matrix (kg*m^2)."""

    ixx: float = 0.0
    ixy: float = 0.0
    ixz: float = 0.0
    iyy: float = 0.0
    iyz: float = 0.0
    izz: float = 0.0
    source: Location | None = _source()

    def matrix(self) -> tuple[Vector3, Vector3, Vector3]:
        """The full symmetric matrix as nested tuples (rows)."""
        return (
            (self.ixx, self.ixy, self.ixz),
            (self.ixy, self.iyy, self.iyz),
            (self.ixz, self.iyz, self.izz),
        )


@dataclass(frozen=True, slots=True)
class Inertial:
    """Mass (kg) and inertia (kg*m^2) about the centre of mass at ``origin``."""

    mass: float = 0.0
    inertia: Inertia = Inertia()
    origin: Origin = Origin()
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Link:
    """A rigid body. ``extras`` keeps child elements URDF does not define, as XML text."""

    name: str
    inertial: Inertial | None = None
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Collision, ...] = ()
    extras: tuple[str, ...] = ()
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Limit:
    """Joint limits: position (rad or m), effort (N*m or N), velocity (rad/s or m/s)."""

    effort: float
    velocity: float
    lower: float = 0.0
    upper: float = 0.0
    source: Location | None = _source()
    unset: tuple[str, ...] = field(default=(), compare=False, repr=False)
    """The bounds the file left out (``lower``, ``upper``), read as 0 as urdfdom reads them."""


@dataclass(frozen=True, slots=True)
class Dynamics:
    """Joint damping and static friction."""

    damping: float = 0.0
    friction: float = 0.0
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Calibration:
    """Positions of the joint's reference edges, when the joint has them."""

    rising: float | None = None
    falling: float | None = None
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Mimic:
    """This joint follows ``joint``: value = multiplier * other + offset."""

    joint: str
    multiplier: float = 1.0
    offset: float = 0.0
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class SafetyController:
    """Soft limits and the gains that enforce them."""

    k_velocity: float
    k_position: float = 0.0
    soft_lower_limit: float = 0.0
    soft_upper_limit: float = 0.0
    source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Joint:
    """A joint from ``parent`` link to ``child`` link. ``axis`` defaults to 1 0 0 (URDF spec)."""

    name: str
    type: JointType
    parent: str
    child: str
    origin: Origin = Origin()
    axis: Vector3 = DEFAULT_AXIS
    limit: Limit | None = None
    dynamics: Dynamics | None = None
    calibration: Calibration | None = None
    mimic: Mimic | None = None
    safety_controller: SafetyController | None = None
    extras: tuple[str, ...] = ()
    source: Location | None = _source()
    parent_source: Location | None = _source()
    child_source: Location | None = _source()


@dataclass(frozen=True, slots=True)
class Robot:
    """A whole robot description.

    ``materials`` are the top-level <material> elements; ``extras`` keeps every top-level
    element URDF does not define (gazebo, transmission, ros2_control, ...) as XML text.
    ``extra_places`` gives, for each of ``extras`` that names parts of the robot (gazebo,
    transmission, ros2_control), where each element in it is written, in document order
    (empty when the reader had no places, or for other extras).
    """

    name: str
    links: tuple[Link, ...] = ()
    joints: tuple[Joint, ...] = ()
    materials: tuple[Material, ...] = ()
    version: str | None = None
    extras: tuple[str, ...] = ()
    source: Location | None = _source()
    extra_places: tuple[tuple[Location | None, ...], ...] = field(
        default=(), compare=False, repr=False
    )

    def link(self, name: str) -> Link:
        """The link called ``name``. Linear in the number of links.

        Raises:
            UnknownNameError: There is none (a KeyError too).
        """
        for link in self.links:
            if link.name == name:
                return link
        raise UnknownNameError("link", name, (link.name for link in self.links))

    def joint(self, name: str) -> Joint:
        """The joint called ``name``. Linear in the number of joints.

        Raises:
            UnknownNameError: There is none (a KeyError too).
        """
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise UnknownNameError("joint", name, (joint.name for joint in self.joints))
