"""Gazebo sensors held to the robot: the link each is on, its settings, where its rays start."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ...analysis import Analysis
from ...analysis.gazebo import Block
from ...analysis.sensors import Scan, Sensor
from ...catalog.gazebo import SENSOR_REFERENCE, SENSOR_SELF_HIT, SENSOR_SETTINGS
from ...diagnostics import Diagnostic, Kind, Subject
from ...model import Box, Cylinder, Geometry, Sphere
from ...spatial import Pose, mat_vec, transpose

__all__ = ["sensors"]

# Rays cast through the physics engine's collision shapes; a GPU one renders the visuals.
_PHYSICS_RAYS = ("ray", "lidar")
_DIRECTIONS = 360  # ray directions looked at, at most
_EPS = 1e-9


def sensors(analysis: Analysis, block: Block, *, select: frozenset[str]) -> Iterator[Diagnostic]:
    """Findings about the sensors of ``block``, of the rules in ``select``."""
    for sensor in analysis.sensors:
        if sensor.block is not block:
            continue
        label = f"sensor {sensor.name!r} ({sensor.kind})"
        if SENSOR_REFERENCE.id in select:
            yield from _reference(analysis, sensor, label)
        if SENSOR_SETTINGS.id in select:
            for message, hint in _settings(sensor):
                yield SENSOR_SETTINGS.report(
                    f"{label}: {message}",
                    sensor.where,
                    path=analysis.path,
                    subject=_subject(analysis, sensor),
                    hint=hint,
                )
        if SENSOR_SELF_HIT.id in select and sensor.kind in _PHYSICS_RAYS:
            yield from _self_hit(analysis, sensor, label)


def _subject(analysis: Analysis, sensor: Sensor) -> Subject:
    if sensor.link in analysis.links:
        return Subject(Kind.LINK, sensor.link or "")
    return Subject(Kind.ROBOT, analysis.robot.name)


def _reference(analysis: Analysis, sensor: Sensor, label: str) -> Iterator[Diagnostic]:
    name = sensor.link
    if name is None:
        message = f"{label} is in a <gazebo> block with no reference, so no link holds it"
    elif name in analysis.links or name not in analysis.joints:
        return  # a link, or a name of nothing (unknown-reference's)
    elif sensor.kind == "force_torque":
        return  # a joint's sensor
    else:
        message = f"{label} is in <gazebo reference={name!r}>, which names a joint, not a link"
    links = analysis.links
    child = analysis.joints[name].child if name is not None and name in analysis.joints else None
    hint = f"write <gazebo reference={child!r}>" if child in links else "name the sensor's link"
    yield SENSOR_REFERENCE.report(
        message,
        sensor.where,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, analysis.robot.name),
        hint=hint,
    )


def _settings(sensor: Sensor) -> Iterator[tuple[str, str]]:
    for camera in sensor.cameras:
        fov = camera.horizontal_fov
        if fov is not None and not 0 < fov < math.pi:
            yield (
                f"<horizontal_fov> is {fov:g}, outside (0, pi) radians",
                f"write it in radians ({fov:g} degrees is {math.radians(fov):.4f})"
                if fov > math.pi
                else "a camera sees a field of view between 0 and pi radians",
            )
        for side, size in (("width", camera.width), ("height", camera.height)):
            if size is not None and size < 1:
                yield f"image <{side}> is {size:g}", "an image is at least 1 pixel each way"
        yield from _order(camera.near, camera.far, "clip")
    for rays in sensor.rays:
        scan = rays.horizontal
        samples = scan.samples
        if samples is not None and samples < 1:
            yield f"scan <samples> is {samples:g}", "a scan has at least 1 sample"
        low, high = scan.min_angle, scan.max_angle
        many = samples is None or samples > 1
        if low is not None and high is not None and (low > high or (low == high and many)):
            yield (
                f"scan <min_angle> {low:g} is not below <max_angle> {high:g}",
                "write the scan's angles from low to high (radians)",
            )
        yield from _order(rays.range_min, rays.range_max, "range")


def _order(near: float | None, far: float | None, what: str) -> Iterator[tuple[str, str]]:
    if near is not None and far is not None and near >= far:
        yield (
            f"<{what}> minimum {near:g} m is not below its maximum {far:g} m",
            "write the minimum below the maximum (metres)",
        )


def _self_hit(analysis: Analysis, sensor: Sensor, label: str) -> Iterator[Diagnostic]:
    name = sensor.link
    poses = analysis.zero_poses
    if name is None or name not in poses or not sensor.rays:
        return
    rays = sensor.rays[0]
    shortest = rays.range_min
    if shortest is None:
        return
    frame = poses[name].then(sensor.pose)
    directions = _directions(rays.horizontal)
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
                    f"is {shortest:g} m: rays that start inside hit the shape, and the scan sees "
                    "the robot itself",
                    sensor.where,
                    path=analysis.path,
                    subject=Subject(Kind.LINK, name),
                    hint=f"raise the sensor out of the shape, or set <min> to {way_out:.3g} or "
                    "more",
                )
                return


def _directions(scan: Scan) -> list[tuple[float, float, float]]:
    """The horizontal directions of a scan's rays in the sensor's frame (at most 360)."""
    low = scan.min_angle or 0.0
    high = scan.max_angle or 0.0
    samples = int(scan.samples or 1)
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
