"""The shapes of an MJCF body: URDF's visuals and collisions as MuJoCo geoms, and the mesh
files they name as assets."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path

from ..analysis import Analysis
from ..model import Box, Cylinder, Geometry, Mesh, Origin, Sphere
from ..spatial import quaternion, rpy_matrix

__all__ = [
    "COLLISION_GROUP",
    "LOADABLE",
    "VISUAL_GROUP",
    "Assets",
    "geom",
    "number",
    "numbers",
    "place",
]

LOADABLE = (".stl", ".obj")
"""The mesh files MuJoCo reads (by suffix, in any case); others are left out."""

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


class Assets:
    """The mesh assets of one model: one per file and scale, named after the file."""

    def __init__(self, analysis: Analysis, meshdir: str | None) -> None:
        self.analysis = analysis
        self.meshdir = meshdir
        self.element = ET.Element("asset")
        self._names: dict[tuple[Path, tuple[float, float, float] | None], str] = {}
        self._taken: set[str] = set()

    def mesh(self, mesh: Mesh) -> str | None:
        """The asset of ``mesh``'s file, or None when MuJoCo cannot read it (no file found,
        or not STL or OBJ)."""
        path = self.analysis.mesh_paths.get(mesh.filename)
        if not path.found or path.file is None or path.file.suffix.lower() not in LOADABLE:
            return None
        key = (path.file, mesh.scale)
        known = self._names.get(key)
        if known is not None:
            return known
        name, count = path.file.stem, 1
        while name in self._taken:
            count += 1
            name = f"{path.file.stem}_{count}"
        self._taken.add(name)
        self._names[key] = name
        element = ET.SubElement(self.element, "mesh", name=name, file=self._file(path.file))
        # MuJoCo computes a mesh's inertia even when it makes no mass of it, and refuses a
        # closed mesh that encloses no volume; as a shell it refuses none (and the number
        # goes unused: the model's masses are the robot's own)
        element.set("inertia", "shell")
        if mesh.scale is not None and mesh.scale != (1.0, 1.0, 1.0):
            element.set("scale", numbers(mesh.scale))
        return name

    def _file(self, file: Path) -> str:
        if self.meshdir is None:
            return str(file.resolve())
        return os.path.relpath(file.resolve(), Path(self.meshdir).resolve())


def geom(assets: Assets, geometry: Geometry, origin: Origin, *, visual: bool) -> ET.Element | None:
    """The geom of one visual or collision shape, or None when MuJoCo cannot have it (a mesh
    it cannot read)."""
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
        name = assets.mesh(geometry)
        if name is None:
            return None
        element.set("type", "mesh")
        element.set("mesh", name)
    place(element, origin)
    if visual:
        element.set("contype", "0")
        element.set("conaffinity", "0")
        element.set("group", str(VISUAL_GROUP))
    else:
        element.set("group", str(COLLISION_GROUP))
    return element
