"""Where the viewer's camera starts: looking at the robot from the front left and above,
as near as it can be with every point of the robot in view."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

__all__ = ["EYE", "FILL", "FOV", "Framing", "aim", "corners", "framing"]

EYE = (1.0, 0.75, 0.65)  # the direction the camera looks from: front left, above (as RViz)
FILL = 0.85  # of the view's height the robot's farthest point from the middle reaches
FOV = math.radians(45)  # vertical field of view: RViz's; a wider one distorts more
_ROUNDS = 3  # of centring: the picture moves by less than a pixel after them
_SMALLEST = 0.05  # metres: the view of a robot of one point (or of none)


@dataclass(frozen=True)
class Framing:
    """A camera: where it is and what it looks at (metres, the root link's frame), which
    way is up, its near and far clipping distances, and its vertical field of view
    (radians)."""

    position: tuple[float, float, float]
    look_at: tuple[float, float, float]
    up: tuple[float, float, float]
    near: float
    far: float
    fov: float


def framing(np: Any, points: Any, aspect: float = 1.0, fov: float = FOV) -> Framing:
    """The camera of vertical field of view ``fov`` (radians) that sees ``points`` (N, 3)
    from :data:`EYE` in a view ``aspect`` times as wide as high, from as near as keeps
    each of them within :data:`FILL` of the way from the middle to the view's edges, and
    looking where the robot is seen in the middle (the near side of a robot looks bigger:
    the point looked at is moved until the picture is centred)."""
    low, high = points.min(axis=0), points.max(axis=0)
    size = float(max(np.max(high - low), _SMALLEST))
    back = np.array(EYE) / np.linalg.norm(EYE)  # from what is looked at to the camera
    right = np.cross(-back, np.array([0.0, 0.0, 1.0]))
    right /= np.linalg.norm(right)
    up = np.cross(right, -back)
    reach = math.tan(fov / 2) * FILL
    axes = np.stack([right, up])
    widths = np.array([max(aspect, 1e-3), 1.0])  # of the view, sideways and up, as its height

    def distance_from(centre: Any) -> float:
        # A point at offset a is in view from distance d when |a . up| is at most
        # tan(fov / 2) FILL times its depth, d - a . back, and |a . right| the aspect
        # times that.
        offsets = points - centre
        side = (np.abs(offsets @ axes.T) / widths).max(axis=1)
        return float(max(np.max(side / reach + offsets @ back), _SMALLEST / 2 / reach))

    centre = (low + high) / 2
    for _ in range(_ROUNDS):
        distance = distance_from(centre)
        offsets = points - centre
        angles = (offsets @ axes.T) / (distance - offsets @ back)[:, None]
        middle = (angles.min(axis=0) + angles.max(axis=0)) / 2  # where the picture's is
        centre = centre + distance * (middle @ axes)
    distance = distance_from(centre)
    return Framing(
        position=_point(centre + distance * back),
        look_at=_point(centre),
        up=(0.0, 0.0, 1.0),
        near=size / 100,
        far=100 * max(size, distance),
        fov=fov,
    )


def corners(np: Any, points: Any) -> Any:
    """The eight corners (8, 3) of the box around ``points`` (N, 3): framed, they keep the
    whole box in view, whatever is inside it."""
    low, high = points.min(axis=0), points.max(axis=0)
    picks = np.array([[k >> i & 1 for i in range(3)] for k in range(8)], dtype=bool)
    return np.where(picks, high, low)


def aim(camera: Any, view: Framing) -> None:
    """Set a viser camera to ``view``: a page's (whose ``position`` moves its ``look_at``
    along, so the point looked at comes last), or the one pages open with."""
    camera.fov = view.fov
    if hasattr(camera, "up_direction"):  # a page's
        camera.up_direction = view.up
    else:
        camera.up = view.up
    camera.position = view.position
    camera.look_at = view.look_at
    camera.near, camera.far = view.near, view.far


def _point(vector: Any) -> tuple[float, float, float]:
    x, y, z = (float(c) for c in vector)
    return (x, y, z)
