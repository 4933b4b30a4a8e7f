"""A robot as triangles to draw: every visual (or collision) shape, tessellated or read from
its mesh file, placed by the forward kinematics at a joint configuration, in the root
link's frame; and, on request, what RViz's "Mass Properties" and link axes show: each
link's mass as a ball of lead at its centre of mass, its inertia as the equivalent box on
its principal axes (`fishbot_urdf.inertia.equivalent_box`), and its frame as three axes;
and what Gazebo will simulate: its sensors' rays and frustums, and the links sdformat's
converter lumps together (`fishbot_urdf.analysis.gazebo`) in one colour each.
`fishbot render` rasterises a scene; `fishbot view` sends one to the browser.

numpy is imported when a scene is built. Mesh files are found by the analysis's
``mesh_paths`` (`fishbot_urdf.analysis.meshpaths`: the files `check` finds) and read by its
``meshes`` (`fishbot_urdf.analysis.meshcontents`: STL and OBJ by `fishbot_urdf.meshfile`,
other formats through trimesh, the `mesh` extra), as `check` reads them. A mesh whose
file is not found is left out; one that cannot be read (malformed, not finite) is drawn as
its bounding box when its size is known (the vertices found in an STL or OBJ file, a
COLLADA file's positions), else left out; so is a shape whose coordinates, scaled and posed,
are not finite or lie farther than :data:`FARTHEST` from the root. Each is a finding in
``Scene.findings``, of the mesh rule it breaks (``shape-not-drawn`` for a shape too far);
a scene with nothing to draw at all is one more, an error (``nothing-drawn``). An inertia
that has no equivalent box (RViz draws none either) is a ``shape-not-drawn`` warning that
says why (`fishbot_urdf.inertia.why_no_box`).
"""

from __future__ import annotations

import warnings
from collections.abc import Collection, Mapping, Sequence
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
from ..errors import ArgumentError, FishbotUrdfError, LimitError, ToolNotFoundError
from ..inertia import NoBox
from ..inputs import deadline
from ..kinematics import Kinematics
from ..model import (
    Box,
    Cylinder,
    Geometry,
    Inertial,
    Link,
    Material,
    Mesh,
    Origin,
    Robot,
    Sphere,
)
from ..rules.meshes import unresolved
from ..wording import did_you_mean
from ._lumping import tints
from ._marks import AXES_SHARE, SEEN_THROUGH, axes, axes_length, inertial_marks
from ._sensors import LIDAR_DEPTH, LIDAR_ROBOTS, reach, sensor_marks
from ._shapes import apply, box, cylinder, origin_matrix, sphere

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = [
    "AXES_SHARE",
    "FARTHEST",
    "LAYERS",
    "SEEN_THROUGH",
    "Part",
    "Scene",
    "build_scene",
    "in_gazebo_colours",
]

FARTHEST = 1e9
"""The farthest a drawn shape's corner may lie from the root, in metres: farther than any
robot reaches, and near enough that drawing it (its normals are squares of its sizes) stays
within floating point."""

LAYERS = ("visual", "collision", "mass", "inertia", "frames", "sensors", "gazebo")
"""What a scene can show: the visual shapes, the collision shapes, each link's mass sphere
and inertia box, each link's frame as axes, the Gazebo sensors' rays and frustums, and the
visual shapes coloured by the Gazebo link sdformat's converter lumps each link into."""

GREY = (0.7, 0.7, 0.72, 1.0)  # RViz draws a visual without a material in a light grey
COLLISION = (0.55, 0.7, 0.85, 1.0)


@dataclass(frozen=True)
class Part:
    """One shape, posed: triangles (T, 3, 3) in the root frame, and its colour.

    Attributes:
        link: The link it belongs to.
        triangles: The corners of every triangle, in metres, in the root frame.
        color: Red, green, blue, alpha, each 0..1.
        local: The same triangles in the link's frame (what a viewer poses itself).
        pose: The link's 4x4 pose in the root frame.
        layer: What it shows, one of :data:`LAYERS`.
        lines: For lines (a lidar's rays, a frustum's edges), their segments (N, 2, 3) in
            the link's frame, which a viewer may draw as lines of a width on screen; the
            triangles draw them as thin boxes. None for a shape.
    """

    link: str
    triangles: NDArray[Any]
    color: tuple[float, float, float, float]
    local: NDArray[Any] = field(repr=False)
    pose: NDArray[Any] = field(repr=False)
    layer: str = "visual"
    lines: NDArray[Any] | None = field(default=None, repr=False)


@dataclass(frozen=True)
class Scene:
    """Every drawn shape of a robot, and what could not be drawn as it is.

    Attributes:
        parts: The shapes, in link order.
        findings: One warning for each shape drawn as its bounding box, or not at all, at
            its element, with the rule it breaks, in the order of their places; and, when no
            shape at all is drawn, after them (it sums them up), an error of rule
            ``nothing-drawn`` at the robot (its ``data``: ``kind``, the
            layers asked for, such as ``visual``, ``collision`` or ``mass,inertia``, and
            the robot's ``visuals`` and ``collisions``).
        poses: Every link's 4x4 pose in the root frame, by name.
        axes_length: How long a link frame's axes are drawn (m): :data:`AXES_SHARE` of
            the robot's size.
    """

    parts: tuple[Part, ...]
    findings: tuple[Diagnostic, ...]
    poses: Mapping[str, NDArray[Any]]
    axes_length: float = 0.1

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
    show: Collection[str] | None = None,
) -> Scene:
    """The robot's visual (or ``collision``) shapes posed at configuration ``q`` (see
    `fishbot_urdf.Kinematics`; None: every joint at zero). Mesh files are found by the
    analysis's ``mesh_paths``; ``path`` is the robot file relative mesh names are read
    beside (default: the analysis's), ``packages`` where ``package://`` names are found (as
    for ``$(find)``; default: the analysis's).

    ``show`` picks what is drawn among :data:`LAYERS` (``collision`` adds the collision
    shapes to it): ``mass``, for each link with an ``<inertial>``, a sphere of the diameter
    `fishbot_urdf.inertia.mass_sphere_diameter` gives at its centre of mass; ``inertia``,
    the box `fishbot_urdf.inertia.equivalent_box` gives, centred there and turned onto the
    principal axes (in the frame of the inertial's origin), both red, opaque as RViz draws
    them but seen through (alpha :data:`SEEN_THROUGH`) when drawn with the visual or
    collision shapes, which an opaque box would hide; ``frames``, each link's x, y and z
    axes in red, green and blue, :attr:`Scene.axes_length` long; ``sensors``, the sensors of
    the robot's ``<gazebo reference>`` blocks at their poses on their links (as sdformat
    keeps them where they are on a link it lumps into another): each lidar's rays from its
    minimum to its maximum range and the arc at the maximum in orange, each camera's
    frustum in purple (`fishbot_urdf.drawing._sensors`); ``gazebo``, the visuals coloured
    by the link of the Gazebo model sdformat's converter makes each link part of, one colour
    for each (`fishbot_urdf.drawing._lumping`), a link it leaves out dark and seen through.
    Default: the visuals (with ``collision``: the collision shapes alone).

    Raises:
        StructureError: The robot has no single root.
        UnknownNameError, ArgumentError: ``q`` names an unknown joint or a bad value;
            ``show`` names no layer.
    """
    import numpy as np  # numpy: ~190 ms to load, only where arrays are made

    layers = _layers(show, collision)
    analysis = of(robot, packages)
    if path is not None and path != analysis.path:
        analysis = replace(analysis, path=path)
    kin = Kinematics(analysis)
    config = np.zeros(len(kin.variables)) if q is None else q
    poses_array = kin.forward(config)
    poses = {name: poses_array[i] for i, name in enumerate(kin.links)}
    loader = _Loader(analysis)
    parts: list[Part] = []
    check = deadline()
    for link in analysis.robot.links:
        check.check("building the scene")
        if link.name not in poses:
            continue
        pose = poses[link.name]
        shapes: list[tuple[Geometry, Origin, Material | None, str]] = []
        if "visual" in layers or "gazebo" in layers:  # (gazebo: recoloured below)
            shapes += [(v.geometry, v.origin, analysis.material(v), "visual") for v in link.visuals]
        if "collision" in layers:
            shapes += [(c.geometry, c.origin, None, "collision") for c in link.collisions]
        loader.unresolved(link, [geometry for geometry, _, _, _ in shapes])
        for geometry, origin, material, layer in shapes:
            local = loader.triangles(link, geometry)
            if local is None or not len(local):
                continue
            placed = _placed(np, loader, link, geometry, origin_matrix(np, origin), local, pose)
            if placed is None:
                continue
            color = COLLISION if layer == "collision" else _color(material)
            parts.append(Part(link.name, apply(np, pose, placed), color, placed, pose, layer))
        if link.inertial is not None and ("mass" in layers or "inertia" in layers):
            parts += _inertial_parts(np, loader, link, link.inertial, pose, layers)
    points = [part.triangles.reshape(-1, 3) for part in parts]
    origins = np.array([pose[:3, 3] for pose in poses.values()]).reshape(-1, 3)
    length = axes_length(np, np.concatenate(points) if points else origins)
    if "frames" in layers:
        for name in kin.links:
            pose = poses[name]
            for mark in axes(np, length):
                world = apply(np, pose, mark.triangles)
                parts.append(Part(name, world, mark.color, mark.triangles, pose, mark.layer))
    if "gazebo" in layers:
        parts = in_gazebo_colours(analysis, parts)
    if "sensors" in layers:  # after the axes' length: a lidar's reach is not the robot's size
        placed = [
            (s, poses[s.link]) for s in analysis.sensors if s.link is not None and s.link in poses
        ]
        body = length / AXES_SHARE  # the robot's size
        depth = max(LIDAR_DEPTH, LIDAR_ROBOTS * body)
        size = max([body, *(reach(s, depth) for s, _ in placed)])
        for sensor, pose in placed:
            for mark in sensor_marks(np, sensor, size, depth):
                world = apply(np, pose, mark.triangles)
                parts.append(
                    Part(
                        sensor.link or "",
                        world,
                        mark.color,
                        mark.triangles,
                        pose,
                        mark.layer,
                        mark.lines,
                    )
                )
    # By place, as check lists them; but nothing-drawn, at the robot's first line, speaks of
    # the warnings that say why each shape is not drawn: it comes after them, as a summary.
    findings = sorted(loader.findings, key=sort_key)
    if not parts:
        findings.append(_nothing_drawn(analysis, layers, tuple(sorted(loader.missing))))
    return Scene(tuple(parts), tuple(findings), poses, length)


def in_gazebo_colours(analysis: Analysis, parts: Sequence[Part]) -> list[Part]:
    """``parts`` with the visuals in their Gazebo colours, of layer ``gazebo``: one colour for
    each link of the Gazebo model sdformat's converter makes (the links it lumps into one
    share it), a link it leaves out dark and seen through (`fishbot_urdf.drawing._lumping`).

    Raises:
        StructureError: The robot has no single root.
    """
    tinted = tints(analysis.gazebo_lumping)
    return [
        replace(part, color=tinted.get(part.link, GREY), layer="gazebo")
        if part.layer == "visual"
        else part
        for part in parts
    ]


def _layers(show: Collection[str] | None, collision: bool) -> tuple[str, ...]:
    """The layers asked for, in :data:`LAYERS` order."""
    if show is None:
        return ("collision",) if collision else ("visual",)
    if isinstance(show, str):
        show = (show,)
    for layer in show:
        if layer not in LAYERS:
            raise ArgumentError(_not_a_layer(layer), name="show")
    asked = {*show, *(("collision",) if collision else ())}
    if not asked:
        raise ArgumentError(f"nothing to show: name one of {', '.join(LAYERS)}", name="show")
    return tuple(layer for layer in LAYERS if layer in asked)


def _not_a_layer(name: str) -> str:
    """What is said of a name that is no layer: the layer it looks like, and all of them."""
    return f"nothing to show called {name!r} ({did_you_mean(name, LAYERS)}{', '.join(LAYERS)})"


def _placed(
    np: Any,
    loader: _Loader,
    link: Link,
    shape: Geometry | Inertial,
    origin: Any,
    local: Any,
    pose: Any,
) -> Any:
    """A shape's triangles in its link's frame, or None (with a finding) when, posed, a
    corner would not be finite or lie farther than :data:`FARTHEST` from the root."""
    with np.errstate(over="ignore", invalid="ignore"):
        placed = apply(np, origin, local)
        near_enough = bool((np.abs(apply(np, pose, placed)) <= FARTHEST).all())  # False: nan
    if near_enough:
        return placed
    loader.report(
        SHAPE_NOT_DRAWN,
        link,
        shape,
        "is not drawn: its corners are not finite numbers, or lie farther than "
        f"{FARTHEST:g} m from the root",
        "a scale, a size or an origin holds a wild number",
    )
    return None


def _inertial_parts(
    np: Any,
    loader: _Loader,
    link: Link,
    inertial: Inertial,
    pose: Any,
    layers: tuple[str, ...],
) -> list[Part]:
    """A link's mass sphere and inertia box, as RViz draws them (see `build_scene`)."""
    with np.errstate(over="ignore", invalid="ignore"):  # (not finite: _placed says so)
        marks, no_box = inertial_marks(np, inertial, layers)
    if no_box is not None:
        what, hint = _NO_BOX[no_box]
        loader.report(
            SHAPE_NOT_DRAWN,
            link,
            inertial,
            "has no inertia box drawn (RViz draws none either): " + what.format(mass=inertial.mass),
            hint,
        )
    parts = []
    for mark in marks:
        local = _placed(np, loader, link, inertial, np.eye(4), mark.triangles, pose)
        if local is not None:
            world = apply(np, pose, local)
            parts.append(Part(link.name, world, mark.color, local, pose, mark.layer))
    return parts


_NO_BOX = {  # why an inertial has no box, and what to do
    NoBox.NOT_FINITE: (
        "its mass or inertia holds a number that is not finite, or so large that products "
        "of them overflow",
        "write the mass in kg and the inertia in kg*m^2",
    ),
    NoBox.MASS: (
        "its mass, {mass:g} kg, is not positive",
        "give the link its mass in kg; a link that carries no mass needs no <inertial>",
    ),
    NoBox.NOT_DEFINITE: (
        "its inertia is not positive definite: ixx, ixx*iyy - ixy^2 and the determinant are "
        "not all above 0",
        "a moment is negative or 0, or a product too large: compute the inertia again, from "
        "the part's shape and mass",
    ),
    NoBox.TRIANGLE: (
        "a principal moment of its inertia is larger than the other two together",
        "no solid has such moments: compute the inertia again, from the part's shape and mass",
    ),
}


def _nothing_drawn(
    analysis: Analysis, layers: tuple[str, ...], packages: tuple[str, ...]
) -> Diagnostic:
    """The error of a scene with no shape in it: the robot has none of the kinds asked for,
    or none of them could be drawn (each said by a warning of its own); ``packages``: those
    not found, that hold its meshes. Its facts say how many shapes of the other kind could
    be drawn, so that the other kind is offered only when that would draw something."""
    robot = analysis.robot
    shapes_of = {
        "visual": [v.geometry for link in robot.links for v in link.visuals],
        "collision": [c.geometry for link in robot.links for c in link.collisions],
    }
    inertials = sum(link.inertial is not None for link in robot.links)
    tags = list(dict.fromkeys(_TAGS[layer] for layer in layers if layer in _TAGS))
    shapes = [shape for tag in tags for shape in shapes_of.get(tag, ())]
    count = len(shapes) + (inertials if "inertial" in tags else 0)
    other = {"visual": "collision", "collision": "visual"}.get(tags[0]) if len(tags) == 1 else None
    others = shapes_of[other] if other else []
    unfound = sum(1 for shape in shapes if not _drawable(analysis, shape))
    kind = " or ".join(tags)
    if count:
        noun = "inertial" if tags == ["inertial"] else f"{kind} shape"
        many = f"none of its {count} {noun}s can be drawn"
        what = many if count > 1 else f"its only {noun} cannot be drawn"
        hint = None  # the warnings before it say why
        if unfound == count > 1:
            hint = "none of its mesh files is found: each mesh-not-found warning says where"
        elif unfound == count:
            hint = "its mesh file is not found: the mesh-not-found warning says where"
    else:
        elements = " or ".join(_ELEMENTS[tag] for tag in tags)
        what, hint = f"no link has {elements}", f"give a link {_ARTICLES[tags[0]]} <{tags[0]}>"
        if tags[0] == "sensor":
            hint = 'write a <sensor type="ray"> or "camera" in a <gazebo reference="LINK"> block'

    return NOTHING_DRAWN.report(
        f"robot {robot.name!r}: {what}: there is nothing to draw",
        robot.source,
        path=analysis.path,
        subject=Subject(Kind.ROBOT, robot.name),
        hint=hint,
        data=NothingDrawnFacts(
            kind=",".join(layers),
            visuals=len(shapes_of["visual"]),
            collisions=len(shapes_of["collision"]),
            other_drawable=sum(1 for shape in others if _drawable(analysis, shape)),
            meshes_not_found=unfound,
            packages=packages,
        ),
    )


_TAGS = {
    "visual": "visual",
    "collision": "collision",
    "mass": "inertial",
    "inertia": "inertial",
    "sensors": "sensor",
    "gazebo": "visual",
}
_ELEMENTS = {
    "visual": "a visual shape",
    "collision": "a collision shape",
    "inertial": "an <inertial>",
    "sensor": "a lidar or camera <sensor> in its <gazebo reference> block",
}
_ARTICLES = {"visual": "a", "collision": "a", "inertial": "an", "sensor": "a"}


def _drawable(analysis: Analysis, shape: Geometry) -> bool:
    """A shape a scene could draw, as far as can be told without reading mesh files: a box,
    cylinder or sphere, or a mesh whose file is found."""
    if not isinstance(shape, Mesh):
        return True
    return bool(shape.filename) and analysis.mesh_paths.get(shape.filename).state is State.FOUND


def _shown(shape: Geometry | Inertial) -> str:
    if isinstance(shape, Mesh):
        return f"mesh {shape.filename!r}"
    return type(shape).__name__.lower()


def _color(material: Material | None) -> tuple[float, float, float, float]:
    """A visual's colour: its material's (as `Analysis.material` resolves it), else grey."""
    if material is None or material.color is None:
        return GREY
    r, g, b, a = material.color
    return (r, g, b, a)


class _Loader:
    """Shapes to triangles in their own frame; each mesh file scaled once."""

    def __init__(self, analysis: Analysis) -> None:
        self.analysis = analysis
        self.paths = analysis.mesh_paths
        self.meshes = analysis.meshes
        self.read: dict[tuple[Path, tuple[float, ...]], Any] = {}
        self.findings: list[Diagnostic] = []
        self.missing: set[str] = set()  # packages not found, said once

    def report(
        self, rule: Rule, link: Link, shape: Geometry | Inertial, what: str, hint: str | None
    ) -> None:
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
            return box(np, *geometry.size)
        if isinstance(geometry, Cylinder):
            return cylinder(np, geometry.radius, geometry.length)
        if isinstance(geometry, Sphere):
            return sphere(np, geometry.radius)
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
            triangles = self.meshes.triangles(file)
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
        found = self.meshes.bounds(file)
        with np.errstate(over="ignore", invalid="ignore"):
            bounds = None if found is None else np.array(found) * factors  # low, high
        if bounds is not None and not (np.abs(bounds) <= FARTHEST).all():
            bounds = None  # garbage read as numbers: no size
        reason = getattr(failure, "message", None) or str(failure) or type(failure).__name__
        drawn = "nor its size: not drawn" if bounds is None else "drawn as its bounding box"
        kind = file.suffix.lower()
        rule: Rule = MESH_INVALID
        hint = "export the mesh again" if kind in (".stl", ".obj") else None
        if isinstance(failure, ToolNotFoundError):
            rule, hint = TOOL_MISSING, failure.hint
        elif kind not in (".stl", ".obj", ".dae"):
            rule, hint = MESH_FORMAT, "export it as STL or OBJ"
        self.report(rule, link, mesh, f"cannot be read ({reason}), {drawn}", hint)
        if bounds is None:
            return None
        low, high = bounds
        return box(np, *(high - low)) + (low + high) / 2
