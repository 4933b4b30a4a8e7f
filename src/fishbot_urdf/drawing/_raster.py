"""The rasteriser of `fishbot_urdf.drawing.picture`: triangles on the screen to the
triangle seen at each sample (nearest first, with a depth buffer), and the transparent
triangles in front of it (or in its plane) blended over it, from the farthest to the
nearest, a few rows at a time; every pixel visit counted against the picture's bound."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

from ..errors import LimitError
from ..inputs import deadline

__all__ = ["PictureLimitError", "Triangles", "Visits", "rasterise", "screen", "see_through"]

_CHUNK = 1 << 16  # candidate pixels worked on at once: small enough to stay in the cache
_ROWS = 1 << 15  # (triangle, row) pairs whose spans are found at once
_BIG_ROWS = 32  # a triangle over as many pixel rows is looked at for copies
_GLASS = 1 << 16  # samples whose transparent layers are sorted at once (a few MiB each)
# A transparent face this share of the depths' size behind the opaque one is taken as in
# front: one in the same plane (an inertia box's top on the cylinder it is the box of) is
# drawn over it everywhere, not in the specks rounding picks; the share is far below a
# sample at any size the picture's bounds allow.
_SAME_PLANE = 2.0**-30


class PictureLimitError(LimitError):
    """A picture would pass one of its bounds: ``needed`` and ``limit`` are samples (see
    :data:`MAX_PIXELS`) or pixel visits (see :data:`MAX_COVER`), as ``what`` says."""

    def __init__(self, message: str, *, what: str, needed: int, limit: int) -> None:
        super().__init__(message)
        self.what = what
        self.needed = needed
        self.limit = limit


class Visits:
    """The pixel visits made so far over a picture's ``samples``, and the bound on them:
    ``cover`` visits per sample (the picture's ``MAX_COVER``)."""

    def __init__(self, cover: int, samples: int) -> None:
        self.count = 0
        self.cover = cover
        self.budget = cover * samples
        self.samples = samples

    def add(self, count: int) -> None:
        self.count += count
        if self.count > self.budget:
            raise PictureLimitError(
                f"the picture's triangles overlap more than {self.cover} times over its "
                f"{self.samples:,} samples: drawing them would take more than "
                f"{self.budget:,} pixel visits",
                what="visits",
                needed=self.count,
                limit=self.budget,
            )


@dataclass(frozen=True)
class Triangles:
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

    def subset(self, np: Any, chosen: Any) -> Triangles:
        """The triangles ``chosen`` (a boolean mask), in their order."""
        return Triangles(*(getattr(self, f.name)[chosen] for f in fields(self)))

    def planes(self, np: Any) -> tuple[Any, Any, Any, Any, Any]:
        """What `_fragments` needs to find a depth: z0, x0, y0, dz/dx, dz/dy."""
        return (
            np.ascontiguousarray(self.depth[:, 0]),
            np.ascontiguousarray(self.px[:, 0]),
            np.ascontiguousarray(self.py[:, 0]),
            self.dzdx,
            self.dzdy,
        )


def screen(
    np: Any, px: Any, py: Any, depth: Any, colors: Any, alphas: Any, height: int, width: int
) -> Triangles:
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
    return Triangles(px, py, depth, np.sign(area), y0, y1, dzdx, dzdy, colors, alphas)


def rasterise(
    np: Any, triangles: Triangles, height: int, width: int, visits: Visits
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
    np: Any, triangles: Triangles, chosen: Any, y0: Any, y1: Any, width: int
) -> tuple[Any, Any, Any, Any]:
    """Each (triangle, row) pair of triangles ``chosen`` over rows ``y0`` .. ``y1`` (each
    triangle's): the triangle, the row, and the first pixel and length of its span."""
    counts = y1 - y0 + 1
    tri = np.repeat(chosen, counts)
    starts = np.cumsum(counts) - counts
    row = np.repeat(y0, counts) + (np.arange(len(tri)) - np.repeat(starts, counts))
    start, end = _spans(np, tri, row + 0.5, triangles.px, triangles.py, triangles.sign, width)
    return tri, row, start, np.maximum(end - start + 1, 0)


def see_through(
    np: Any, glass: Triangles, zbuffer: Any, samples: Any, top: int, width: int, visits: Visits
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
    same_plane = _SAME_PLANE * float(np.abs(glass.depth).max(initial=0.0))
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
        if layers > visits.cover * samples_here:  # all of them are held at once: bound them
            raise PictureLimitError(
                f"the picture's transparent triangles overlap more than {visits.cover} times "
                f"over {samples_here:,} of its samples (rows {low} to {high - 1} of "
                f"{visits.samples // width}): blending them would take {layers:,} layers",
                what="visits",
                needed=layers,
                limit=visits.cover * samples_here,
            )
        pixel, z, t = _fragments(np, (tri, row, start, lengths), planes, width)
        seen = z < zbuffer.reshape(-1)[pixel] + same_plane  # in front of the opaque one
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
