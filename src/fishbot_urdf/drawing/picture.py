"""A shaded picture of a scene, made in numpy: no display, no GPU, no library beyond numpy.

An orthographic camera looks at the scene from one of four views and frames all of it. The
triangles are rasterised with a depth buffer at twice the asked size (every pixel's four
samples averaged: smooth edges), lit by a light from over the viewer's left shoulder, and
written as an RGB PNG with the standard library's zlib. A shape whose colour has an alpha
below 1 is seen through: at each sample the transparent triangles in front of the nearest
opaque one (or in its plane) are blended over it from the farthest to the nearest, each by
its alpha (both faces of a closed shape count, as light goes through both); alpha 0 draws
nothing. The rasteriser is `fishbot_urdf.drawing._raster`.

The work is bounded by the picture, not by the triangles: a picture of more than
:data:`MAX_PIXELS` samples is refused before anything is allocated, triangles are drawn
nearest first so that hidden pixels are turned away cheaply, no more than
:data:`MAX_COVER` pixel visits per sample are made (transparent triangles' included), the
transparent layers are sorted a few rows of the picture at a time, and the deadline in force
(:func:`fishbot_urdf.inputs.deadline`) is checked as the work goes.
"""

from __future__ import annotations

import struct
import zlib
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..analysis import Analysis, of
from ..errors import ArgumentError, RobotError
from ..inputs import deadline
from ..kinematics import Kinematics
from ..model import Robot
from ..output import write_atomic
from ._raster import PictureLimitError, Triangles, Visits, rasterise, screen, see_through
from .dot import source_files
from .scene import Scene, build_scene

__all__ = ["MAX_COVER", "MAX_PIXELS", "VIEWS", "PictureLimitError", "picture", "render_png"]

# Where the camera looks from (towards the scene's centre), and which way is up on screen.
VIEWS: dict[str, tuple[tuple[float, float, float], tuple[float, float, float]]] = {
    "iso": ((1.0, 0.75, 0.65), (0.0, 0.0, 1.0)),  # front left, above: as RViz opens
    "front": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),  # from ahead (+x), looking back
    "side": ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),  # from the left (+y)
    "top": ((0.0, 0.0, 1.0), (1.0, 0.0, 0.0)),  # from above, the robot's front up
}
BACKGROUND = (255, 255, 255)
_SUPERSAMPLE = 2

MAX_PIXELS = 8192 * 8192
"""The most samples a picture is drawn on: 64 Mi (67,108,864), that is a 4096 x 4096
picture, or any other of as many pixels, drawn at twice its width and height. Each sample
holds a depth and a triangle (12 bytes), so the buffers stay under 800 MiB."""

MAX_COVER = 64
"""The most pixel visits per sample: a robot's shapes overlap a few times over, while a
mesh of many big triangles stacked on one another would otherwise cost their number times
the picture."""

_BYTES_PER_SAMPLE = 12  # a float64 depth and an int32 triangle
_BAND = 256  # rows of the picture coloured and averaged at once


def picture(
    robot: Robot | Analysis,
    path: str | Path | None = None,
    *,
    view: str = "iso",
    width: int = 800,
    height: int = 600,
    positions: Mapping[str, float] | None = None,
    collision: bool = False,
    packages: Mapping[str, str | Path] | None = None,
    show: Collection[str] | None = None,
) -> bytes:
    """A shaded 3D picture of the robot as PNG bytes, as `fishbot render` draws it.

    The visuals in their materials' colours (or, with ``collision``, the collision shapes)
    posed at ``positions`` (radians or metres by joint name; the rest at zero, mimic
    joints following), seen from ``view`` (``iso``, ``front``, ``side`` or ``top``), on a
    ``width`` x ``height`` picture; ``show`` draws other layers (``visual``, ``collision``,
    ``mass``, ``inertia``, ``frames``: see `build_scene`). Meshes are found as `check` finds
    them (``packages``: folders of ROS packages by name, for ``package://`` names); what
    cannot be drawn as it is is left out or drawn as its box, as `build_scene` says in its
    findings. With
    ``path``, the PNG is also written there, whole or not at all, and never over a file the
    robot was read from (the link/joint graph is `render_graph`'s).

    Returns:
        The PNG file's bytes.

    Raises:
        RobotError: Nothing would be drawn: its ``diagnostics`` are the scene's findings,
            the ``nothing-drawn`` error among them (no blank picture is made).
        StructureError: The robot has no single root.
        UnknownNameError, ArgumentError: ``positions`` names an unknown joint or holds a
            position out of its limits; ``view``, a size or a layer is wrong.
        PictureLimitError: The picture would pass :data:`MAX_PIXELS` or :data:`MAX_COVER`.
        InputError: ``path`` cannot be written, or is a file the robot was read from.
    """
    analysis = of(robot, packages)
    q = Kinematics(analysis).configuration(positions)
    scene = build_scene(analysis, q, collision=collision, show=show)
    if any(finding.is_error for finding in scene.findings):
        raise RobotError(scene.findings, path=analysis.path)
    data = render_png(scene, view, width, height)
    if path is not None:
        meshes = map(str, analysis.mesh_paths.found(analysis.robot))
        write_atomic(path, data, inputs=[*source_files(analysis.robot), *meshes])
    return data


def render_png(scene: Scene, view: str = "iso", width: int = 800, height: int = 600) -> bytes:
    """The scene drawn from ``view`` (``iso``, ``front``, ``side`` or ``top``), as the bytes
    of a ``width`` x ``height`` PNG file.

    Raises:
        ArgumentError: ``view`` is not a view, or a size is not a positive whole number.
        PictureLimitError: The picture has more than :data:`MAX_PIXELS` samples, or its
            triangles would take more than :data:`MAX_COVER` visits per sample.
        TimeLimitError: Drawing went past the deadline in force.
    """
    if view not in VIEWS:
        raise ArgumentError(f"no view {view!r} (views: {', '.join(VIEWS)})", name="view")
    for name, value in (("width", width), ("height", height)):
        if not isinstance(value, int) or value < 1:
            raise ArgumentError(f"the {name} must be a positive whole number", name=name)
    samples = width * height * _SUPERSAMPLE * _SUPERSAMPLE
    if samples > MAX_PIXELS:
        side = int(MAX_PIXELS**0.5) // _SUPERSAMPLE
        raise PictureLimitError(
            f"a {width} x {height} picture is drawn on {samples:,} samples (about "
            f"{_gibibytes(samples * _BYTES_PER_SAMPLE)}), more than the bound of {MAX_PIXELS:,} "
            f"(a {side} x {side} picture)",
            what="samples",
            needed=samples,
            limit=MAX_PIXELS,
        )
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    wide, high = width * _SUPERSAMPLE, height * _SUPERSAMPLE
    visits = Visits(MAX_COVER, wide * high)
    drawn = _draw(np, scene, view, wide, high, visits)
    table = np.concatenate([drawn.colors, np.array([BACKGROUND], dtype=float)])
    rgb = np.empty((height, width, 3), dtype=np.uint8)
    check = deadline()
    for top in range(0, height, _BAND):  # a band at a time: no float picture of every sample
        check.check("rendering")
        first, last = top * _SUPERSAMPLE, min(top + _BAND, height) * _SUPERSAMPLE
        samples = table[drawn.index[first:last]]
        if drawn.glass is not None:
            see_through(np, drawn.glass, drawn.depth, samples, first, wide, visits)
        band = samples.reshape(-1, _SUPERSAMPLE, width, _SUPERSAMPLE, 3).mean(axis=(1, 3))
        rgb[top : top + _BAND] = np.clip(np.rint(band), 0, 255).astype(np.uint8)
    return _png(rgb)


def _gibibytes(size: int) -> str:
    return f"{size / (1 << 30):,.1f} GiB" if size >= 1 << 30 else f"{size / (1 << 20):,.0f} MiB"


def _camera(np: Any, view: str) -> tuple[Any, Any, Any]:
    """Right, up and forward (into the screen) unit vectors of the view."""
    eye, up_hint = (np.array(v, dtype=float) for v in VIEWS[view])
    forward = -eye / np.linalg.norm(eye)
    right = np.cross(forward, up_hint)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    return right, up, forward


@dataclass(frozen=True)
class _Drawn:
    """The opaque triangles drawn: each sample's triangle (``len(colors)`` where none) and
    depth (inf where none), each triangle's shaded colour; and the transparent triangles,
    blended over them band by band (None when there are none)."""

    index: Any
    depth: Any
    colors: Any
    glass: Triangles | None


def _draw(np: Any, scene: Scene, view: str, width: int, height: int, visits: Visits) -> _Drawn:
    """The scene's opaque triangles rasterised, and its transparent ones made ready."""
    parts = [p for p in scene.parts if len(p.triangles) and p.color[3] > 0]
    corners = (
        np.concatenate([p.triangles for p in parts]) if parts else np.empty((0, 3, 3))
    )  # (T, 3, 3)
    colors = np.concatenate(
        [np.broadcast_to(np.array(p.color), (len(p.triangles), 4)) for p in parts]
        or [np.empty((0, 4))]
    )
    finite = np.isfinite(corners).all(axis=(1, 2))
    if not finite.all():  # the scene leaves such shapes out; nothing else can be drawn
        corners, colors = corners[finite], colors[finite]
    if not len(corners):
        empty = np.zeros((height, width), dtype=np.int32)
        return _Drawn(empty, np.full((height, width), np.inf), np.empty((0, 3)), None)
    right, up, forward = _camera(np, view)
    sx, sy, depth = corners @ right, corners @ up, corners @ forward
    # Frame everything, with a margin, keeping the aspect.
    low_x, high_x, low_y, high_y = sx.min(), sx.max(), sy.min(), sy.max()
    span = max((high_x - low_x) / width, (high_y - low_y) / height, 1e-9) * 1.12
    cx, cy = (low_x + high_x) / 2, (low_y + high_y) / 2
    px = (sx - cx) / span + width / 2
    py = height / 2 - (sy - cy) / span
    # Light from over the viewer's left shoulder; both faces of a triangle are lit.
    edge1, edge2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    normals = np.cross(edge1, edge2)
    lengths = np.linalg.norm(normals, axis=1)
    keep = lengths > 1e-18
    normals = normals[keep] / lengths[keep, None]
    light = -forward + 0.6 * up - 0.4 * right
    light /= np.linalg.norm(light)
    shade = 0.35 + 0.65 * np.abs(normals @ light)
    shaded = colors[keep, :3] * 255.0 * shade[:, None]
    alphas = np.clip(colors[keep, 3], 0.0, 1.0)
    drawn = screen(np, px[keep], py[keep], depth[keep], shaded, alphas, height, width)
    solid = alphas >= 1.0
    index, zbuffer = rasterise(np, drawn.subset(np, solid), height, width, visits)
    glass = None if solid.all() else drawn.subset(np, ~solid)
    return _Drawn(index, zbuffer, shaded[solid], glass)


def _png(rgb: Any) -> bytes:
    """An 8-bit RGB PNG of ``rgb`` (height, width, 3)."""
    height, width = rgb.shape[:2]
    rows = b"".join(b"\0" + rgb[i].tobytes() for i in range(height))

    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(rows, 6))
        + chunk(b"IEND", b"")
    )
