"""A shaded picture of a scene, made in numpy: no display, no GPU, no library beyond numpy.

An orthographic camera looks at the scene from one of four views and frames all of it. The
triangles are rasterised with a depth buffer at twice the asked size (every pixel's four
samples averaged: smooth edges), lit by a light from over the viewer's left shoulder, and
written as an RGB PNG with the standard library's zlib.

The work is bounded by the picture, not by the triangles: a picture of more than
:data:`MAX_PIXELS` samples is refused before anything is allocated, triangles are drawn
nearest first so that hidden pixels are turned away cheaply, no more than
:data:`MAX_COVER` pixel visits per sample are made, and the deadline in force
(:func:`fishbot_urdf.inputs.deadline`) is checked as the work goes.
"""

from __future__ import annotations

import struct
import zlib
from typing import TYPE_CHECKING, Any

from ..errors import ArgumentError, LimitError
from ..inputs import deadline

if TYPE_CHECKING:
    from .scene import Scene

__all__ = ["MAX_COVER", "MAX_PIXELS", "VIEWS", "PictureLimitError", "render_png"]

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
_CHUNK = 1 << 16  # candidate pixels worked on at once: small enough to stay in the cache
_ROWS = 1 << 15  # (triangle, row) pairs whose spans are found at once
_BIG_ROWS = 32  # a triangle over as many pixel rows is looked at for copies
_BAND = 256  # rows of the picture coloured and averaged at once


class PictureLimitError(LimitError):
    """A picture would pass one of its bounds: ``needed`` and ``limit`` are samples (see
    :data:`MAX_PIXELS`) or pixel visits (see :data:`MAX_COVER`), as ``what`` says."""

    def __init__(self, message: str, *, what: str, needed: int, limit: int) -> None:
        super().__init__(message)
        self.what = what
        self.needed = needed
        self.limit = limit


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

    index, colors = _draw(np, scene, view, width * _SUPERSAMPLE, height * _SUPERSAMPLE)
    table = np.concatenate([colors, np.array([BACKGROUND], dtype=float)])
    rgb = np.empty((height, width, 3), dtype=np.uint8)
    check = deadline()
    for top in range(0, height, _BAND):  # a band at a time: no float picture of every sample
        check.check("rendering")
        rows = index[top * _SUPERSAMPLE : (top + _BAND) * _SUPERSAMPLE]
        band = table[rows].reshape(-1, _SUPERSAMPLE, width, _SUPERSAMPLE, 3).mean(axis=(1, 3))
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


def _draw(np: Any, scene: Scene, view: str, width: int, height: int) -> tuple[Any, Any]:
    """Each sample's triangle (``len(colors)`` where none is drawn), and each triangle's
    shaded colour."""
    parts = [p for p in scene.parts if len(p.triangles)]
    corners = (
        np.concatenate([p.triangles for p in parts]) if parts else np.empty((0, 3, 3))
    )  # (T, 3, 3)
    colors = np.concatenate(
        [np.broadcast_to(np.array(p.color[:3]), (len(p.triangles), 3)) for p in parts]
        or [np.empty((0, 3))]
    )
    finite = np.isfinite(corners).all(axis=(1, 2))
    if not finite.all():  # the scene leaves such shapes out; nothing else can be drawn
        corners, colors = corners[finite], colors[finite]
    if not len(corners):
        return np.zeros((height, width), dtype=np.int32), np.empty((0, 3))
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
    shaded = colors[keep] * 255.0 * shade[:, None]
    index = _rasterise(np, px[keep], py[keep], depth[keep], height, width)
    return index, shaded


def _rasterise(np: Any, px: Any, py: Any, depth: Any, height: int, width: int) -> Any:
    """The triangle seen at every pixel centre: the nearest one whose triangle holds it
    (of two as near, the first). Each triangle is cut into rows, each row into the span
    its three edges leave open; triangles are taken nearest first, so that most hidden
    pixels are turned away before the costly sort."""
    count = len(px)
    zbuffer = np.full(height * width, np.inf)
    index = np.full(height * width, count, dtype=np.int32 if count < 2**31 - 1 else np.int64)
    ax, bx, cx = px[:, 0], px[:, 1], px[:, 2]
    ay, by, cy = py[:, 0], py[:, 1], py[:, 2]
    area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    sign = np.sign(area)
    # Depth as a plane over the screen: z = z0 + dzdx (x - ax) + dzdy (y - ay).
    dz1, dz2 = depth[:, 1] - depth[:, 0], depth[:, 2] - depth[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        dzdx = (dz1 * (cy - ay) - dz2 * (by - ay)) / area
        dzdy = (dz2 * (bx - ax) - dz1 * (cx - ax)) / area
    # Only the rows on the screen: a triangle off it, or between two pixel rows, costs nothing.
    y0 = np.clip(np.ceil(py.min(axis=1) - 0.5), 0, height).astype(np.int64)
    y1 = np.clip(np.floor(py.max(axis=1) - 0.5), -1, height - 1).astype(np.int64)
    left = px.min(axis=1) <= width - 0.5
    rightward = px.max(axis=1) >= 0.5
    drawn = np.nonzero((area != 0) & (y1 >= y0) & left & rightward)[0]
    # A big triangle given again (a face repeated in its file) is drawn once: it would lose
    # every pixel to the first anyway.
    big = drawn[y1[drawn] - y0[drawn] >= _BIG_ROWS]
    if len(big) > 1:
        corners = np.concatenate([px[big], py[big], depth[big]], axis=1)
        _, first = np.unique(corners, axis=0, return_index=True)
        again = np.ones(count, dtype=bool)
        again[big] = False
        again[big[first]] = True
        drawn = drawn[again[drawn]]
    drawn = drawn[np.argsort(depth.min(axis=1)[drawn], kind="stable")]
    rows_of = (y1 - y0 + 1)[drawn]
    ends = np.cumsum(rows_of)
    visits, budget = 0, MAX_COVER * height * width
    planes = (
        np.ascontiguousarray(depth[:, 0]),
        np.ascontiguousarray(px[:, 0]),
        np.ascontiguousarray(py[:, 0]),
        dzdx,
        dzdy,
    )
    check = deadline()
    done, total = 0, int(ends[-1]) if len(ends) else 0
    while done < total:  # (triangle, row) pairs, whole triangles at a time
        check.check("rendering")
        first = int(np.searchsorted(ends, done, side="right"))
        last = int(np.searchsorted(ends, done + _ROWS, side="right")) + 1
        chosen = drawn[first:last]
        counts = rows_of[first:last]
        tri = np.repeat(chosen, counts)
        starts = np.cumsum(counts) - counts
        row = y0[tri] + (np.arange(len(tri)) - np.repeat(starts, counts))
        centre_y = row + 0.5
        start, end = _spans(np, tri, centre_y, px, py, sign, width)
        lengths = np.maximum(end - start + 1, 0)
        visits += int(lengths.sum())
        if visits > budget:
            raise PictureLimitError(
                f"the picture's triangles overlap more than {MAX_COVER} times over its "
                f"{height * width:,} samples: drawing them would take more than {budget:,} "
                "pixel visits",
                what="visits",
                needed=visits,
                limit=budget,
            )
        ready = np.cumsum(lengths)
        begin = 0
        while begin < len(tri):  # the pairs' pixels, a chunk at a time
            check.check("rendering")
            stop = int(np.searchsorted(ready, ready[begin] - lengths[begin] + _CHUNK, "right"))
            stop = max(stop, begin + 1)
            part = slice(begin, stop)
            _fill(
                np,
                (tri[part], row[part], centre_y[part], start[part], lengths[part]),
                planes,
                zbuffer,
                index,
                width,
            )
            begin = stop
        done = int(ends[min(last, len(ends)) - 1])
    return index.reshape(height, width)


def _spans(
    np: Any, tri: Any, centre_y: Any, px: Any, py: Any, sign: Any, width: int
) -> tuple[Any, Any]:
    """The first and last pixel of each (triangle, row) pair whose centre is inside."""
    low = np.full(len(tri), -np.inf)
    high = np.full(len(tri), np.inf)
    s = sign[tri]
    for p, q in ((1, 2), (2, 0), (0, 1)):  # each edge: (qx - px)(y - py) - (qy - py)(x - px)
        ex, ey = px[tri, q] - px[tri, p], py[tri, q] - py[tri, p]
        slope = -ey * s  # the edge function (times the sign) grows with x at this rate
        rest = (ex * (centre_y - py[tri, p]) + ey * px[tri, p]) * s
        with np.errstate(divide="ignore", invalid="ignore"):
            bound = -rest / slope
        low = np.where(slope > 0, np.maximum(low, bound), low)
        high = np.where(slope < 0, np.minimum(high, bound), high)
        flat_edge = slope == 0
        high = np.where(flat_edge & (rest < 0), -np.inf, high)
    start = np.clip(np.ceil(low - 0.5), 0, width).astype(np.int64)
    end = np.clip(np.floor(high - 0.5), -1, width - 1).astype(np.int64)
    return start, end


def _fill(
    np: Any,
    pairs: tuple[Any, Any, Any, Any, Any],
    planes: tuple[Any, Any, Any, Any, Any],
    zbuffer: Any,
    index: Any,
    width: int,
) -> None:
    """Draw the spans of some (triangle, row) pairs where they are nearer than what is
    drawn (or as near, and of an earlier triangle)."""
    tri, row, centre_y, start, counts = pairs
    depth0, px0, py0, dzdx, dzdy = planes
    total = int(counts.sum())
    if not total:
        return
    # What is the same along a span, once per pair: z = z0 + dzdx (x + 0.5 - x0) + rest.
    offsets = np.cumsum(counts) - counts
    x = np.repeat(start - offsets, counts) + np.arange(total)
    t = np.repeat(tri, counts)
    rest = dzdy[tri] * (centre_y - py0[tri])
    z = np.repeat(depth0[tri], counts) + np.repeat(dzdx[tri], counts) * (
        x + 0.5 - np.repeat(px0[tri], counts)
    )
    z += np.repeat(rest, counts)
    pixel = np.repeat(row * width, counts) + x
    drawn = zbuffer[pixel]
    nearer = (z < drawn) | ((z == drawn) & (t < index[pixel]))
    pixel, z, t = pixel[nearer], z[nearer], t[nearer]
    np.minimum.at(zbuffer, pixel, z)  # the nearest of each pixel's candidates
    won = z == zbuffer[pixel]
    pixel, t = pixel[won], t[won]
    index[pixel] = np.iinfo(index.dtype).max
    np.minimum.at(index, pixel, t)  # of as near, the first triangle


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
