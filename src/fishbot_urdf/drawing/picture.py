"""A shaded picture of a scene, made in numpy: no display, no GPU, no library beyond numpy.

An orthographic camera looks at the scene from one of four views and frames all of it. The
triangles are rasterised with a depth buffer at twice the asked size (every pixel's four
samples averaged: smooth edges), lit by a light from over the viewer's left shoulder, and
written as an RGB PNG with the standard library's zlib.

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
from dataclasses import dataclass, fields
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
_GLASS = 1 << 16  # samples whose transparent layers are sorted at once (a few MiB each)


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

    wide, high = width * _SUPERSAMPLE, height * _SUPERSAMPLE
    visits = _Visits(MAX_COVER * wide * high, wide * high)
    drawn = _draw(np, scene, view, wide, high, visits)
    table = np.concatenate([drawn.colors, np.array([BACKGROUND], dtype=float)])
    rgb = np.empty((height, width, 3), dtype=np.uint8)
    check = deadline()
    for top in range(0, height, _BAND):  # a band at a time: no float picture of every sample
        check.check("rendering")
        first, last = top * _SUPERSAMPLE, min(top + _BAND, height) * _SUPERSAMPLE
        samples = table[drawn.index[first:last]]
        if drawn.glass is not None:
            _see_through(np, drawn.glass, drawn.depth, samples, first, wide, visits)
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


class _Visits:
    """The pixel visits made so far, and the bound on them (see :data:`MAX_COVER`)."""

    def __init__(self, budget: int, samples: int) -> None:
        self.count = 0
        self.budget = budget
        self.samples = samples

    def add(self, count: int) -> None:
        self.count += count
        if self.count > self.budget:
            raise PictureLimitError(
                f"the picture's triangles overlap more than {MAX_COVER} times over its "
                f"{self.samples:,} samples: drawing them would take more than "
                f"{self.budget:,} pixel visits",
                what="visits",
                needed=self.count,
                limit=self.budget,
            )


@dataclass(frozen=True)
class _Triangles:
    """Triangles on the screen, in samples: corners' ``px``, ``py`` and ``depth`` (T, 3),
    the sign of their area, the rows they cover (``y0`` .. ``y1``), their depth as a plane
    (z = z0 + dzdx (x - x0) + dzdy (y - y0), from the first corner), and their shaded
    colours (T, 3, 0..255) and alphas."""

    px: Any
    py: Any
    depth: Any
    sign: Any
    y0: Any
    y1: Any
    dzdx: Any
    dzdy: Any
    colors: Any
    alphas: Any

    def subset(self, np: Any, chosen: Any) -> _Triangles:
        """The triangles ``chosen`` (a boolean mask), in their order."""
        return _Triangles(*(getattr(self, f.name)[chosen] for f in fields(self)))

    def planes(self, np: Any) -> tuple[Any, Any, Any, Any, Any]:
        """What `_fragments` needs to find a depth: z0, x0, y0, dz/dx, dz/dy."""
        return (
            np.ascontiguousarray(self.depth[:, 0]),
            np.ascontiguousarray(self.px[:, 0]),
            np.ascontiguousarray(self.py[:, 0]),
            self.dzdx,
            self.dzdy,
        )


@dataclass(frozen=True)
class _Drawn:
    """The opaque triangles drawn: each sample's triangle (``len(colors)`` where none) and
    depth (inf where none), each triangle's shaded colour; and the transparent triangles,
    blended over them band by band (None when there are none)."""

    index: Any
    depth: Any
    colors: Any
    glass: _Triangles | None


def _draw(np: Any, scene: Scene, view: str, width: int, height: int, visits: _Visits) -> _Drawn:
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
    screen = _screen(np, px[keep], py[keep], depth[keep], shaded, alphas, height, width)
    solid = alphas >= 1.0
    index, zbuffer = _rasterise(np, screen.subset(np, solid), height, width, visits)
    glass = None if solid.all() else screen.subset(np, ~solid)
    return _Drawn(index, zbuffer, shaded[solid], glass)


def _screen(
    np: Any, px: Any, py: Any, depth: Any, colors: Any, alphas: Any, height: int, width: int
) -> _Triangles:
    ax, bx, cx = px[:, 0], px[:, 1], px[:, 2]
    ay, by, cy = py[:, 0], py[:, 1], py[:, 2]
    area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    dz1, dz2 = depth[:, 1] - depth[:, 0], depth[:, 2] - depth[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        dzdx = (dz1 * (cy - ay) - dz2 * (by - ay)) / area
        dzdy = (dz2 * (bx - ax) - dz1 * (cx - ax)) / area
    # Only the rows on the screen: a triangle off it, or between two pixel rows, costs nothing.
    y0 = np.clip(np.ceil(py.min(axis=1) - 0.5), 0, height).astype(np.int64)
    y1 = np.clip(np.floor(py.max(axis=1) - 0.5), -1, height - 1).astype(np.int64)
    left = px.min(axis=1) <= width - 0.5
    rightward = px.max(axis=1) >= 0.5
    y1[~((area != 0) & left & rightward)] = -1  # drawn nowhere: no row
    return _Triangles(px, py, depth, np.sign(area), y0, y1, dzdx, dzdy, colors, alphas)


def _rasterise(
    np: Any, triangles: _Triangles, height: int, width: int, visits: _Visits
) -> tuple[Any, Any]:
    """The triangle seen at every pixel centre, the nearest one whose triangle holds it (of
    two as near, the first), and its depth. Each triangle is cut into rows, each row into
    the span its three edges leave open; triangles are taken nearest first, so that most
    hidden pixels are turned away before the costly sort."""
    count = len(triangles.px)
    zbuffer = np.full(height * width, np.inf)
    index = np.full(height * width, count, dtype=np.int32 if count < 2**31 - 1 else np.int64)
    px, py, depth, y0, y1 = triangles.px, triangles.py, triangles.depth, triangles.y0, triangles.y1
    drawn = np.nonzero(y1 >= y0)[0]
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
    planes = triangles.planes(np)
    check = deadline()
    done, total = 0, int(ends[-1]) if len(ends) else 0
    while done < total:  # (triangle, row) pairs, whole triangles at a time
        check.check("rendering")
        first = int(np.searchsorted(ends, done, side="right"))
        last = int(np.searchsorted(ends, done + _ROWS, side="right")) + 1
        chosen = drawn[first:last]
        tri, row, start, lengths = _pairs(np, triangles, chosen, y0[chosen], y1[chosen], width)
        visits.add(int(lengths.sum()))
        ready = np.cumsum(lengths)
        begin = 0
        while begin < len(tri):  # the pairs' pixels, a chunk at a time
            check.check("rendering")
            stop = int(np.searchsorted(ready, ready[begin] - lengths[begin] + _CHUNK, "right"))
            stop = max(stop, begin + 1)
            part = slice(begin, stop)
            pixel, z, t = _fragments(
                np, (tri[part], row[part], start[part], lengths[part]), planes, width
            )
            _nearest(np, pixel, z, t, zbuffer, index)
            begin = stop
        done = int(ends[min(last, len(ends)) - 1])
    return index.reshape(height, width), zbuffer.reshape(height, width)


def _pairs(
    np: Any, triangles: _Triangles, chosen: Any, y0: Any, y1: Any, width: int
) -> tuple[Any, Any, Any, Any]:
    """Each (triangle, row) pair of triangles ``chosen`` over rows ``y0`` .. ``y1`` (each
    triangle's): the triangle, the row, and the first pixel and length of its span."""
    counts = y1 - y0 + 1
    tri = np.repeat(chosen, counts)
    starts = np.cumsum(counts) - counts
    row = np.repeat(y0, counts) + (np.arange(len(tri)) - np.repeat(starts, counts))
    start, end = _spans(np, tri, row + 0.5, triangles.px, triangles.py, triangles.sign, width)
    return tri, row, start, np.maximum(end - start + 1, 0)


def _see_through(
    np: Any, glass: _Triangles, zbuffer: Any, samples: Any, top: int, width: int, visits: _Visits
) -> None:
    """Blend the transparent triangles over ``samples`` (the colours of the picture's rows
    from ``top``, in place), where they are nearer than the opaque ones: at each sample
    from the farthest to the nearest, each colour c of alpha a making the colour behind it
    b into a c + (1 - a) b. Unrolled from the nearest: the colour is the sum of
    a_i c_i times the product of (1 - a_j) over the layers j before it, plus the colour
    behind all of them times the product of all the (1 - a_j)."""
    rows = max(1, _GLASS // width)
    flat = samples.reshape(-1, 3)
    planes = glass.planes(np)
    check = deadline()
    for low in range(top, top + len(samples), rows):
        check.check("rendering")
        high = min(low + rows, top + len(samples))
        chosen = np.nonzero((glass.y1 >= low) & (glass.y0 < high) & (glass.y1 >= glass.y0))[0]
        if not len(chosen):
            continue
        y0 = np.maximum(glass.y0[chosen], low)
        y1 = np.minimum(glass.y1[chosen], high - 1)
        tri, row, start, lengths = _pairs(np, glass, chosen, y0, y1, width)
        layers, samples_here = int(lengths.sum()), (high - low) * width
        visits.add(layers)
        if layers > MAX_COVER * samples_here:  # all of them are held at once: bound them
            raise PictureLimitError(
                f"the picture's transparent triangles overlap more than {MAX_COVER} times "
                f"over {samples_here:,} of its samples (rows {low} to {high - 1} of "
                f"{visits.samples // width}): blending them would take {layers:,} layers",
                what="visits",
                needed=layers,
                limit=MAX_COVER * samples_here,
            )
        pixel, z, t = _fragments(np, (tri, row, start, lengths), planes, width)
        seen = z < zbuffer.reshape(-1)[pixel]  # in front of the opaque triangle there
        if not seen.any():
            continue
        pixel, z, t = pixel[seen] - low * width, z[seen], t[seen]
        # Each sample's layers, nearest first: one sort of the sample (below 2**25) plus its
        # depth scaled into 0 .. 0.5, so that layers 2**-25 of the depths' range apart still
        # sort apart (nearer is as good as one plane).
        low_z, high_z = z.min(), z.max()
        key = pixel + (z - low_z) * (0.5 / max(high_z - low_z, 1e-300))
        order = np.argsort(key, kind="stable")
        pixel, t = pixel[order], t[order]
        alpha = glass.alphas[t]
        through = np.log1p(-alpha)  # the share of the light behind a layer it lets by
        new = np.empty(len(pixel), dtype=bool)
        new[0], new[1:] = True, pixel[1:] != pixel[:-1]
        first = np.nonzero(new)[0]
        group = np.cumsum(new) - 1
        total = np.cumsum(through)
        before = total - through  # over the layers nearer than this one, at this sample
        before -= before[first][group]
        weight = alpha * np.exp(before)
        count = len(first)
        colors = glass.colors[t]
        added = np.stack(
            [np.bincount(group, colors[:, i] * weight, minlength=count) for i in range(3)],
            axis=1,
        )
        behind = np.exp(np.bincount(group, through, minlength=count))
        where = pixel[first] + (low - top) * width
        flat[where] = flat[where] * behind[:, None] + added


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


def _fragments(
    np: Any, pairs: tuple[Any, Any, Any, Any], planes: tuple[Any, Any, Any, Any, Any], width: int
) -> tuple[Any, Any, Any]:
    """Every pixel of the spans of some (triangle, row) pairs: the pixel, the triangle's
    depth there, and the triangle."""
    tri, row, start, counts = pairs
    depth0, px0, py0, dzdx, dzdy = planes
    total = int(counts.sum())
    # What is the same along a span, once per pair: z = z0 + dzdx (x + 0.5 - x0) + rest.
    offsets = np.cumsum(counts) - counts
    x = np.repeat(start - offsets, counts) + np.arange(total)
    t = np.repeat(tri, counts)
    rest = dzdy[tri] * (row + 0.5 - py0[tri])
    z = np.repeat(depth0[tri], counts) + np.repeat(dzdx[tri], counts) * (
        x + 0.5 - np.repeat(px0[tri], counts)
    )
    z += np.repeat(rest, counts)
    pixel = np.repeat(row * width, counts) + x
    return pixel, z, t


def _nearest(np: Any, pixel: Any, z: Any, t: Any, zbuffer: Any, index: Any) -> None:
    """Draw the pixels where they are nearer than what is drawn (or as near, and of an
    earlier triangle)."""
    if not len(pixel):
        return
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
