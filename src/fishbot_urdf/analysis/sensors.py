"""The sensors of the robot's ``<gazebo>`` blocks, read once: the link each is on, where on it,
and what a lidar's rays or a camera's view are as written, for the checks and the drawings.

A setting is None when it is not written or is no finite number (a xacro expression left
unexpanded): the checks judge what is written, a drawing fills in sdformat's defaults.
"""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from ..model import Location
from ..spatial import Pose, rpy_matrix
from .gazebo import Block, number, text

__all__ = ["CAMERAS", "RAYS", "Camera", "Rays", "Scan", "Sensor", "sdf_pose", "sensors"]

RAYS = ("ray", "gpu_ray", "lidar", "gpu_lidar")
"""The sensor types that cast rays (Gazebo Classic's ``ray``, ``gpu_ray``; gz-sim's
``lidar``, ``gpu_lidar``)."""

CAMERAS = ("camera", "depth", "depth_camera", "rgbd_camera", "rgbd", "multicamera")
"""The sensor types that see through one or more ``<camera>``."""


@dataclass(frozen=True, slots=True)
class Scan:
    """One direction of a lidar's scan (``<scan><horizontal>`` or ``<vertical>``).

    Attributes:
        samples: How many rays, from ``min_angle`` to ``max_angle``.
        min_angle: The first ray's angle (radians; about the sensor's z axis for the
            horizontal scan, from its x-y plane up for the vertical one).
        max_angle: The last ray's angle (radians).
    """

    samples: float | None
    min_angle: float | None
    max_angle: float | None


@dataclass(frozen=True, slots=True)
class Rays:
    """A ``<ray>`` or ``<lidar>`` element: the scan and the range of its rays.

    Attributes:
        horizontal: Its ``<scan><horizontal>`` (every field None when not written).
        vertical: Its ``<scan><vertical>``; None when not written (one row of rays).
        range_min: Where the rays start, from the sensor (metres).
        range_max: Where they end (metres).
    """

    horizontal: Scan
    vertical: Scan | None
    range_min: float | None
    range_max: float | None


@dataclass(frozen=True, slots=True)
class Camera:
    """A ``<camera>`` element: what it sees, along its x axis.

    Attributes:
        horizontal_fov: Its field of view across (radians).
        width: Its image's width (pixels).
        height: Its image's height (pixels).
        near: Its near clip plane (metres).
        far: Its far clip plane (metres).
        pose: Its ``<pose>`` in the sensor's frame (a multicamera's cameras have one each).
    """

    horizontal_fov: float | None
    width: float | None
    height: float | None
    near: float | None
    far: float | None
    pose: Pose


@dataclass(frozen=True, slots=True)
class Sensor:
    """A ``<sensor>`` of a ``<gazebo>`` block.

    Attributes:
        kind: Its ``type`` (``ray``, ``camera``, ``imu``, ...; "" when not written).
        name: Its ``name`` ("" when not written).
        link: Its block's ``reference`` (a link's name when written right; None for a block
            about the whole robot).
        pose: Its ``<pose>`` in that link's frame (identity when not written, or not six
            numbers).
        update_rate: Its ``<update_rate>`` (Hz).
        rays: Its ``<ray>`` and ``<lidar>`` elements, for a sensor of a :data:`RAYS` type
            (one, as a rule), else none.
        cameras: Its ``<camera>`` elements, for a sensor of a :data:`CAMERAS` type (a
            multicamera's several), else none.
        where: Where its block is written, when the reader said.
        block: Its block.
    """

    kind: str
    name: str
    link: str | None
    pose: Pose
    update_rate: float | None
    rays: tuple[Rays, ...]
    cameras: tuple[Camera, ...]
    where: Location | None
    block: Block


def sensors(blocks: tuple[Block, ...]) -> tuple[Sensor, ...]:
    """Every ``<sensor>`` of the ``<gazebo>`` blocks among ``blocks``, in file order."""
    found: list[Sensor] = []
    for block in blocks:
        if block.element.tag != "gazebo":
            continue
        for element in block.element.iter("sensor"):
            kind = element.get("type") or ""
            rays = (*element.iter("ray"), *element.iter("lidar")) if kind in RAYS else ()
            cameras = tuple(element.iter("camera")) if kind in CAMERAS else ()
            found.append(
                Sensor(
                    kind=kind,
                    name=element.get("name") or "",
                    link=block.reference,
                    pose=sdf_pose(text(element, "pose")),
                    update_rate=number(element, "update_rate"),
                    rays=tuple(_rays(ray) for ray in rays),
                    cameras=tuple(_camera(camera) for camera in cameras),
                    where=block.where,
                    block=block,
                )
            )
    return tuple(found)


def sdf_pose(written: str | None) -> Pose:
    """An SDF ``<pose>`` (x y z roll pitch yaw, metres and radians) as a Pose; identity when
    not written or not six numbers."""
    try:
        values = [float(v) for v in (written or "").split()]
    except ValueError:
        return Pose()
    if len(values) != 6:
        return Pose()
    x, y, z, roll, pitch, yaw = values
    return Pose(rpy_matrix((roll, pitch, yaw)), (x, y, z))


def _rays(element: etree._Element) -> Rays:
    vertical = element.find("scan/vertical")
    return Rays(
        horizontal=_scan(element, "scan/horizontal"),
        vertical=None if vertical is None else _scan(element, "scan/vertical"),
        range_min=number(element, "range/min"),
        range_max=number(element, "range/max"),
    )


def _scan(element: etree._Element, path: str) -> Scan:
    return Scan(
        samples=number(element, f"{path}/samples"),
        min_angle=number(element, f"{path}/min_angle"),
        max_angle=number(element, f"{path}/max_angle"),
    )


def _camera(element: etree._Element) -> Camera:
    return Camera(
        horizontal_fov=number(element, "horizontal_fov"),
        width=number(element, "image/width"),
        height=number(element, "image/height"),
        near=number(element, "clip/near"),
        far=number(element, "clip/far"),
        pose=sdf_pose(text(element, "pose")),
    )
