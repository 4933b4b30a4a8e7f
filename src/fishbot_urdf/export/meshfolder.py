"""A folder of mesh files converted for MuJoCo: the triangles of a mesh it cannot read as it
is (COLLADA, PLY, glTF, an ASCII STL), written as a file it reads.

MuJoCo 4.0 reads a binary STL of 1 to 200,000 triangles and an OBJ; it refuses an ASCII STL
and an STL of 0 or more than 200,000 triangles (``number of faces should be between 1 and
200000``), and any other format (``no decoder found``). A converted mesh is a binary STL,
or an OBJ past 200,000 triangles. The same triangles make the same bytes, so converting
twice writes the same files (and a file that holds them already is left as it is).
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import InputError
from ..output import Source, write_atomic

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["MOST_STL_TRIANGLES", "MeshFolder"]

MOST_STL_TRIANGLES = 200_000
"""The most triangles MuJoCo reads from an STL file (its ``stl_decoder``)."""


class MeshFolder:
    """A folder converted mesh files are written to, each source file once, named after it.

    Args:
        path: The folder (made when the first file is written).
        inputs: The files the model is made from: none is written over, and the folder must
            not be one that holds any of them.
    """

    def __init__(self, path: str | Path, *, inputs: Iterable[Source] = ()) -> None:
        self.path = Path(path)
        self.inputs = tuple(inputs)
        self.written: list[Path] = []
        """The files written (or found holding what they would be written with), in order."""
        self._names: dict[Path, str] = {}
        self._taken: set[str] = set()
        self._folders: dict[str, Path] | None = None

    def add(self, source: Path, triangles: NDArray[Any]) -> str:
        """Write ``triangles`` (T, 3, 3), those of the file ``source``, into the folder, once
        per source; the name of the file written, in the folder.

        Raises:
            InputError: The folder holds an input, or the file cannot be written.
        """
        key = Path(os.path.abspath(source))
        known = self._names.get(key)
        if known is not None:
            return known
        self._refuse_input_folder(key)
        suffix = ".stl" if len(triangles) <= MOST_STL_TRIANGLES else ".obj"
        stem, count = source.stem, 1
        name = stem + suffix
        while name.lower() in self._taken:  # one name per file on a folder blind to case too
            count += 1
            name = f"{stem}_{count}{suffix}"
        self._taken.add(name.lower())
        self._names[key] = name
        data = _binary_stl(triangles, source.name) if suffix == ".stl" else _obj(triangles)
        target = self.path / name
        if not _holds(target, data):
            write_atomic(target, data, inputs=(*self.inputs, key), through_links=False)
        self.written.append(target)
        return name

    def _refuse_input_folder(self, source: Path) -> None:
        if self._folders is None:  # the inputs' folders, found once
            self._folders = {}
            for named in self.inputs:
                if not isinstance(named, int):
                    self._folders.setdefault(os.path.realpath(Path(named).parent), Path(named))
        folder = os.path.realpath(self.path)
        held = self._folders.get(folder)
        if held is None and os.path.realpath(source.parent) == folder:
            held = source
        if held is not None:
            raise InputError(
                f"refusing to write converted meshes into the folder of the input {held}",
                path=str(self.path),
            )


def _holds(target: Path, data: bytes) -> bool:
    """Whether ``target`` is a regular file (not a link) that holds ``data`` already."""
    try:
        if target.is_symlink() or not target.is_file() or target.stat().st_size != len(data):
            return False
        return target.read_bytes() == data
    except OSError:
        return False


def _binary_stl(triangles: NDArray[Any], name: str) -> bytes:
    """A binary STL of ``triangles``, each with its unit normal (0 for a triangle without
    area), a header that names the source."""
    import numpy as np  # numpy: ~190 ms to load, only where a mesh is converted

    corners = np.asarray(triangles, dtype=np.float64)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    normals = np.divide(
        normals, lengths[:, None], out=np.zeros_like(normals), where=lengths[:, None] > 0
    )
    record = np.zeros(
        len(corners), dtype=[("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("a", "<u2")]
    )
    record["normal"] = normals
    record["corners"] = corners
    header = f"binary STL converted by fishbot-urdf from {name}".encode("utf-8", "replace")
    header = header[:80].ljust(80, b" ")
    return header + len(corners).to_bytes(4, "little") + record.tobytes()


def _obj(triangles: NDArray[Any]) -> bytes:
    """An OBJ of ``triangles``: each distinct corner a vertex, each triangle a face."""
    import numpy as np  # numpy: ~190 ms to load, only where a mesh is converted

    corners = np.asarray(triangles, dtype=np.float64).reshape(-1, 3)
    vertices, index = np.unique(corners, axis=0, return_inverse=True)
    faces = index.reshape(-1, 3) + 1
    lines = ["# converted by fishbot-urdf"]
    lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += [f"f {a} {b} {c}" for a, b, c in faces.tolist()]
    return ("\n".join(lines) + "\n").encode("ascii")
