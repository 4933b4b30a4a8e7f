"""What a robot's mesh files hold, each answer about a file made once per analysis.

A robot's `MeshContents` is built with its analysis (``Analysis.meshes``); the checks, the
drawings and the mass computations ask it for what they need of a file that
``Analysis.mesh_paths`` found: its facts (`fishbot_urdf.meshfile.MeshFacts`: faces, box,
how far from flat), whether it is closed, its triangles, the box around what of it can be
read, and the volume, centre and inertia of the solid it encloses. Each answer is made once,
from the file's bytes read for it (by `fishbot_urdf.inputs.read_input`), and kept as long
as the analysis: a file the checks, a drawing and the mass computations all ask of is read
once for each kind of answer, not once for each caller and question.

The formats are read by `fishbot_urdf.meshfile` (STL and OBJ, strictly) and by trimesh (the
`mesh` extra) for the others and for solids. Errors are not kept: a file that cannot be read
is tried again (the limits in force may differ), one that is not a mesh is read again, to
raise its error again (a kept error's traceback would keep the frames of
the first caller, and all they hold).
"""

from __future__ import annotations

import io
import os
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from ..errors import ShapeError, ToolNotFoundError
from ..inputs import read_input
from ..meshfile import (
    MeshFacts,
    Reader,
    binary_stl_count,
    mesh_bounds,
    mesh_closed,
    mesh_facts,
    mesh_triangles,
)
from ..model import Vector3
from ..spatial import Matrix3

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["MeshContents", "Solid"]

_T = TypeVar("_T")

_SOLID_FORMATS = ("stl", "obj", "dae", "ply", "off", "glb")
"""Mesh files read for their solid (archives and formats that name other files are not)."""


@dataclass(frozen=True, slots=True)
class Solid:
    """What a closed mesh encloses, filled with a density of 1 kg/m^3.

    Attributes:
        volume: Its volume (m^3).
        centre: Its centre of mass (m).
        inertia: Its inertia about the centre (kg*m^2 at 1 kg/m^3).
        extent: The largest side of the box around it (m).
    """

    volume: float
    centre: Vector3
    inertia: Matrix3
    extent: float


class _Once:
    """One answer, made by the first thread that asks; the others wait for it."""

    __slots__ = ("done", "lock", "value")

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.done = False
        self.value: Any = None


class MeshContents:
    """The contents of mesh files, each answer made once (from one read of the file), by
    file. Safe to share between threads (a thread asking what another is reading waits for
    it)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._answers: dict[tuple[str, str, Vector3 | None], _Once] = {}

    def facts(self, file: Path) -> MeshFacts | None:
        """The facts of an STL or OBJ file (see `fishbot_urdf.meshfile.mesh_facts`); None
        for other formats, files that cannot be read and files with no vertices."""
        return self._once("facts", file, lambda: mesh_facts(file, self._bytes))

    def closed(self, file: Path) -> bool | None:
        """Whether every edge of an STL or OBJ file's mesh is shared by exactly two of its
        triangles (see `fishbot_urdf.meshfile.mesh_closed`); None when it is not well formed
        or cannot be read."""
        return self._once("closed", file, lambda: mesh_closed(file, self._bytes))

    def triangles(self, file: Path) -> NDArray[Any]:
        """The triangles (T, 3, 3) of a mesh file, in its units: STL and OBJ as
        `fishbot_urdf.meshfile.mesh_triangles` reads them, other formats through trimesh;
        a COLLADA file's as RViz places them, in metres (its nodes' transforms and its
        ``<unit meter>`` applied, its ``<up_axis>`` not).

        Raises:
            InputError: The file cannot be read (or is bigger than the size limit).
            ShapeError: The file is not well formed, or holds no triangles.
            ToolNotFoundError: The file is not STL or OBJ and trimesh is not installed (or,
                for COLLADA, pycollada).
            TimeLimitError: Reading went past the deadline in force.
        """
        if file.suffix.lower() in (".stl", ".obj"):
            return self._once("triangles", file, lambda: mesh_triangles(file, self._bytes))
        return self._once("triangles", file, lambda: _foreign_triangles(file, self._bytes))

    def binary_count(self, file: Path) -> int | None:
        """The triangles of a binary STL file (see `fishbot_urdf.meshfile.binary_stl_count`);
        None for any other file.

        Raises:
            InputError: The file cannot be read (or is bigger than the size limit).
        """
        return self._once("binary", file, lambda: binary_stl_count(file, self._bytes))

    def bounds(self, file: Path) -> tuple[Vector3, Vector3] | None:
        """The box around what vertices of a mesh file can be read, even when it is not well
        formed (see `fishbot_urdf.meshfile.mesh_bounds`); None when no finite box is found."""
        return self._once("bounds", file, lambda: mesh_bounds(file, self._bytes))

    def solid(self, file: Path, scale: Vector3 | None = None) -> Solid:
        """What the closed mesh of a file, scaled by ``scale``, encloses (through trimesh).

        Raises:
            ShapeError: The file is not a format read for a solid, cannot be read as one,
                holds no triangles, or is not closed.
            InputError: The file cannot be read.
            ToolNotFoundError: trimesh (or, for COLLADA, pycollada) is not installed.
        """
        return self._once("solid", file, lambda: _solid(file, self._bytes, scale), scale)

    def _bytes(self, file: str | Path) -> bytes:
        """The file's bytes, read for the answer being made. (Not kept: kept for as long as
        the analysis, a robot's meshes cost a check of the PyPI corpus in one process 6% of
        its time and 40 MB more at its peak, for the second read of a file that a drawing
        or an inertia asks of beside the checks.)"""
        return read_input(file)

    def _once(
        self, what: str, file: str | Path, make: Callable[[], _T], scale: Vector3 | None = None
    ) -> _T:
        """``what`` of ``file`` (at ``scale``), made by ``make`` when first asked (and asked
        again of it when it raised)."""
        key = (what, os.path.abspath(file), scale)
        with self._lock:
            answer = self._answers.get(key)
            if answer is None:
                answer = self._answers[key] = _Once()
        with answer.lock:
            if not answer.done:
                answer.value = make()
                answer.done = True
        value: _T = answer.value
        return value


def _foreign_triangles(file: Path, read: Reader) -> NDArray[Any]:
    """Triangles (T, 3, 3) of a mesh file that is not STL or OBJ, through trimesh."""
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    kind = file.suffix.lower()
    trimesh = _trimesh(f"reading a {kind or 'file without extension'} mesh")
    data = read(file)
    triangles: NDArray[Any]
    try:
        if kind == ".dae":
            triangles = _collada_triangles(np, trimesh, data)
        else:
            loaded: Any = trimesh.load(io.BytesIO(data), file_type=kind.lstrip("."), force="mesh")
            if not hasattr(loaded, "triangles") or not len(loaded.faces):
                raise ShapeError("no triangles")
            triangles = np.asarray(loaded.triangles, dtype=float)
    except ImportError as exc:  # COLLADA is read by the pycollada package, which is optional
        if kind == ".dae":
            raise _no_pycollada(file) from exc
        raise ShapeError(str(exc) or type(exc).__name__) from exc
    except ShapeError:
        raise
    except Exception as exc:  # whatever a foreign reader makes of a file it cannot read
        raise ShapeError(str(exc) or type(exc).__name__) from exc
    if triangles.ndim != 3 or triangles.shape[1:] != (3, 3) or not np.isfinite(triangles).all():
        raise ShapeError("a vertex is not a finite number")
    return triangles


def _collada_triangles(np: Any, trimesh: Any, data: bytes) -> Any:
    """A COLLADA file's triangles as RViz draws them: each geometry moved by its nodes'
    transforms (trimesh does so), in metres by the file's ``<unit meter>`` (trimesh notes
    the unit but does not apply it), its ``<up_axis>`` ignored (as RViz and trimesh do)."""
    scene: Any = trimesh.load(io.BytesIO(data), file_type="dae", force="scene")
    if scene.units not in (None, "meters"):
        scene = scene.convert_units("meters")
    parts = [np.asarray(g.triangles, dtype=float) for g in scene.dump() if hasattr(g, "faces")]
    parts = [p for p in parts if len(p)]
    if not parts:
        raise ShapeError("no triangles")
    return np.concatenate(parts)


def _no_pycollada(file: Path) -> ToolNotFoundError:
    return ToolNotFoundError(
        f"reading the COLLADA mesh {file} needs the pycollada package",
        tool="pycollada",
        hint="pip install 'fishbot-urdf[mesh]'",
    )


def _solid(path: Path, read: Reader, scale: Vector3 | None) -> Solid:
    """The closed trimesh mesh of ``path`` (its bytes read by ``read``), scaled, as plain
    numbers."""
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    trimesh = _trimesh("the inertia of a mesh")
    kind = path.suffix.lower().lstrip(".")
    if kind not in _SOLID_FORMATS:
        raise ShapeError(
            f"the mesh {path} is not a file fishbot reads ({', '.join(_SOLID_FORMATS)}, by "
            "its extension)",
            path=str(path),
        )
    data = read(path)  # a regular file within the size limit
    # Coordinates near the floats' limit overflow inside trimesh: the numbers come out as
    # inf or nan, refused by the caller, rather than as warnings on stderr.
    with np.errstate(all="ignore"):
        try:
            mesh: Any = trimesh.load(io.BytesIO(data), file_type=kind, force="mesh")
        except ImportError as exc:
            if kind == "dae":  # COLLADA is read by the pycollada package, which is optional
                raise _no_pycollada(path) from exc
            raise ShapeError(
                f"cannot read the mesh {path} as {kind.upper()}", path=str(path)
            ) from exc
        except Exception as exc:  # whatever a foreign reader makes of bytes that are no mesh
            raise ShapeError(
                f"cannot read the mesh {path} as {kind.upper()}: {exc}", path=str(path)
            ) from exc
        if type(mesh).__name__ != "Trimesh" or len(mesh.faces) == 0:
            raise ShapeError(f"the mesh {path} holds no triangles", path=str(path))
        if scale is not None:
            mesh.apply_scale(scale)
        if not mesh.is_watertight:
            raise ShapeError(f"the mesh {path} is not closed, so it has no volume", path=str(path))
        mesh.density = 1.0
        return Solid(
            float(mesh.volume),
            tuple(float(c) for c in mesh.center_mass),  # type: ignore[arg-type]
            _matrix3(mesh.moment_inertia),
            float(max(mesh.extents)),
        )


def _trimesh(what: str) -> Any:
    """The trimesh module, or an error that says ``what`` needs it and how to install it."""
    try:
        import trimesh  # the mesh extra (optional): ~600 ms to load
    except ImportError:
        raise ToolNotFoundError(
            f"{what} needs the trimesh package",
            tool="trimesh",
            hint="pip install 'fishbot-urdf[mesh]'",
        ) from None
    return trimesh


def _matrix3(array: Any) -> Matrix3:
    rows = [tuple(float(v) + 0.0 for v in row) for row in array]  # + 0.0: no -0
    return (rows[0], rows[1], rows[2])  # type: ignore[return-value]
