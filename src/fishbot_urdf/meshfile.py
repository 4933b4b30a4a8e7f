"""What a mesh file holds: its face count, its extent and whether it is closed, and its
triangles, read strictly.

The facts are enough to tell a mesh exported in millimetres, or a collision mesh too fine for
a simulator, without trimesh: `check` reads STL (binary and ASCII) and OBJ this way, every
vertex looked at in numpy (the count of a binary STL is in its header). A file's facts are
read once per process while its size and time of change stay the same. Whether a mesh is
closed is read only when asked. COLLADA files carry their own unit: only the box around their
positions is read (:func:`mesh_bounds`).

The triangles (:func:`mesh_triangles`, for drawing) are read only from a well-formed file: a
binary STL as long as its header says, numbers that are numbers and finite, OBJ faces whose
vertices exist. Anything else is a :class:`~fishbot_urdf.errors.ShapeError` that says what
is wrong and where, never a foreign exception. Both readers check the deadline in force
(:func:`fishbot_urdf.inputs.deadline`) as they go.

Each function reads the file's bytes with ``read`` (by default
:func:`~fishbot_urdf.inputs.read_input`): the owner of a robot's mesh contents
(`fishbot_urdf.analysis.meshcontents`) passes its own, which reads each file once.
"""

from __future__ import annotations

import bisect
import io
import math
import os
import re
import struct
import threading
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .errors import InputError, ShapeError
from .inputs import deadline, read_input
from .model import Vector3

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = [
    "EmptyMeshError",
    "MeshFacts",
    "Reader",
    "binary_stl_count",
    "mesh_bounds",
    "mesh_closed",
    "mesh_facts",
    "mesh_triangles",
    "triangles_facts",
]


class EmptyMeshError(ShapeError):
    """A mesh file holds no triangles at all (an empty file, a placeholder)."""


_RECORD = [("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")]
"""One triangle of a binary STL file: 50 bytes."""
# The same record as nine coordinates of their own (x of the first corner, y, z, x of the
# second, ...): a minimum over one of them is a plain loop over the file, where one over the
# corners block goes a row of three at a time, twelve times slower.
_COORDINATES = {
    "names": [f"{axis}{corner}" for corner in range(3) for axis in "xyz"],
    "formats": ["<f4"] * 9,
    "offsets": [12 + 4 * index for index in range(9)],
    "itemsize": 50,
}
_KNOWN_MOST = 4096  # the most files whose facts are kept
_STEP = 4096  # vertices or faces read between two looks at the deadline
_ASCII_VERTEX = re.compile(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)")
_OBJ_VERTEX = re.compile(rb"^[ \t]*v[ \t]+(\S+)[ \t]+(\S+)[ \t]+(\S+)", re.MULTILINE)
_OBJ_VERTEX_LINE = re.compile(rb"^[ \t]*v[ \t]", re.MULTILINE)
_OBJ_FACE = re.compile(rb"^[ \t]*f[ \t]", re.MULTILINE)
_OBJ_FACE_LINE = re.compile(rb"^[ \t]*f[ \t]+([^\r\n]*)", re.MULTILINE)
# The bytes of the vertex lines numpy's reader takes as the patterns above do: numbers
# written plainly, spaces and tabs, line ends.
_PLAIN_VERTICES = b"v0123456789+-.eE \t\r\n"
_COLLADA_POSITIONS = re.compile(rb"<float_array[^>]*positions?[^>]*>([^<]*)<", re.IGNORECASE)

Reader = Callable[[str | Path], bytes]
"""What reads a file's bytes: :func:`~fishbot_urdf.inputs.read_input`, or one that keeps
them."""


@dataclass(frozen=True, slots=True)
class MeshFacts:
    """A mesh file's face count and the box around its vertices, in the file's units.

    Attributes:
        faces: Triangles (STL) or polygons (OBJ).
        low: The smallest x, y, z of its vertices.
        high: The largest.
        path: The file they were read from (None for facts made otherwise); `closed`
            reads it.
        spread: How far its vertices lie, at most, from the plane that fits them best and
            from the line that does (0 and 0: a point; 0 and more: flat, no volume for a
            convex hull); the line's only for a mesh within 0.1% of its size of flat
            (None for the others); None when not measured.
        vertices: Its distinct vertices, counted for a mesh of a few triangles only (None
            for the others).
        binary: Whether an STL file is written in binary (MuJoCo reads no other); None for
            an OBJ file.
        missing_normals: Whether an OBJ file has normals (``vn``) and a face that names
            none (MuJoCo refuses it: ``normal index out of bounds``).
    """

    faces: int
    low: Vector3
    high: Vector3
    path: str | None = field(default=None, compare=False, repr=False)
    spread: tuple[float, float | None] | None = field(default=None, compare=False, repr=False)
    vertices: int | None = field(default=None, compare=False, repr=False)
    binary: bool | None = field(default=None, compare=False, repr=False)
    missing_normals: bool = field(default=False, compare=False, repr=False)

    def extent(self, scale: Vector3 | None = None) -> float:
        """The largest side of the box around the vertices, after ``scale``."""
        factors = scale or (1.0, 1.0, 1.0)
        return max(abs((h - lo) * f) for lo, h, f in zip(self.low, self.high, factors, strict=True))

    @property
    def closed(self) -> bool | None:
        """Whether every edge of the mesh is shared by exactly two of its triangles (see
        :func:`mesh_closed`): read from the file when first asked, not with the other
        facts (it costs several times their reading). None when the file cannot be read."""
        return None if self.path is None else mesh_closed(self.path)


def mesh_facts(path: str | Path, read: Reader | None = None) -> MeshFacts | None:
    """The facts of an STL or OBJ file (by its extension); None for other formats, files
    that cannot be read, and files with no vertices.

    A file's facts are read once per process and kept while its size and time of change
    stay the same: robots checked together often share their meshes.
    """
    kind = Path(path).suffix.lower()
    if kind not in (".stl", ".obj"):
        return None
    key = _key(path)
    if key is None:
        return None
    with _KNOWN_LOCK:
        if key in _KNOWN:
            return _KNOWN[key]
    try:
        data = (read or read_input)(path)
    except (InputError, OSError):
        return None  # (not kept: the size limit in force may differ next time)
    facts = _read_facts(kind, data)
    if facts is not None:
        facts = replace(facts, path=key[0])
    with _KNOWN_LOCK:
        if len(_KNOWN) >= _KNOWN_MOST:
            _KNOWN.clear()
        _KNOWN[key] = facts
    return facts


def mesh_closed(path: str | Path, read: Reader | None = None) -> bool | None:
    """Whether every edge of an STL or OBJ file's mesh is shared by exactly two of its
    triangles, corners at the same place taken as one vertex (a mesh that encloses a
    volume, as a mass computed from it needs); None when the file is not well formed
    (:func:`mesh_triangles` says why) or cannot be read. Kept, as the facts are, while the
    file's size and time of change stay the same.

    Raises:
        TimeLimitError: Reading went past the deadline in force.
    """
    key = _key(path)
    if key is None:
        return None
    with _KNOWN_LOCK:
        if key in _CLOSED:
            return _CLOSED[key]
    try:
        triangles = mesh_triangles(path, read)
    except (ShapeError, InputError):
        return None
    closed = _closed(triangles)
    with _KNOWN_LOCK:
        if len(_CLOSED) >= _KNOWN_MOST:
            _CLOSED.clear()
        _CLOSED[key] = closed
    return closed


def _key(path: str | Path) -> tuple[str, int, int, int] | None:
    """What a file's facts are kept by: its path, and its inode, size and time of change."""
    try:
        status = os.stat(path)
    except (OSError, ValueError):
        return None
    return (os.path.abspath(path), status.st_ino, status.st_size, status.st_mtime_ns)


_KNOWN: dict[tuple[str, int, int, int], MeshFacts | None] = {}
_CLOSED: dict[tuple[str, int, int, int], bool] = {}
_KNOWN_LOCK = threading.Lock()


def _closed(triangles: NDArray[Any]) -> bool:
    """Whether every edge of ``triangles`` (T, 3, 3) is shared by exactly two of them."""
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    corners = np.ascontiguousarray(triangles.reshape(-1, 3) + 0.0)  # (-0.0 is 0.0)
    # Equal corners welded into one vertex: sorted by a hash of their bits, then the hash's
    # groups checked to hold one place each (sorting the places themselves is slower).
    bits = corners.view(np.uint64)
    hashed = (bits[:, 0] * np.uint64(0x9E3779B97F4A7C15)) ^ (
        bits[:, 1] * np.uint64(0xC2B2AE3D27D4EB4F)
    )
    hashed ^= bits[:, 2]
    _, first, vertex = np.unique(hashed, return_index=True, return_inverse=True)
    if not np.array_equal(corners[first[vertex]], corners):  # two places, one hash
        _, vertex = np.unique(corners, axis=0, return_inverse=True)
    vertex = vertex.reshape(-1, 3).astype(np.int64)
    ends = np.stack([vertex, np.roll(vertex, -1, axis=1)])
    edges = np.sort(
        np.minimum(ends[0], ends[1]).ravel() << 32 | np.maximum(ends[0], ends[1]).ravel()
    )
    if len(edges) % 2:
        return False
    # Sorted, each edge twice: the pairs (0, 1), (2, 3), ... equal, and no pair equal to
    # the next.
    return bool((edges[0::2] == edges[1::2]).all() and (edges[1:-1:2] != edges[2::2]).all())


def _read_facts(kind: str, data: bytes) -> MeshFacts | None:
    if kind == ".obj":
        facts = _obj_facts(data)
        if facts is None or not _OBJ_NORMAL.search(data):
            return facts
        return replace(facts, missing_normals=bool(_OBJ_FACE_WITHOUT_NORMAL.search(data)))
    count = _binary_count(data)
    if count is not None:
        facts = _binary_stl(data, count)
        return None if facts is None else replace(facts, binary=True)
    vertices = _ASCII_VERTEX.findall(data)
    facts = _bounds(vertices, len(vertices) // 3)
    return None if facts is None else replace(facts, binary=False)


_OBJ_NORMAL = re.compile(rb"^[ \t]*vn[ \t]", re.MULTILINE)
# a face with a corner of a vertex alone, or a vertex and a texture coordinate ("3", "3/1")
_OBJ_FACE_WITHOUT_NORMAL = re.compile(
    rb"^[ \t]*f[ \t](?:[^\n#]*?[ \t])?-?\d+(?:/-?\d*)?(?=[ \t\r#]|$)", re.MULTILINE
)


def _obj_facts(data: bytes) -> MeshFacts | None:
    """An OBJ file's facts: its lines told apart by their first two bytes in numpy, its
    vertex lines read by numpy's reader; by the patterns (ten times slower) when a line
    starts with white space, or a vertex line holds more than plain numbers."""
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    padded = b"\n" + data + b"\n\n"  # every line after a line end, two bytes past the last
    text = np.frombuffer(padded, np.uint8)
    starts = np.flatnonzero(text[:-2] == ord("\n")) + 1
    first, second = text[starts], text[starts + 1]
    blank, tab = (first == ord(" ")) | (first == ord("\t")), second == ord("\t")
    vertex, face = first == ord("v"), first == ord("f")
    if blank.any() or ((vertex | face) & tab).any():
        return _bounds(_OBJ_VERTEX.findall(data), len(_OBJ_FACE.findall(data)))
    faces = int((face & (second == ord(" "))).sum())
    vertex &= second == ord(" ")
    # Each run of vertex lines, from the start of its first to that of the line after it.
    edges = np.flatnonzero(np.diff(vertex.view(np.int8), prepend=0, append=0))
    bounds = np.append(starts, len(padded) - 1)[edges].tolist()
    lines = b"".join(padded[bounds[i] : bounds[i + 1]] for i in range(0, len(bounds), 2))
    if not lines:
        return None
    if lines.translate(None, _PLAIN_VERTICES) or lines.count(b"\r") != lines.count(b"\r\n"):
        return _bounds(_OBJ_VERTEX.findall(data), faces)

    try:
        numbers = np.loadtxt(io.BytesIO(lines), usecols=(1, 2, 3), comments=None, ndmin=2)
    except ValueError:  # a line of fewer than three numbers, or a word that is none
        return _bounds(_OBJ_VERTEX.findall(data), faces)
    if not np.isfinite(numbers).all():
        return _bounds(_OBJ_VERTEX.findall(data), faces)
    lows, highs = numbers.min(axis=0).tolist(), numbers.max(axis=0).tolist()
    return _facts(faces, lows, highs, list(numbers.T))


def mesh_bounds(path: str | Path, read: Reader | None = None) -> tuple[Vector3, Vector3] | None:
    """The smallest and largest corner of the box around what vertices of a mesh file can
    be read, even when the file is not well formed. For an STL or OBJ file: those of its
    facts (numbers that are not numbers left out), or, for a binary STL longer or shorter
    than its header says, those of the whole records it holds; for any other (COLLADA):
    those of its position arrays, its nodes' transforms left out. None when no finite box
    is found.

    Raises:
        TimeLimitError: Reading went past the deadline in force.
    """
    kind = Path(path).suffix.lower()
    facts = mesh_facts(path, read) if kind in (".stl", ".obj") else None
    if facts is not None:
        return facts.low, facts.high
    if kind == ".obj":
        return None
    try:
        data = (read or read_input)(path)
    except (InputError, OSError):
        return None
    if kind != ".stl":
        return _positions_bounds(data)
    if len(data) < 84 + 50 or _ASCII_VERTEX.search(data):
        return None
    records = (len(data) - 84) // 50
    facts = _binary_stl(data[: 84 + 50 * records], records)
    return None if facts is None else (facts.low, facts.high)


def _positions_bounds(data: bytes) -> tuple[Vector3, Vector3] | None:
    """The box around a COLLADA file's position arrays, when all are finite numbers."""
    arrays = _COLLADA_POSITIONS.findall(data)
    try:
        numbers = [float(v) for chunk in arrays for v in chunk.split()]
    except ValueError:
        return None
    points = numbers[: len(numbers) // 3 * 3]
    if not points or not all(math.isfinite(v) for v in points):
        return None
    low, high = [min(points[k::3]) for k in range(3)], [max(points[k::3]) for k in range(3)]
    return (low[0], low[1], low[2]), (high[0], high[1], high[2])


def triangles_facts(triangles: NDArray[Any]) -> MeshFacts | None:
    """The facts of triangles (T, 3, 3) read from a file of another format (a COLLADA
    file, for one): as a file of them would have; None for none, or a vertex at infinity."""
    corners = triangles.reshape(-1, 3)
    if not len(corners):
        return None
    axes = [corners[:, k] for k in range(3)]
    lows = [float(axis.min()) for axis in axes]
    highs = [float(axis.max()) for axis in axes]
    return _facts(len(triangles), lows, highs, axes)


def binary_stl_count(path: str | Path, read: Reader | None = None) -> int | None:
    """The triangles of a binary STL file, as its header counts them, when its length is
    what that count makes it; None for any other file (an ASCII STL, one cut short).

    Raises:
        InputError: The file cannot be read (or is bigger than the size limit).
    """
    return _binary_count((read or read_input)(path))


def _binary_count(data: bytes) -> int | None:
    """The triangles of a binary STL file: None unless its length is what its header says."""
    if len(data) < 84:
        return None
    (count,) = struct.unpack_from("<I", data, 80)
    return count if len(data) == 84 + 50 * count else None


def _binary_stl(data: bytes, count: int) -> MeshFacts | None:
    """Every corner of every triangle, looked at in numpy (a file of a million triangles
    in a few milliseconds; a loop over them in Python took a second)."""
    if count == 0:
        return None
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    records: Any = np.frombuffer(data, np.dtype(_COORDINATES), count, 84)  # type: ignore[call-overload]
    lows, highs, axes = [], [], []
    for axis in "xyz":
        values = np.concatenate([records[f"{axis}{corner}"] for corner in range(3)])
        lows.append(float(values.min()))
        highs.append(float(values.max()))
        axes.append(values)
    return _facts(count, lows, highs, axes)


def _bounds(vertices: list[tuple[bytes, bytes, bytes]], faces: int) -> MeshFacts | None:
    if vertices:
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        try:  # every number read at once; a word that is none, one by one below
            numbers = np.array(vertices).astype(float)
        except ValueError:
            numbers = None
        if numbers is not None and np.isfinite(numbers).all():
            lows, highs = numbers.min(axis=0).tolist(), numbers.max(axis=0).tolist()
            return _facts(faces, lows, highs, list(numbers.T))
    lows = [float("inf")] * 3
    highs = [float("-inf")] * 3
    check = deadline()
    for number, vertex in enumerate(vertices):
        if not number % _STEP:
            check.check("reading meshes")
        for axis in range(3):
            try:
                value = float(vertex[axis])
            except ValueError:
                continue
            lows[axis] = min(lows[axis], value)
            highs[axis] = max(highs[axis], value)
    return _facts(faces, lows, highs)


def _facts(
    faces: int, lows: list[float], highs: list[float], axes: list[Any] | None = None
) -> MeshFacts | None:
    finite = all(abs(v) < float("inf") for v in (*lows, *highs))
    if not finite:  # no vertex read, or one at infinity (NaN comparisons leave inf)
        return None
    spread, vertices = _spread(axes) if axes is not None else (None, None)
    low, high = (lows[0], lows[1], lows[2]), (highs[0], highs[1], highs[2])
    return MeshFacts(faces, low, high, spread=spread, vertices=vertices)


_FEW = 12  # the vertices of a mesh of at most this many corners are counted
_SAMPLE = 20_000  # the vertices whose principal axes give the plane and the line
_NEAR_FLAT = 1e-3  # a mesh this thin, for its size, is measured again in double


def _spread(axes: list[Any]) -> tuple[tuple[float, float | None], int | None]:
    """How far the vertices (their x, y and z columns) lie, at most, from the plane and the
    line that fit them best (the line only for a mesh near flat), and how many distinct
    ones a mesh of a few corners has.

    The plane's normal and the line's direction are the principal axes of at most
    ``_SAMPLE`` of the vertices, evenly spread (a flat mesh's sample is flat too). The
    distances of all of them are taken in the file's precision, and again in double for a
    mesh within ``_NEAR_FLAT`` of flat. The facts of the PyPI corpus's meshes take 40%
    longer for it (0.83 s to 1.17 s), mostly numpy's cost per call on small files; with the
    principal axes of every vertex in double, 50%."""
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    step = max(1, len(axes[0]) // _SAMPLE)
    sample = np.stack([np.asarray(a[::step], dtype=np.float64) for a in axes])
    scale = max(float(np.abs(sample).max()), 1e-300)
    sample /= scale  # (coordinates near the floats' limit would overflow in the products)
    middle = sample.mean(axis=1)
    sample -= middle[:, None]
    _, directions = np.linalg.eigh(sample @ sample.T)  # eigenvalues ascending: the normal first
    size = max(float(np.abs(sample).max()) * scale, 1e-300)
    middle *= scale

    def farthest(k: int, kind: Any) -> float:
        n = directions[:, k].astype(kind)
        along = axes[0] * n[0]  # each vertex along n, less the middle's: its distance
        along += axes[1] * n[1]
        along += axes[2] * n[2]
        centre = float(directions[:, k] @ middle)
        return max(float(along.max()) - centre, centre - float(along.min()))

    with np.errstate(over="ignore", invalid="ignore"):  # inf: too far apart to be flat
        plane = farthest(0, axes[0].dtype)
    line = None
    if plane <= _NEAR_FLAT * size:
        plane, line = farthest(0, np.float64), farthest(1, np.float64)
    vertices = None
    if len(axes[0]) <= _FEW:
        vertices = len(np.unique(np.stack([np.asarray(a) for a in axes], axis=1), axis=0))
    return (plane, line), vertices


def mesh_triangles(path: str | Path, read: Reader | None = None) -> NDArray[Any]:
    """The triangles of an STL (binary or ASCII) or OBJ file (by its extension), in the
    file's units: an array (T, 3, 3) of every triangle's corners. An OBJ polygon is cut
    into a fan of triangles.

    Raises:
        InputError: The file cannot be read (or is bigger than the size limit).
        ShapeError: The file is not one of those formats, or is not well formed: empty, a
            binary STL shorter or longer than its header says, a number that is not one or
            not finite, a face naming a vertex that does not exist, or no triangles at all.
        TimeLimitError: Reading went past the deadline in force.
    """
    name = str(path)
    kind = Path(name).suffix.lower()
    if kind not in (".stl", ".obj"):
        raise ShapeError(f"{kind or 'no extension'}: not an STL or OBJ file", path=name)
    data = (read or read_input)(path)
    if not data.strip():
        raise EmptyMeshError("the file is empty", path=name)
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    triangles: NDArray[Any] = _obj(np, data, name) if kind == ".obj" else _stl(np, data, name)
    if not len(triangles):
        raise EmptyMeshError(f"no triangles in the {kind[1:].upper()} file", path=name)
    if not np.isfinite(triangles).all():
        raise ShapeError("a vertex is not a finite number", path=name)
    return triangles


def _stl(np: Any, data: bytes, name: str) -> Any:
    count = _binary_count(data)
    if count is not None:
        record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("a", "<u2")])
        return np.frombuffer(data, record, count, 84)["corners"].astype(float)
    found = _ASCII_VERTEX.findall(data)
    if not found:
        if len(data) >= 84:
            (claimed,) = struct.unpack_from("<I", data, 80)
            raise ShapeError(
                f"not an ASCII STL, nor a binary one: a binary STL of {claimed:,} triangles "
                f"is {84 + 50 * claimed:,} bytes long, not {len(data):,}",
                path=name,
            )
        raise EmptyMeshError("no triangles in the STL file", path=name)
    if len(found) % 3:
        raise ShapeError(f"{len(found):,} vertices are not a whole number of triangles", path=name)
    corners = _numbers(np, found, name, "vertex")
    return corners.reshape(-1, 3, 3)


def _numbers(np: Any, rows: list[tuple[bytes, ...]], name: str, what: str) -> Any:
    """The rows of numbers read as floats, or an error naming the first that is not one."""
    try:
        return np.array(rows, dtype=float)
    except ValueError:
        pass
    read = []
    for row in rows:  # one at a time, to say which
        values = []
        for token in row:
            try:
                values.append(float(token))
            except ValueError:
                shown = token[:40].decode("utf-8", "replace")
                raise ShapeError(f"{what} {shown!r} is not a number", path=name) from None
        read.append(values)
    return np.array(read, dtype=float)


def _obj(np: Any, data: bytes, name: str) -> Any:
    matches = list(_OBJ_VERTEX.finditer(data))
    if len(matches) != len(_OBJ_VERTEX_LINE.findall(data)):
        raise ShapeError("a vertex ('v' line) has fewer than three numbers", path=name)
    vertices = _numbers(np, [m.groups() for m in matches], name, "vertex")
    starts = [m.start() for m in matches]
    triangles: list[tuple[int, int, int]] = []
    check = deadline()
    for number, face in enumerate(_OBJ_FACE_LINE.finditer(data)):
        if not number % _STEP:
            check.check("reading meshes")
        index = [_vertex_index(token, face, starts, data, name) for token in face[1].split()]
        if len(index) < 3:
            raise ShapeError(
                f"line {_line(data, face)}: a face of fewer than three vertices", path=name
            )
        triangles.extend((index[0], index[k], index[k + 1]) for k in range(1, len(index) - 1))
    if not triangles:
        return np.empty((0, 3, 3))
    return vertices[np.array(triangles)]


def _vertex_index(
    token: bytes, face: re.Match[bytes], starts: list[int], data: bytes, name: str
) -> int:
    """A face's vertex (``7``, ``7/1``, ``7//2``, ``-1``) as an index into the vertices;
    a negative one counts back from the last vertex before the face, as OBJ says."""
    text = token.split(b"/")[0]
    try:
        given = int(text)
    except ValueError:
        shown = text[:40].decode("utf-8", "replace")
        raise ShapeError(
            f"line {_line(data, face)}: vertex {shown!r} of a face is not a whole number",
            path=name,
        ) from None
    before = bisect.bisect_left(starts, face.start())  # vertices defined above the face
    index = given - 1 if given > 0 else before + given
    if given == 0 or not 0 <= index < (len(starts) if given > 0 else before):
        defined = len(starts) if given > 0 else before
        raise ShapeError(
            f"line {_line(data, face)}: a face names vertex {given}, of {defined:,}"
            + (" (OBJ counts from 1)" if given == 0 else ""),
            path=name,
        )
    return index


def _line(data: bytes, match: re.Match[bytes]) -> int:
    return data.count(b"\n", 0, match.start()) + 1
