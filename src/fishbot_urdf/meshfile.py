"""What a mesh file holds, read in plain Python: its face count and its extent.

Enough to tell a mesh exported in millimetres, or a collision mesh too fine for a simulator,
without numpy or trimesh: `check` reads STL (binary and ASCII) and OBJ this way. A binary
STL of many triangles is sampled evenly for its extent (the count is in its header).
COLLADA files carry their own unit and are not read here.
"""

from __future__ import annotations

import re
import struct
from dataclasses import dataclass
from pathlib import Path

from .errors import InputError
from .inputs import read_input
from .model import Vector3

__all__ = ["MeshFacts", "mesh_facts"]

_SAMPLES = 20_000  # triangles of a binary STL read for its extent, at most
_ASCII_VERTEX = re.compile(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)")
_OBJ_VERTEX = re.compile(rb"^[ \t]*v[ \t]+(\S+)[ \t]+(\S+)[ \t]+(\S+)", re.MULTILINE)
_OBJ_FACE = re.compile(rb"^[ \t]*f[ \t]", re.MULTILINE)


@dataclass(frozen=True, slots=True)
class MeshFacts:
    """A mesh file's face count and the box around its vertices, in the file's units.

    Attributes:
        faces: Triangles (STL) or polygons (OBJ).
        low: The smallest x, y, z of its vertices.
        high: The largest.
    """

    faces: int
    low: Vector3
    high: Vector3

    def extent(self, scale: Vector3 | None = None) -> float:
        """The largest side of the box around the vertices, after ``scale``."""
        factors = scale or (1.0, 1.0, 1.0)
        return max(abs((h - lo) * f) for lo, h, f in zip(self.low, self.high, factors, strict=True))


def mesh_facts(path: str | Path) -> MeshFacts | None:
    """The facts of an STL or OBJ file (by its extension); None for other formats, files
    that cannot be read, and files with no vertices."""
    kind = Path(path).suffix.lower()
    if kind not in (".stl", ".obj"):
        return None
    try:
        data = read_input(path)
    except (InputError, OSError):
        return None
    if kind == ".obj":
        return _bounds(_OBJ_VERTEX.findall(data), len(_OBJ_FACE.findall(data)))
    if len(data) >= 84:
        (count,) = struct.unpack_from("<I", data, 80)
        if len(data) == 84 + 50 * count:
            return _binary_stl(data, count)
    vertices = _ASCII_VERTEX.findall(data)
    return _bounds(vertices, len(vertices) // 3)


def _binary_stl(data: bytes, count: int) -> MeshFacts | None:
    if count == 0:
        return None
    step = max(1, count // _SAMPLES)
    lows = [float("inf")] * 3
    highs = [float("-inf")] * 3
    unpack = struct.Struct("<9f").unpack_from
    for index in range(0, count, step):
        values = unpack(data, 84 + 50 * index + 12)  # after the normal: three vertices
        for axis in range(3):
            trio = values[axis], values[axis + 3], values[axis + 6]
            lows[axis] = min(lows[axis], *trio)
            highs[axis] = max(highs[axis], *trio)
    return _facts(count, lows, highs)


def _bounds(vertices: list[tuple[bytes, bytes, bytes]], faces: int) -> MeshFacts | None:
    lows = [float("inf")] * 3
    highs = [float("-inf")] * 3
    for vertex in vertices:
        for axis in range(3):
            try:
                value = float(vertex[axis])
            except ValueError:
                continue
            lows[axis] = min(lows[axis], value)
            highs[axis] = max(highs[axis], value)
    return _facts(faces, lows, highs)


def _facts(faces: int, lows: list[float], highs: list[float]) -> MeshFacts | None:
    finite = all(abs(v) < float("inf") for v in (*lows, *highs))
    if not finite:  # no vertex read, or one at infinity (NaN comparisons leave inf)
        return None
    return MeshFacts(faces, (lows[0], lows[1], lows[2]), (highs[0], highs[1], highs[2]))
