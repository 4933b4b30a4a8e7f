"""What Gazebo's sensors see, as triangles in their link's frame: a lidar's fan of rays from
its minimum to its maximum range with the arc at the maximum, a camera's frustum; each at
the sensor's pose on its link. A setting not written is sdformat's default."""

from __future__ import annotations

import math
from typing import Any

from ..analysis.sensors import Camera, Rays, Scan, Sensor
from ..spatial import Pose
from ._marks import Mark
from ._shapes import box

__all__ = [
    "CAMERA",
    "CAMERA_DEPTH",
    "COLUMNS",
    "LIDAR",
    "LIDAR_DEPTH",
    "LIDAR_ROBOTS",
    "LINE",
    "ROWS",
    "reach",
    "sensor_marks",
]

LIDAR = (1.0, 0.5, 0.0, 1.0)  # orange: neither an axis' colour nor the mass' red
CAMERA = (0.6, 0.2, 0.9, 1.0)  # purple
COLUMNS = 60
"""The most rays of one row of a lidar's scan drawn: every k-th sample, k = ceil((samples -
1) / (COLUMNS - 1)), from the first, and the last one."""
ROWS = 8
"""The most rows of a 3D lidar's scan drawn, taken as its columns are."""
CAMERA_DEPTH = 1.0
"""How deep a camera's frustum is drawn at most (metres): to its far clip when nearer. A far
clip of hundreds of metres would dwarf the robot."""
LIDAR_DEPTH = 2.0
"""How far a lidar's rays are drawn at least (metres): to its maximum range when nearer, else
to the larger of this and :data:`LIDAR_ROBOTS` times the robot's size; a scan of 30 m would
make the robot a speck. Rays cut short end without the arc of the maximum range."""
LIDAR_ROBOTS = 4.0
_ARC_STEP = math.radians(3)  # the arc at the maximum range, in straight pieces this long
LINE = 0.003
"""A ray or a frustum's edge is this share of the drawing's size thick: about a pixel."""
_SIDE_ALPHA = 0.15  # a frustum's sides: seen through, what it sees shows

# sdformat's defaults of what is not written (sdf/1.9/ray.sdf, camera.sdf)
_SAMPLES, _VERTICAL_SAMPLES = 640, 1
_FOV, _WIDTH, _HEIGHT, _NEAR, _FAR = 1.047, 320, 240, 0.1, 100.0


def reach(sensor: Sensor, depth: float = math.inf) -> float:
    """How far from the sensor its marks go, at most (metres): its lidar's maximum range (to
    ``depth`` at most), its cameras' frustums' depth; 0 for another sensor."""
    far = [min(rays.range_max or 0.0, depth) for rays in sensor.rays]
    far += [_view(camera)[-1] for camera in sensor.cameras]
    return max(far, default=0.0)


def sensor_marks(np: Any, sensor: Sensor, size: float, depth: float = math.inf) -> list[Mark]:
    """The marks of a lidar's rays (at most :data:`COLUMNS` of a row, at most :data:`ROWS`
    rows) and of each camera's frustum (:data:`CAMERA_DEPTH` deep at most), posed in the
    frame of the sensor's link, their lines :data:`LINE` of ``size`` (metres: the size of
    the picture's subject) thick, the rays ``depth`` long at most; none for another sensor,
    or a lidar with no maximum range beyond its minimum."""
    thick = LINE * size
    marks: list[Mark] = []
    for rays in sensor.rays:
        segments = _fan(np, rays, depth)
        if segments is not None:
            segments = _placed(np, sensor.pose, segments)
            marks.append(Mark(_lines(np, segments, thick), LIDAR, "sensors", segments))
    for camera in sensor.cameras:
        pose = sensor.pose.then(camera.pose)
        edges, sides = _frustum(np, camera)
        if edges is None:
            continue
        edges = _placed(np, pose, edges)
        marks.append(Mark(_lines(np, edges, thick), CAMERA, "sensors", edges))
        marks.append(Mark(_placed(np, pose, sides), (*CAMERA[:3], _SIDE_ALPHA), "sensors"))
    return marks


def _angles(scan: Scan | None, default: int, most: int) -> list[float]:
    """The angles of a scan's rays drawn (radians): its samples from the first to the last,
    every k-th, at most ``most``, the last one always."""
    if scan is None:
        return [0.0]
    samples = int(scan.samples if scan.samples is not None and scan.samples >= 1 else default)
    low = scan.min_angle or 0.0
    high = scan.max_angle if scan.max_angle is not None else 0.0
    if samples == 1 or high <= low:
        return [low]
    step = (high - low) / (samples - 1)
    every = math.ceil((samples - 1) / (most - 1)) if most > 1 else samples
    picked = list(range(0, samples, every))
    if picked[-1] != samples - 1:
        picked.append(samples - 1)
    return [low + i * step for i in picked]


def _fan(np: Any, rays: Rays, depth: float) -> Any:
    """The rays (``depth`` long at most) and the arcs at the maximum range (when they reach
    it), as segments (N, 2, 3) in the sensor's frame; None when there is no range to draw."""
    far = rays.range_max
    near = max(rays.range_min or 0.0, 0.0)
    if far is None or not far > near:
        return None
    cut = far > depth
    far = min(far, max(depth, near))
    columns = _angles(rays.horizontal, _SAMPLES, COLUMNS)
    rows = _angles(rays.vertical, _VERTICAL_SAMPLES, ROWS)
    h = np.array(columns)[None, :]
    v = np.array(rows)[:, None]
    ways = np.stack(
        [np.cos(v) * np.cos(h), np.cos(v) * np.sin(h), np.sin(v) * np.ones_like(h)], axis=-1
    ).reshape(-1, 3)
    segments = [np.stack([near * ways, far * ways], axis=1)]
    low, high = columns[0], columns[-1]
    if high > low and not cut:
        pieces = max(1, math.ceil((high - low) / _ARC_STEP))
        a = np.linspace(low, high, pieces + 1)[None, :]
        arc = far * np.stack(
            [np.cos(v) * np.cos(a), np.cos(v) * np.sin(a), np.sin(v) * np.ones_like(a)], axis=-1
        )
        segments.append(np.stack([arc[:, :-1], arc[:, 1:]], axis=2).reshape(-1, 2, 3))
    return np.concatenate(segments)


def _frustum(np: Any, camera: Camera) -> tuple[Any, Any]:
    """A camera's frustum along its x axis: its edges as segments (N, 2, 3) from its origin
    to the far corners, round the near and far rectangles, and its four sides as triangles;
    (None, None) when it sees nothing."""
    fov, width, height, near, depth = _view(camera)
    if not (0 < fov < math.pi) or not depth > max(near, 0.0):
        return None, None
    across = math.tan(fov / 2)
    up = across * height / width

    def rectangle(x: float) -> Any:  # counter-clockwise seen from behind the camera
        return np.array(
            [
                [x, x * across, x * up],
                [x, -x * across, x * up],
                [x, -x * across, -x * up],
                [x, x * across, -x * up],
            ]
        )

    far_corners = rectangle(depth)
    origin = np.zeros((4, 3))
    edges = [np.stack([origin, far_corners], axis=1)]
    for x in (near, depth) if near > 0 else (depth,):
        corners = rectangle(x)
        edges.append(np.stack([corners, np.roll(corners, -1, axis=0)], axis=1))
    sides = np.stack([origin, far_corners, np.roll(far_corners, -1, axis=0)], axis=1)
    return np.concatenate(edges), sides


def _view(camera: Camera) -> tuple[float, float, float, float, float]:
    """A camera's field of view, image width and height, near clip and the depth its
    frustum is drawn to, sdformat's defaults for what is not written."""
    fov = camera.horizontal_fov if camera.horizontal_fov is not None else _FOV
    width = camera.width if camera.width is not None and camera.width >= 1 else _WIDTH
    height = camera.height if camera.height is not None and camera.height >= 1 else _HEIGHT
    near = camera.near if camera.near is not None else _NEAR
    far = camera.far if camera.far is not None else _FAR
    depth = min(far, CAMERA_DEPTH) if near < CAMERA_DEPTH else far
    return fov, width, height, near, depth


def _lines(np: Any, segments: Any, thick: float) -> Any:
    """Each segment (N, 2, 3) as a box ``thick`` square across: triangles (12 N, 3, 3)."""
    start, end = segments[:, 0], segments[:, 1]
    along = end - start
    length = np.linalg.norm(along, axis=1)
    keep = length > 0
    start, along, length = start[keep], along[keep], length[keep]
    u = along / length[:, None]
    helper = np.where(np.abs(u[:, 2:3]) < 0.9, [[0.0, 0.0, 1.0]], [[1.0, 0.0, 0.0]])
    v = np.cross(u, helper)
    v /= np.linalg.norm(v, axis=1)[:, None]
    w = np.cross(u, v)
    unit = box(np, 1.0, 1.0, 1.0) + np.array([0.5, 0.0, 0.0])  # x from 0 to 1
    sizes = np.stack([length, np.full_like(length, thick), np.full_like(length, thick)], axis=1)
    turn = np.stack([u, v, w], axis=2)  # columns: the box's x, y and z
    scaled = unit[None] * sizes[:, None, None, :]  # (N, 12, 3, 3)
    placed = np.einsum("nij,ntcj->ntci", turn, scaled) + start[:, None, None, :]
    return placed.reshape(-1, 3, 3)


def _placed(np: Any, pose: Pose, triangles: Any) -> Any:
    """Triangles (or segments) in the sensor's frame, in its link's."""
    return triangles @ np.array(pose.rotation).T + np.array(pose.translation)
