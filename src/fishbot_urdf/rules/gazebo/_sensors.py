"""Gazebo sensors held to the robot: the link each is on, its settings, where its rays start."""

from __future__ import annotations

import math
from collections.abc import Iterator

from lxml import etree

from ...analysis import Analysis
from ...analysis.gazebo import Block, number, text
from ...catalog.gazebo import SENSOR_REFERENCE, SENSOR_SELF_HIT, SENSOR_SETTINGS
from ...diagnostics import Diagnostic, Kind, Subject
from ...model import Box, Cylinder, Geometry, Sphere
from ...spatial import Pose, mat_vec, rpy_matrix, transpose

__all__ = ["sensors"]

_RAYS = ("ray", "gpu_ray", "lidar", "gpu_lidar")
# Rays cast through the physics engine's collision shapes; a GPU one renders the visuals.
_PHYSICS_RAYS = ("ray", "lidar")
_CAMERAS = ("camera", "depth", "depth_camera", "rgbd_camera", "rgbd", "multicamera")
_DIRECTIONS = 360  # ray directions looked at, at most
_EPS = 1e-9


def sensors(analysis: Analysis, block: Block, *, select: frozenset[str]) -> Iterator[Diagnostic]:
    """Findings about the sensors of ``block``, of the rules in ``select``."""
    if block.element.tag != "gazebo":
        return
    for sensor in block.element.iter("sensor"):
        kind = sensor.get("type") or ""
        label = f"sensor {sensor.get('name') or ''!r} ({kind})"
        if SENSOR_REFERENCE.id in select:
            yield from _reference(analysis, block, sensor, label, kind)
        if SENSOR_SETTINGS.id in select:
            for message, hint in _settings(sensor, kind):
                yield SENSOR_SETTINGS.report(
                    f"{label}: {message}",
                    block.where,
                    path=analysis.path,
                    subject=_subject(analysis, block),
                    hint=hint,
                )
        if SENSOR_SELF_HIT.id in select and kind in _PHYSICS_RAYS:
            yield from _self_hit(analysis, block, sensor, label)


def _subject(analysis: Analysis, block: Block) -> Subject:
    if block.reference in analysis.links:
        return Subject(Kind.LINK, block.reference or "")
    return Subject(Kind.ROBOT, analysis.robot.name)


def _reference(
    analysis: Analysis, block: Block, sensor: etree._Element, label: str, kind: str
) -> Iterator[Diagnostic]:
    name = block.reference
    if name is None:
        message = f"{label} is in a <gazebo> block with no reference, so no link holds it"
    elif name in analysis.links or name not in analysis.joints:
        return  # a link, or a name of nothing (unknown-reference's)
    elif kind == "force_torque":
        return  # a joint's sensor
    else:
        message = f"{label} is in <gazebo reference={name!r}>, which names a joint, not a link"
    links = analysis.links
    child = analysis.joints[name].child if name is not None and name in analysis.joints else None
    hint = f"write <gazebo reference={child!r}>" if child in links else "name the sensor's link"
    yield SENSOR_REFERENCE.report(
        message,
        block.where,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, analysis.robot.name),
        hint=hint,
    )


def _settings(sensor: etree._Element, kind: str) -> Iterator[tuple[str, str]]:
    if kind in _CAMERAS:
        for camera in sensor.iter("camera"):
            fov = number(camera, "horizontal_fov")
            if fov is not None and not 0 < fov < math.pi:
                yield (
                    f"<horizontal_fov> is {fov:g}, outside (0, pi) radians",
                    f"write it in radians ({fov:g} degrees is {math.radians(fov):.4f})"
                    if fov > math.pi
                    else "a camera sees a field of view between 0 and pi radians",
                )
            for side in ("width", "height"):
                size = number(camera, f"image/{side}")
                if size is not None and size < 1:
                    yield f"image <{side}> is {size:g}", "an image is at least 1 pixel each way"
            yield from _order(camera, "clip/near", "clip/far", "clip")
    if kind in _RAYS:
        for ray in (*sensor.iter("ray"), *sensor.iter("lidar")):
            samples = number(ray, "scan/horizontal/samples")
            if samples is not None and samples < 1:
                yield f"scan <samples> is {samples:g}", "a scan has at least 1 sample"
            low = number(ray, "scan/horizontal/min_angle")
            high = number(ray, "scan/horizontal/max_angle")
            many = samples is None or samples > 1
            if low is not None and high is not None and (low > high or (low == high and many)):
                yield (
                    f"scan <min_angle> {low:g} is not below <max_angle> {high:g}",
                    "write the scan's angles from low to high (radians)",
                )
            yield from _order(ray, "range/min", "range/max", "range")


def _order(element: etree._Element, low: str, high: str, what: str) -> Iterator[tuple[str, str]]:
    near, far = number(element, low), number(element, high)
    if near is not None and far is not None and near >= far:
        yield (
            f"<{what}> minimum {near:g} m is not below its maximum {far:g} m",
            "write the minimum below the maximum (metres)",
        )


def _self_hit(
    analysis: Analysis, block: Block, sensor: etree._Element, label: str
) -> Iterator[Diagnostic]:
    name = block.reference
    poses = analysis.zero_poses
    if name is None or name not in poses:
        return
    ray = sensor.find("ray")
    if ray is None:
        ray = sensor.find("lidar")
    if ray is None:
        return
    shortest = number(ray, "range/min")
    if shortest is None:
        return
    frame = poses[name].then(_pose(text(sensor, "pose")))
    directions = _directions(ray)
    for link in analysis.robot.links:
        if link.name not in poses:
            continue
        for collision in link.collisions:
            shape = poses[link.name].then(Pose.of(collision.origin))
            back = transpose(shape.rotation)
            start = shape.inverse().apply(frame.translation)
            if not _inside(collision.geometry, start):
                continue
            way_out = max(
                _exit(collision.geometry, start, mat_vec(back, mat_vec(frame.rotation, d)))
                for d in directions
            )
            if shortest < way_out - 1e-6:
                yield SENSOR_SELF_HIT.report(
                    f"{label} on {name!r} starts inside link {link.name!r}'s collision shape, "
                    f"and its rays leave it only after {way_out:.3g} m, but its minimum range "
                    f"is {shortest:g} m",
                    block.where,
                    path=analysis.path,
                    subject=Subject(Kind.LINK, name),
                    hint=f"raise the sensor out of the shape, or set <min> to {way_out:.3g} or "
                    "more",
                )
                return


def _pose(written: str | None) -> Pose:
    try:
        values = [float(v) for v in (written or "").split()]
    except ValueError:
        return Pose()
    if len(values) != 6:
        return Pose()
    x, y, z, roll, pitch, yaw = values
    return Pose(rpy_matrix((roll, pitch, yaw)), (x, y, z))


def _directions(ray: etree._Element) -> list[tuple[float, float, float]]:
    """The horizontal directions of a scan's rays in the sensor's frame (at most 360)."""
    low = number(ray, "scan/horizontal/min_angle") or 0.0
    high = number(ray, "scan/horizontal/max_angle") or 0.0
    samples = int(number(ray, "scan/horizontal/samples") or 1)
    count = max(1, min(samples, _DIRECTIONS))
    if count == 1 or high <= low:
        angles = [low]
    else:
        angles = [low + (high - low) * i / (count - 1) for i in range(count)]
    return [(math.cos(a), math.sin(a), 0.0) for a in angles]


def _inside(shape: Geometry, p: tuple[float, float, float]) -> bool:
    x, y, z = p
    if isinstance(shape, Box):
        return all(abs(v) < s / 2 - _EPS for v, s in zip(p, shape.size, strict=True))
    if isinstance(shape, Cylinder):
        return x * x + y * y < shape.radius**2 and abs(z) < shape.length / 2
    if isinstance(shape, Sphere):
        return x * x + y * y + z * z < shape.radius**2
    return False  # a mesh's inside is not judged


def _exit(shape: Geometry, p: tuple[float, float, float], d: tuple[float, float, float]) -> float:
    """How far from ``p``, inside ``shape``, along unit ``d`` the shape's surface is."""
    if isinstance(shape, Box):
        return min(_slab(v, w, s / 2) for v, w, s in zip(p, d, shape.size, strict=True))
    if isinstance(shape, Cylinder):
        a = d[0] ** 2 + d[1] ** 2
        if a > _EPS:
            b = p[0] * d[0] + p[1] * d[1]
            c = p[0] ** 2 + p[1] ** 2 - shape.radius**2
            radial = (-b + math.sqrt(max(b * b - a * c, 0.0))) / a
        else:
            radial = math.inf
        return min(radial, _slab(p[2], d[2], shape.length / 2))
    if isinstance(shape, Sphere):
        b = sum(v * w for v, w in zip(p, d, strict=True))
        c = sum(v * v for v in p) - shape.radius**2
        return -b + math.sqrt(max(b * b - c, 0.0))
    return 0.0


def _slab(v: float, w: float, half: float) -> float:
    if abs(w) < _EPS:
        return math.inf
    return ((half if w > 0 else -half) - v) / w
