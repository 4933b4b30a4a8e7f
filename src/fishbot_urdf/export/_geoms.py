"""The shapes of an MJCF body: URDF's visuals and collisions as MuJoCo geoms, and the mesh
files they name as assets."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import NamedTuple

from ..analysis import Analysis
from ..errors import InputError, ShapeError, ToolNotFoundError
from ..meshfile import MeshFacts, triangles_facts
from ..model import Box, Cylinder, Geometry, Mesh, Origin, Sphere
from ..spatial import quaternion, rpy_matrix
from .meshfolder import MOST_STL_TRIANGLES, MeshFolder

__all__ = [
    "COLLISION_GROUP",
    "VISUAL_GROUP",
    "Asset",
    "Assets",
    "geom",
    "number",
    "numbers",
    "place",
]

VISUAL_GROUP = 2
"""The geom group of a visual: drawn by MuJoCo's viewer by default, colliding with nothing."""
COLLISION_GROUP = 3
"""The geom group of a collision: hidden by MuJoCo's viewer by default."""


def number(value: float) -> str:
    """A number as the shortest text that reads back to the same double."""
    text = repr(float(value))
    return "0" if text in ("0.0", "-0.0") else text.removesuffix(".0")


def numbers(values: tuple[float, ...] | list[float]) -> str:
    return " ".join(map(number, values))


def place(element: ET.Element, origin: Origin) -> None:
    """Give ``element`` the ``pos`` and ``quat`` of a URDF ``<origin>`` (where not zero)."""
    if any(origin.xyz):
        element.set("pos", numbers(origin.xyz))
    if any(origin.rpy):
        x, y, z, w = quaternion(rpy_matrix(origin.rpy))
        element.set("quat", numbers((w, x, y, z)))


class Asset(NamedTuple):
    """The asset of a mesh, or why there is none."""

    name: str | None
    """The asset's name in the model; None when the shape is left out."""
    converted: str | None = None
    """The file the mesh was converted to, in the mesh folder; None when it was not."""
    why: str | None = None
    """Why the mesh is converted or left out (``is a .dae file, which MuJoCo cannot read``)."""
    hint: str | None = None
    """What to do about a mesh left out."""
    convertible: bool = False
    """Whether a mesh left out would have been converted into a mesh folder."""
    facts: MeshFacts | None = None
    """The facts of the file MuJoCo reads (the converted one, for a mesh converted)."""


class Assets:
    """The mesh assets of one model: one per file and scale, named after the file. Meshes
    MuJoCo cannot read as they are are converted into ``folder`` when one is given."""

    def __init__(
        self, analysis: Analysis, meshdir: str | None, folder: MeshFolder | None = None
    ) -> None:
        self.analysis = analysis
        self.meshdir = meshdir
        self.folder = folder
        self.converted = False
        """Whether a mesh was converted into ``folder``."""
        self.element = ET.Element("asset")
        self._names: dict[tuple[Path, tuple[float, float, float] | None], Asset] = {}
        self._taken: set[str] = set()

    def mesh(self, mesh: Mesh) -> Asset:
        """The asset of ``mesh``'s file: the file as it is when MuJoCo reads it, else
        converted into the folder; or why the shape is left out.

        Raises:
            InputError: The folder holds an input, or a converted file cannot be written.
        """
        path = self.analysis.mesh_paths.get(mesh.filename)
        if not path.found or path.file is None:
            return Asset(None, why="is not found", hint="name the file that is there")
        file = path.file
        key = (file, mesh.scale)
        known = self._names.get(key)
        if known is not None:
            return known
        why = self._unreadable(file)
        converted = None
        if why is None:
            facts = self.analysis.meshes.facts(file)
            few = _few(facts)
            if few is not None:
                return Asset(None, why=few, hint=_FEW_HINT)
        else:
            if self.folder is None:
                return Asset(None, why=why, hint="export it as binary STL or OBJ", convertible=True)
            try:
                triangles = self.analysis.meshes.triangles(file)
            except ToolNotFoundError as exc:
                return Asset(None, why=f"{why}, and {exc.message}", hint=exc.hint)
            except (ShapeError, InputError) as exc:
                return Asset(None, why=f"{why}, and cannot be converted: {exc.message}")
            facts = triangles_facts(triangles)
            few = _few(facts)
            if few is not None:
                return Asset(None, why=f"{why}, and {few}", hint=_FEW_HINT)
            converted = self.folder.add(file, triangles)  # (an error writing it stops all)
            self.converted = True
        name, count = file.stem, 1
        while name in self._taken:
            count += 1
            name = f"{file.stem}_{count}"
        self._taken.add(name)
        asset = self._names[key] = Asset(name, converted, why, facts=facts)
        where = converted if converted is not None else self._file(file)
        element = ET.SubElement(self.element, "mesh", name=name, file=where)
        # MuJoCo computes a mesh's inertia even when it makes no mass of it, and refuses a
        # closed mesh that encloses no volume; as a shell it refuses none (and the number
        # goes unused: the model's masses are the robot's own)
        element.set("inertia", "shell")
        if mesh.scale is not None and mesh.scale != (1.0, 1.0, 1.0):
            element.set("scale", numbers(mesh.scale))
        return asset

    def _unreadable(self, file: Path) -> str | None:
        """Why MuJoCo cannot read ``file`` as it is; None when it can."""
        suffix = file.suffix.lower()
        if suffix == ".obj":
            facts = self.analysis.meshes.facts(file)
            if facts is not None and facts.missing_normals:
                return "has normals, and faces that name none, which MuJoCo refuses"
            return None
        if suffix != ".stl":
            return f"is a {suffix} file, which MuJoCo cannot read" if suffix else "has no suffix"
        try:
            count = self.analysis.meshes.binary_count(file)
        except InputError:
            return "cannot be read"
        if count is None:
            facts = self.analysis.meshes.facts(file)
            if facts is None or not facts.faces:
                return "holds no triangles MuJoCo reads"
            return "is an ASCII STL, which MuJoCo cannot read"
        if count == 0:
            return "holds no triangles MuJoCo reads"
        if count > MOST_STL_TRIANGLES:
            return f"is an STL of {count:,} triangles, more than MuJoCo reads"
        return None

    def _file(self, file: Path) -> str:
        if self.meshdir is None:
            return str(file.resolve())
        return os.path.relpath(file.resolve(), Path(self.meshdir).resolve())


_FEW_HINT = "give it its thickness, or draw it as a thin box"
_LEAST_VERTICES = 4  # MuJoCo refuses a mesh of fewer ("at least 4 vertices required")


def _few(facts: MeshFacts | None) -> str | None:
    """Why MuJoCo refuses a mesh of these facts for its few distinct vertices; None when it
    does not (or they were not counted: a mesh of more than a few triangles)."""
    if facts is None or facts.vertices is None or facts.vertices >= _LEAST_VERTICES:
        return None
    return f"has {facts.vertices} distinct vertices, fewer than the {_LEAST_VERTICES} MuJoCo needs"


def geom(
    geometry: Geometry,
    origin: Origin,
    *,
    visual: bool,
    mesh: str | None = None,
    rgba: tuple[float, float, float, float] | None = None,
) -> ET.Element:
    """The geom of one visual or collision shape: a mesh by its asset's name ``mesh``, in
    the colour ``rgba`` when given."""
    element = ET.Element("geom")
    if isinstance(geometry, Box):
        element.set("type", "box")
        element.set("size", numbers([s / 2.0 for s in geometry.size]))
    elif isinstance(geometry, Cylinder):  # both along the local z
        element.set("type", "cylinder")
        element.set("size", numbers((geometry.radius, geometry.length / 2.0)))
    elif isinstance(geometry, Sphere):
        element.set("type", "sphere")
        element.set("size", number(geometry.radius))
    else:
        assert mesh is not None
        element.set("type", "mesh")
        element.set("mesh", mesh)
    place(element, origin)
    if rgba is not None:
        element.set("rgba", numbers(rgba))
    if visual:
        element.set("contype", "0")
        element.set("conaffinity", "0")
        element.set("group", str(VISUAL_GROUP))
    else:
        element.set("group", str(COLLISION_GROUP))
    return element
