"""A shaded picture of a scene, made in numpy: no display, no GPU, no library beyond numpy.

An orthographic camera looks at the scene from one of four views and frames all of it. The
triangles are rasterised with a depth buffer at twice the asked size (every pixel's four
samples averaged: smooth edges), lit by a light from over the viewer's left shoulder, and
written as an RGB PNG with the standard library's zlib.
"""

from __future__ import annotations

import struct
import zlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .scene import Scene

__all__ = ["VIEWS", "render_png"]

# Where the camera looks from (towards the scene's centre), and which way is up on screen.
VIEWS: dict[str, tuple[tuple[float, float, float], tuple[float, float, float]]] = {
    "iso": ((1.0, 0.75, 0.65), (0.0, 0.0, 1.0)),  # front left, above: as RViz opens
    "front": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),  # from ahead (+x), looking back
    "side": ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),  # from the left (+y)
    "top": ((0.0, 0.0, 1.0), (1.0, 0.0, 0.0)),  # from above, the robot's front up
}
BACKGROUND = (255, 255, 255)
_SUPERSAMPLE = 2
_CHUNK = 2_000_000  # candidate pixels worked on at once


def render_png(scene: Scene, view: str = "iso", width: int = 800, height: int = 600) -> bytes:
    """The scene drawn from ``view`` (``iso``, ``front``, ``side`` or ``top``), as the bytes
    of a ``width`` x ``height`` PNG file."""
    import numpy as np

    pixels = _draw(np, scene, view, width * _SUPERSAMPLE, height * _SUPERSAMPLE)
    small = pixels.reshape(height, _SUPERSAMPLE, width, _SUPERSAMPLE, 3).mean(axis=(1, 3))
    return _png(np.clip(np.rint(small), 0, 255).astype(np.uint8))


def _camera(np: Any, view: str) -> tuple[Any, Any, Any]:
    """Right, up and forward (into the screen) unit vectors of the view."""
    eye, up_hint = (np.array(v, dtype=float) for v in VIEWS[view])
    forward = -eye / np.linalg.norm(eye)
    right = np.cross(forward, up_hint)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    return right, up, forward


def _draw(np: Any, scene: Scene, view: str, width: int, height: int) -> Any:
    image = np.empty((height, width, 3))
    image[:] = BACKGROUND
    triangles = [p.triangles for p in scene.parts if len(p.triangles)]
    if not triangles:
        return image
    corners = np.concatenate(triangles)  # (T, 3, 3)
    colors = np.concatenate(
        [
            np.broadcast_to(np.array(p.color[:3]), (len(p.triangles), 3))
            for p in scene.parts
            if len(p.triangles)
        ]
    )
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
    _rasterise(np, px[keep], py[keep], depth[keep], shaded, image)
    return image


def _rasterise(np: Any, px: Any, py: Any, depth: Any, colors: Any, image: Any) -> None:
    """Fill every pixel whose centre lies in a triangle, nearest triangle first: each
    triangle is cut into rows, each row into the span its three edges leave open."""
    height, width = image.shape[:2]
    zbuffer = np.full(height * width, np.inf)
    flat = image.reshape(-1, 3)
    ax, bx, cx = px[:, 0], px[:, 1], px[:, 2]
    ay, by, cy = py[:, 0], py[:, 1], py[:, 2]
    area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    drawn = np.nonzero(area != 0)[0]
    sign = np.sign(area)
    # Depth as a plane over the screen: z = z0 + dzdx (x - ax) + dzdy (y - ay).
    dz1, dz2 = depth[:, 1] - depth[:, 0], depth[:, 2] - depth[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        dzdx = (dz1 * (cy - ay) - dz2 * (by - ay)) / area
        dzdy = (dz2 * (bx - ax) - dz1 * (cx - ax)) / area
    y0 = np.clip(np.ceil(py.min(axis=1) - 0.5), 0, height).astype(np.int64)
    y1 = np.clip(np.floor(py.max(axis=1) - 0.5), -1, height - 1).astype(np.int64)
    rows_of = np.maximum(y1 - y0 + 1, 0)[drawn]
    total = int(rows_of.sum())
    done = 0
    while done < total:  # (triangle, row) pairs, a chunk at a time
        ends = np.cumsum(rows_of)
        first = int(np.searchsorted(ends, done, side="right"))
        last = int(np.searchsorted(ends, done + _CHUNK // 64, side="right")) + 1
        chosen = drawn[first:last]
        counts = rows_of[first:last]
        tri = np.repeat(chosen, counts)
        starts = np.cumsum(counts) - counts
        row = y0[tri] + (np.arange(len(tri)) - np.repeat(starts, counts))
        _spans(
            np, tri, row + 0.5, row, px, py, sign, depth, dzdx, dzdy, colors, zbuffer, flat, width
        )
        done = int(ends[min(last, len(ends)) - 1])


def _spans(
    np: Any,
    tri: Any,
    centre_y: Any,
    row: Any,
    px: Any,
    py: Any,
    sign: Any,
    depth: Any,
    dzdx: Any,
    dzdy: Any,
    colors: Any,
    zbuffer: Any,
    flat: Any,
    width: int,
) -> None:
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
    counts = np.maximum(end - start + 1, 0)
    if not counts.any():
        return
    pair = np.repeat(np.arange(len(tri)), counts)
    offsets = np.cumsum(counts) - counts
    x = start[pair] + (np.arange(len(pair)) - offsets[pair])
    t = tri[pair]
    z = depth[t, 0] + dzdx[t] * (x + 0.5 - px[t, 0]) + dzdy[t] * (centre_y[pair] - py[t, 0])
    pixel = row[pair] * width + x
    nearer = z < zbuffer[pixel]
    pixel, z, t = pixel[nearer], z[nearer], t[nearer]
    order = np.lexsort((z, pixel))  # by pixel, nearest first
    pixel, z, t = pixel[order], z[order], t[order]
    keep = np.ones(len(pixel), dtype=bool)
    keep[1:] = pixel[1:] != pixel[:-1]
    zbuffer[pixel[keep]] = z[keep]
    flat[pixel[keep]] = colors[t[keep]]


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
