"""A robot as triangles to draw: every visual (or collision) shape, tessellated or read from
its mesh file, placed by the forward kinematics at a joint configuration, in the root
link's frame. `fishbot render` rasterises a scene; `fishbot view` sends one to the browser.

numpy is imported when a scene is built. Mesh files are found by the analysis's
``mesh_paths`` (`fishbot_urdf.analysis.meshpaths`: the files `check` finds) and read from STL
and OBJ
(by `fishbot_urdf.meshfile`); other formats need trimesh (the `mesh` extra). A mesh whose
file is not found is left out; one that cannot be read (malformed, not finite) is drawn as
its bounding box when its size is known (the vertices found in an STL or OBJ file, a
COLLADA file's positions), else left out; so is a shape whose coordinates, scaled and posed,
are not finite or lie farther than :data:`FARTHEST` from the root. Each is a finding in
``Scene.findings``, of the mesh rule it breaks (``shape-not-drawn`` for a shape too far);
a scene with nothing to draw at all is one more, an error (``nothing-drawn``).
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..analysis import Analysis, of
from ..analysis.meshpaths import State
from ..catalog import Rule
from ..catalog.meshes import (
    MESH_FORMAT,
    MESH_INVALID,
    NOTHING_DRAWN,
    SHAPE_NOT_DRAWN,
    MeshNotFoundFacts,
    NothingDrawnFacts,
)
from ..catalog.setup import TOOL_MISSING
from ..diagnostics import Diagnostic, Kind, Severity, Subject, sort_key
from ..errors import FishbotUrdfError, LimitError, ShapeError, ToolNotFoundError
from ..inputs import deadline, read_input
from ..kinematics import Kinematics
from ..meshfile import mesh_bounds, mesh_triangles
from ..model import Box, Cylinder, Geometry, Link, Material, Mesh, Origin, Robot, Sphere
from ..rules.meshes import unresolved
from ..spatial import rpy_matrix

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["FARTHEST", "Part", "Scene", "build_scene"]

FARTHEST = 1e9
"""The farthest a drawn shape's corner may lie from the root, in metres: farther than any
robot reaches, and near enough that drawing it (its normals are squares of its sizes) stays
within floating point."""

GREY = (0.7, 0.7, 0.72, 1.0)  # RViz draws a visual without a material in a light grey
_SEGMENTS = 48  # around a cylinder or sphere


@dataclass(frozen=True)
class Part:
    """One shape, posed: triangles (T, 3, 3) in the root frame, and its colour.

    Attributes:
        link: The link it belongs to.
        triangles: The corners of every triangle, in metres, in the root frame.
        color: Red, green, blue, alpha, each 0..1.
        local: The same triangles in the link's frame (what a viewer poses itself).
        pose: The link's 4x4 pose in the root frame.
    """

    link: str
    triangles: NDArray[Any]
    color: tuple[float, float, float, float]
    local: NDArray[Any] = field(repr=False)
    pose: NDArray[Any] = field(repr=False)


@dataclass(frozen=True)
class Scene:
    """Every drawn shape of a robot, and what could not be drawn as it is.

    Attributes:
        parts: The shapes, in link order.
        findings: One warning for each shape drawn as its bounding box, or not at all, at
            its element, with the rule it breaks; and, when no shape at all is drawn, an
            error of rule ``nothing-drawn`` at the robot (its ``data``: ``kind``,
            ``visual`` or ``collision``, and the robot's ``visuals`` and ``collisions``).
        poses: Every link's 4x4 pose in the root frame, by name.
    """

    parts: tuple[Part, ...]
    findings: tuple[Diagnostic, ...]
    poses: Mapping[str, NDArray[Any]]

    @property
    def warnings(self) -> tuple[str, ...]:
        """The findings' messages (deprecated: read ``findings``, which have their rule and
        place)."""
        warnings.warn(
            "Scene.warnings is deprecated: read Scene.findings", DeprecationWarning, stacklevel=2
        )
        return tuple(finding.message for finding in self.findings)

    def bounds(self) -> tuple[NDArray[Any], NDArray[Any]]:
        """The smallest and largest corner of the box around every part (or of the link
        frames, when nothing is drawn)."""
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        points = [p.triangles.reshape(-1, 3) for p in self.parts if len(p.triangles)]
        if not points:
            points = [np.array([pose[:3, 3] for pose in self.poses.values()])]
        every = np.concatenate(points)
        return every.min(axis=0), every.max(axis=0)


def build_scene(
    robot: Robot | Analysis,
    q: Any = None,
    *,
    collision: bool = False,
    packages: Mapping[str, str | Path] | None = None,
    path: str | None = None,
) -> Scene:
    """The robot's visual (or ``collision``) shapes posed at configuration ``q`` (see
    `fishbot_urdf.Kinematics`; None: every joint at zero). Mesh files are found by the
    analysis's ``mesh_paths``; ``path`` is the robot file relative mesh names are read
    beside (default: the analysis's), ``packages`` where ``package://`` names are found (as
    for ``$(find)``; default: the analysis's).

    Raises:
        StructureError: The robot has no single root.
        UnknownNameError, ArgumentError: ``q`` names an unknown joint or a bad value.
    """
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    analysis = of(robot, packages)
    if path is not None and path != analysis.path:
        analysis = replace(analysis, path=path)
    kin = Kinematics(analysis)
    config = np.zeros(len(kin.variables)) if q is None else q
    poses_array = kin.forward(config)
    poses = {name: poses_array[i] for i, name in enumerate(kin.links)}
    materials = {m.name: m for m in analysis.robot.materials if m.name}
    loader = _Loader(analysis)
    parts: list[Part] = []
    check = deadline()
    for link in analysis.robot.links:
        check.check("building the scene")
        if link.name not in poses:
            continue
        pose = poses[link.name]
        shapes: list[tuple[Geometry, Origin, Material | None]]
        if collision:
            shapes = [(c.geometry, c.origin, None) for c in link.collisions]
        else:
            shapes = [(v.geometry, v.origin, v.material) for v in link.visuals]
        loader.unresolved(link, [geometry for geometry, _, _ in shapes])
        for geometry, origin, material in shapes:
            local = loader.triangles(link, geometry)
            if local is None or not len(local):
                continue
            with np.errstate(over="ignore", invalid="ignore"):
                placed = _apply(np, _origin_matrix(np, origin), local)
                world = _apply(np, pose, placed)
                near_enough = bool((np.abs(world) <= FARTHEST).all())  # False for nan
            if not near_enough:
                loader.report(
                    SHAPE_NOT_DRAWN,
                    link,
                    geometry,
                    "is not drawn: its corners are not finite numbers, or lie farther than "
                    f"{FARTHEST:g} m from the root",
                    "a scale, a size or an origin holds a wild number",
                )
                continue
            color = (0.55, 0.7, 0.85, 1.0) if collision else _color(material, materials)
            parts.append(Part(link.name, world, color, placed, pose))
    if not parts:
        loader.findings.append(_nothing_drawn(analysis, collision, tuple(sorted(loader.missing))))
    return Scene(tuple(parts), tuple(sorted(loader.findings, key=sort_key)), poses)


def _nothing_drawn(analysis: Analysis, collision: bool, packages: tuple[str, ...]) -> Diagnostic:
    """The error of a scene with no shape in it: the robot has none of the kind asked for,
    or none of them could be drawn (each said by a warning of its own); ``packages``: those
    not found, that hold its meshes. Its facts say how many shapes of the other kind could
    be drawn, so that the other kind is offered only when that would draw something."""
    robot = analysis.robot
    visuals = [v.geometry for link in robot.links for v in link.visuals]
    collisions = [c.geometry for link in robot.links for c in link.collisions]
    kind, shapes, others = (
        ("collision", collisions, visuals) if collision else ("visual", visuals, collisions)
    )
    unfound = sum(1 for shape in shapes if not _drawable(analysis, shape))
    if shapes:
        many = f"none of its {len(shapes)} {kind} shapes can be drawn"
        what = many if len(shapes) > 1 else f"its only {kind} shape cannot be drawn"
        hint = None  # the warnings say why
        if unfound == len(shapes) > 1:
            hint = "none of its mesh files is found: each mesh-not-found warning says where"
        elif unfound == len(shapes):
            hint = "its mesh file is not found: the mesh-not-found warning says where"
    else:
        what, hint = f"no link has a {kind} shape", f"give a link a <{kind}>"
    return NOTHING_DRAWN.report(
        f"robot {robot.name!r}: {what}: there is nothing to draw",
        robot.source,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, robot.name),
        hint=hint,
        data=NothingDrawnFacts(
            kind=kind,
            visuals=len(visuals),
            collisions=len(collisions),
            other_drawable=sum(1 for shape in others if _drawable(analysis, shape)),
            meshes_not_found=unfound,
            packages=packages,
        ),
    )


def _drawable(analysis: Analysis, shape: Geometry) -> bool:
    """A shape a scene could draw, as far as can be told without reading mesh files: a box,
    cylinder or sphere, or a mesh whose file is found."""
    if not isinstance(shape, Mesh):
        return True
    return bool(shape.filename) and analysis.mesh_paths.get(shape.filename).state is State.FOUND


def _shown(geometry: Geometry) -> str:
    if isinstance(geometry, Mesh):
        return f"mesh {geometry.filename!r}"
    return type(geometry).__name__.lower()


def _apply(np: Any, matrix: Any, triangles: Any) -> Any:
    return triangles @ matrix[:3, :3].T + matrix[:3, 3]


def _origin_matrix(np: Any, origin: Origin) -> Any:
    out = np.eye(4)
    out[:3, :3] = np.array(rpy_matrix(origin.rpy))
    out[:3, 3] = origin.xyz
    return out


def _color(
    material: Material | None, materials: Mapping[str, Material]
) -> tuple[float, float, float, float]:
    """A visual's colour as urdfdom resolves it: the top-level material of its name first."""
    if material is None:
        return GREY
    defined = materials.get(material.name)
    for candidate in (defined, material):
        if candidate is not None and candidate.color is not None:
            r, g, b, a = candidate.color
            return (r, g, b, a)
    return GREY


class _Loader:
    """Shapes to triangles in their own frame; each mesh file read once."""

    def __init__(self, analysis: Analysis) -> None:
        self.analysis = analysis
        self.paths = analysis.mesh_paths
        self.read: dict[tuple[Path, tuple[float, ...]], Any] = {}
        self.findings: list[Diagnostic] = []
        self.missing: set[str] = set()  # packages not found, said once

    def report(self, rule: Rule, link: Link, shape: Geometry, what: str, hint: str | None) -> None:
        self.findings.append(
            rule.report(
                f"link {link.name!r}: {_shown(shape)} {what}",
                shape.source,
                path=self.analysis.path,
                subject=Subject(Kind.LINK, link.name),
                hint=hint,
                severity=Severity.WARNING,
            )
        )

    def unresolved(self, link: Link, shapes: list[Geometry]) -> None:
        """Say, once for each, which of a link's meshes lead to no file."""
        uses = [(link, shape) for shape in shapes if isinstance(shape, Mesh) and shape.filename]
        for finding in unresolved(self.analysis, uses, drawing=True):
            facts = finding.data
            package = facts.package if isinstance(facts, MeshNotFoundFacts) else None
            if package is not None:  # one finding for a package, for all its meshes
                if package in self.missing:
                    continue
                self.missing.add(package)
            self.findings.append(finding)

    def triangles(self, link: Link, geometry: Geometry) -> Any:
        import numpy as np  # numpy: ~190 ms to load, only where arrays are made

        if isinstance(geometry, Box):
            return _box(np, *geometry.size)
        if isinstance(geometry, Cylinder):
            return _cylinder(np, geometry.radius, geometry.length)
        if isinstance(geometry, Sphere):
            return _sphere(np, geometry.radius)
        if isinstance(geometry, Mesh):
            path = self.paths.get(geometry.filename)
            if not path.found or path.file is None:
                return None  # said by `unresolved`
            scale = geometry.scale or (1.0, 1.0, 1.0)
            key = (path.file, tuple(scale))
            if key not in self.read:
                self.read[key] = self._mesh(np, link, geometry, path.file, scale)
            return self.read[key]
        return None

    def _mesh(self, np: Any, link: Link, mesh: Mesh, file: Path, scale: tuple[float, ...]) -> Any:
        try:
            triangles = _read_mesh(np, file)
        except (OSError, FishbotUrdfError) as exc:
            if isinstance(exc, LimitError):  # the deadline: the whole scene stops
                raise
            triangles = None
            failure: OSError | FishbotUrdfError | None = exc
        else:
            failure = None
        factors = np.asarray(scale, dtype=float)
        if triangles is not None:
            with np.errstate(over="ignore", invalid="ignore"):
                return triangles * factors  # (not finite: left out by build_scene)
        box = _bounds_of(np, file)
        if box is not None:
            with np.errstate(over="ignore", invalid="ignore"):
                box = box[0] * factors, box[1] * factors
            if not (np.abs(box) <= FARTHEST).all():  # garbage read as numbers: no size
                box = None
        reason = getattr(failure, "message", None) or str(failure) or type(failure).__name__
        drawn = "nor its size: not drawn" if box is None else "drawn as its bounding box"
        kind = file.suffix.lower()
        rule: Rule = MESH_INVALID
        hint = "export the mesh again" if kind in (".stl", ".obj") else None
        if isinstance(failure, ToolNotFoundError):
            rule, hint = TOOL_MISSING, failure.hint
        elif kind not in (".stl", ".obj", ".dae"):
            rule, hint = MESH_FORMAT, "export it as STL or OBJ"
        self.report(rule, link, mesh, f"cannot be read ({reason}), {drawn}", hint)
        if box is None:
            return None
        low, high = box
        return _box(np, *(high - low)) + (low + high) / 2


def _read_mesh(np: Any, file: Path) -> Any:
    """Triangles (T, 3, 3) of an STL or OBJ file (others through trimesh, if installed)."""
    kind = file.suffix.lower()
    if kind in (".stl", ".obj"):
        return mesh_triangles(file)
    try:
        import trimesh  # the mesh extra (optional): ~600 ms to load
    except ImportError:
        raise ToolNotFoundError(
            f"reading a {kind or 'file without extension'} mesh needs the trimesh package",
            tool="trimesh",
            hint="pip install 'fishbot-urdf[mesh]'",
        ) from None
    try:
        loaded: Any = trimesh.load(str(file), force="mesh")
        if not hasattr(loaded, "triangles") or not len(loaded.faces):
            raise ShapeError("no triangles")
        triangles = np.asarray(loaded.triangles, dtype=float)
    except ShapeError:
        raise
    except Exception as exc:  # whatever a foreign reader makes of a file it cannot read
        raise ShapeError(str(exc) or type(exc).__name__) from exc
    if triangles.ndim != 3 or triangles.shape[1:] != (3, 3) or not np.isfinite(triangles).all():
        raise ShapeError("a vertex is not a finite number")
    return triangles


def _bounds_of(np: Any, file: Path) -> tuple[Any, Any] | None:
    """The box around a mesh file's vertices without reading it as a mesh: those an STL or
    OBJ file's facts found, or a COLLADA file's position arrays (its nodes' transforms left
    out); None when no finite box is found."""
    if file.suffix.lower() in (".stl", ".obj"):
        box = mesh_bounds(file)
        return None if box is None else (np.array(box[0]), np.array(box[1]))
    try:
        data = read_input(file)
    except LimitError:
        raise
    except (OSError, FishbotUrdfError):
        return None
    arrays = re.findall(rb"<float_array[^>]*positions?[^>]*>([^<]*)<", data, re.IGNORECASE)
    try:
        numbers = [float(v) for chunk in arrays for v in chunk.split()]
    except ValueError:
        return None
    if len(numbers) < 3:
        return None
    points = np.array(numbers[: len(numbers) // 3 * 3]).reshape(-1, 3)
    if not np.isfinite(points).all():
        return None
    return points.min(axis=0), points.max(axis=0)


def _box(np: Any, x: float, y: float, z: float) -> Any:
    c = np.array([[i, j, k] for i in (-0.5, 0.5) for j in (-0.5, 0.5) for k in (-0.5, 0.5)])
    c = c * np.array([x, y, z])
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1)]
    faces += [(2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    return c[np.array(faces)]


def _cylinder(np: Any, radius: float, length: float) -> Any:
    angles = np.linspace(0.0, 2 * math.pi, _SEGMENTS + 1)
    ring = np.stack([radius * np.cos(angles), radius * np.sin(angles)], axis=1)
    half = length / 2
    out = []
    for k in range(_SEGMENTS):
        (x0, y0), (x1, y1) = ring[k], ring[k + 1]
        out.append([[x0, y0, -half], [x1, y1, -half], [x1, y1, half]])
        out.append([[x0, y0, -half], [x1, y1, half], [x0, y0, half]])
        out.append([[0, 0, half], [x0, y0, half], [x1, y1, half]])
        out.append([[0, 0, -half], [x1, y1, -half], [x0, y0, -half]])
    return np.array(out, dtype=float)


def _sphere(np: Any, radius: float) -> Any:
    rows = _SEGMENTS // 2
    theta = np.linspace(0.0, math.pi, rows + 1)
    phi = np.linspace(0.0, 2 * math.pi, _SEGMENTS + 1)
    grid = (
        np.stack(
            [
                np.outer(np.sin(theta), np.cos(phi)),
                np.outer(np.sin(theta), np.sin(phi)),
                np.outer(np.cos(theta), np.ones_like(phi)),
            ],
            axis=-1,
        )
        * radius
    )
    out = []
    for i in range(rows):
        for j in range(_SEGMENTS):
            a, b = grid[i, j], grid[i, j + 1]
            c, d = grid[i + 1, j], grid[i + 1, j + 1]
            out.append([a, c, d])
            out.append([a, d, b])
    return np.array(out, dtype=float)
