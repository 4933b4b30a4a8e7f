"""Inertia of uniform solids: the closed forms of the fishbot's common_inertia.xacro, closed
meshes, and several solids taken together.

Every function returns an ``Inertial`` whose numbers are the very floats the xacro macros
produce (the same operations in the same order), about the solid's centre, in its own
frame: pass the ``origin`` of the visual or collision it belongs to.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

from ..analysis.meshcontents import MeshContents
from ..analysis.meshpaths import MeshPaths
from ..errors import ArgumentError, InertiaUnderflowError, ShapeError
from ..model import (
    ZERO3,
    Box,
    Cylinder,
    Geometry,
    Inertia,
    Inertial,
    Mesh,
    Origin,
    Sphere,
    Vector3,
)
from ..packages import PackageFinder
from ..spatial import (
    Matrix3,
    Pose,
    add,
    eigenvalues,
    mat_add,
    point_mass_tensor,
    rotate_tensor,
    scale,
)

__all__ = [
    "MassProperties",
    "box_inertia",
    "combine",
    "cylinder_inertia",
    "geometry_inertia",
    "mesh_inertia",
    "principal_moments",
    "solid_moments",
    "sphere_inertia",
    "volume",
]

_AT_LINK = Origin()


def box_inertia(m: float, w: float, h: float, d: float, origin: Origin = _AT_LINK) -> Inertial:
    """The inertial of a solid box of mass ``m`` (kg) and sides ``w``, ``h``, ``d`` (m).

    The sides are along x, y and z, as ``<box size="w h d"/>``: ixx = m/12 (h^2 + d^2),
    iyy = m/12 (w^2 + d^2), izz = m/12 (w^2 + h^2) (kg*m^2).

    Raises:
        InertiaUnderflowError: A moment that is positive comes out 0 or subnormal (a box
            of sides 1e-200 m)."""
    moments = _box(m, w, h, d)
    _representable("box", (("x", w), ("y", h), ("z", d)), m, moments, ((h, d), (w, d), (w, h)))
    return _diagonal(m, moments, origin)


def cylinder_inertia(m: float, r: float, h: float, origin: Origin = _AT_LINK) -> Inertial:
    """The inertial of a solid cylinder of mass ``m`` (kg), radius ``r`` and height ``h`` (m).

    The height is along its z axis, as ``<cylinder radius="r" length="h"/>``:
    ixx = iyy = m/12 (3 r^2 + h^2), izz = m/2 r^2 (kg*m^2).

    Raises:
        InertiaUnderflowError: A moment that is positive comes out 0 or subnormal."""
    moments = _cylinder(m, r, h)
    _representable("cylinder", (("radius", r), ("length", h)), m, moments, ((r, h), (r, h), (r,)))
    return _diagonal(m, moments, origin)


def sphere_inertia(m: float, r: float, origin: Origin = _AT_LINK) -> Inertial:
    """A solid sphere of mass ``m`` (kg) and radius ``r`` (m): 2/5 m r^2 about every axis.

    Raises:
        InertiaUnderflowError: The moment comes out 0 or subnormal (a radius of 1e-200 m)."""
    moments = _sphere(m, r)
    _representable("sphere", (("radius", r),), m, moments, ((r,), (r,), (r,)))
    return _diagonal(m, moments, origin)


_SMALLEST = sys.float_info.min
"""The smallest normal float (2.2e-308): below it a number keeps fewer digits, down to 0."""


def _representable(
    shape: str,
    sizes: tuple[tuple[str, float], ...],
    m: float,
    moments: Vector3,
    lengths: tuple[tuple[float, ...], ...],
) -> None:
    """Refuse moments that are positive (a positive mass, and a length they are made of
    that is not 0) but come out 0 or subnormal: a tensor of zeros that no simulator takes.

    Raises:
        InertiaUnderflowError: One does."""
    for moment, made_of in zip(moments, lengths, strict=True):
        if m > 0 and any(length != 0 for length in made_of) and abs(moment) < _SMALLEST:
            raise InertiaUnderflowError(shape, sizes, m, moments)


def solid_moments(shape: Box | Cylinder | Sphere, mass: float) -> Vector3:
    """ixx, iyy and izz of a box, cylinder or sphere filled uniformly with ``mass`` (kg), in
    its own frame (where its products are 0): the numbers `geometry_inertia` gives."""
    if isinstance(shape, Box):
        return _box(mass, *shape.size)
    if isinstance(shape, Cylinder):
        return _cylinder(mass, shape.radius, shape.length)
    return _sphere(mass, shape.radius)


def _box(m: float, w: float, h: float, d: float) -> Vector3:
    return (m / 12.0 * (h * h + d * d), m / 12.0 * (w * w + d * d), m / 12.0 * (w * w + h * h))


def _cylinder(m: float, r: float, h: float) -> Vector3:
    across = m / 12.0 * (3 * r * r + h * h)
    return (across, across, m / 2.0 * r * r)


def _sphere(m: float, r: float) -> Vector3:
    moment = 2.0 / 5.0 * m * r * r
    return (moment, moment, moment)


def _diagonal(m: float, moments: Vector3, origin: Origin) -> Inertial:
    ixx, iyy, izz = moments
    return Inertial(mass=m, inertia=Inertia(ixx=ixx, iyy=iyy, izz=izz), origin=origin)


def geometry_inertia(
    geometry: Geometry,
    mass: float,
    origin: Origin = _AT_LINK,
    resolve: Callable[[Mesh], Path] | None = None,
    *,
    meshes: MeshContents | None = None,
) -> Inertial:
    """The inertia of a URDF shape filled uniformly with ``mass`` (kg).

    A box, cylinder or sphere, or a closed mesh when the optional trimesh package is
    installed.

    A mesh's file is found by ``resolve`` (for a robot's mesh, its analysis's
    ``mesh_paths.file``, as every command finds it), or else by the rule of
    `fishbot_urdf.analysis.meshpaths` with the file the mesh was read from as the robot file (the
    working folder for a mesh made in Python); it is read by ``meshes`` (for a robot's
    mesh, its analysis's ``meshes``, which read each file once), or else read for this call.

    Raises:
        ArgumentError: The geometry is not a box, cylinder, sphere or mesh.
        ShapeError: The mesh is not closed.
        InertiaUnderflowError: The shape is too small for its moments to be floats.
        PackageNotFoundError: The mesh's package is not found.
        MeshNotFoundError: The mesh's file is not found.
        ToolNotFoundError: The geometry is a mesh and trimesh is not installed.
    """
    if isinstance(geometry, Box):
        x, y, z = geometry.size
        return box_inertia(mass, x, y, z, origin)
    if isinstance(geometry, Cylinder):
        return cylinder_inertia(mass, geometry.radius, geometry.length, origin)
    if isinstance(geometry, Sphere):
        return sphere_inertia(mass, geometry.radius, origin)
    if isinstance(geometry, Mesh):
        where = resolve(geometry) if resolve is not None else _mesh_file(geometry)
        return mesh_inertia(where, mass, origin, geometry.scale, meshes=meshes)
    raise ArgumentError(
        f"no closed form for {type(geometry).__name__} (box, cylinder, sphere, mesh)",
        name="geometry",
    )


def _mesh_file(mesh: Mesh) -> Path:
    # A mesh made in Python has no file: its relative name is read from the working folder.
    robot_file = mesh.source.path if mesh.source else os.path.join(os.curdir, "robot.urdf")
    return MeshPaths(robot_file, PackageFinder()).file(mesh)


def principal_moments(inertia: Inertia) -> Vector3:
    """The eigenvalues of the inertia matrix, smallest first (kg*m^2)."""
    return eigenvalues(inertia.matrix())


def _inertia(m: Matrix3) -> Inertia:
    return Inertia(ixx=m[0][0], ixy=m[0][1], ixz=m[0][2], iyy=m[1][1], iyz=m[1][2], izz=m[2][2])


@dataclass(frozen=True, slots=True)
class MassProperties:
    """The mass properties of several bodies taken together.

    Attributes:
        mass: Total mass (kg).
        com: Centre of mass (m), in the frame the bodies were given in.
        inertia: Inertia about the centre of mass, axes of that frame (kg*m^2).
    """

    mass: float
    com: Vector3
    inertia: Inertia

    @property
    def principal_moments(self) -> Vector3:
        """The eigenvalues of ``inertia``, smallest first (kg*m^2)."""
        return principal_moments(self.inertia)


def exact_sum(values: list[float]) -> float:
    """The correctly rounded sum; inf or nan, as plain addition gives, where a partial sum
    leaves the floats or infinities meet (``math.fsum`` raises there)."""
    try:
        return math.fsum(values)
    except (OverflowError, ValueError):  # ValueError: inf and -inf among the values
        return sum(values)


def combine(parts: Iterable[tuple[Inertial, Pose]]) -> MassProperties:
    """Add up inertials, each placed by a pose (the frame of the link it belongs to).

    The centre of mass is the mass-weighted mean of the parts'; the inertia is the sum of
    each part's, turned into the common frame and moved to the common centre of mass
    (parallel axis theorem). With zero total mass the centre is the origin.
    """
    placed: list[tuple[float, Vector3, Matrix3]] = []
    for inertial, pose in parts:
        frame = pose.then(Pose.of(inertial.origin))
        tensor = rotate_tensor(frame.rotation, inertial.inertia.matrix())
        placed.append((inertial.mass, frame.translation, tensor))
    mass = exact_sum([m for m, _, _ in placed])
    com = ZERO3
    if mass != 0.0:
        com = tuple(exact_sum([m * c[k] for m, c, _ in placed]) / mass for k in range(3))  # type: ignore[assignment]
    total: Matrix3 = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    for m, c, tensor in placed:
        total = mat_add(total, mat_add(tensor, point_mass_tensor(m, add(c, scale(com, -1.0)))))
    return MassProperties(mass, com, _inertia(total))


def volume(
    geometry: Geometry,
    resolve: Callable[[Mesh], Path] | None = None,
    *,
    meshes: MeshContents | None = None,
) -> float:
    """The volume of a URDF shape (m^3).

    A box, cylinder or sphere, or a closed mesh when the optional trimesh package is
    installed (found and read as `geometry_inertia` finds and reads it).

    Raises:
        ShapeError: The mesh is not closed.
        PackageNotFoundError: The mesh's package is not found.
        MeshNotFoundError: The mesh's file is not found.
        ToolNotFoundError: The geometry is a mesh and trimesh is not installed.
    """
    if isinstance(geometry, Box):
        x, y, z = geometry.size
        return x * y * z
    if isinstance(geometry, Cylinder):
        return math.pi * geometry.radius * geometry.radius * geometry.length  # inf, not an error
    if isinstance(geometry, Sphere):
        return 4.0 / 3.0 * math.pi * geometry.radius * geometry.radius * geometry.radius
    if isinstance(geometry, Mesh):
        where = resolve(geometry) if resolve is not None else _mesh_file(geometry)
        return _contents(meshes).solid(where, geometry.scale).volume
    raise ArgumentError(
        f"no closed form for {type(geometry).__name__} (box, cylinder, sphere, mesh)",
        name="geometry",
    )


LARGEST_PART = 5.0
"""Metres: a mesh larger than this is no robot part (a file in millimetres, read as metres)."""


def plausible_mesh(
    geometry: Mesh,
    resolve: Callable[[Mesh], Path] | None = None,
    *,
    meshes: MeshContents | None = None,
) -> None:
    """Refuse a mesh too large to be a robot part: its inertia would be written in tonnes
    (found and read as `geometry_inertia` finds and reads it).

    Raises:
        ShapeError: The mesh is more than `LARGEST_PART` across (or not closed, or unread).
    """
    where = resolve(geometry) if resolve is not None else _mesh_file(geometry)
    extent = _contents(meshes).solid(where, geometry.scale).extent
    if extent > LARGEST_PART:
        raise ShapeError(
            f"the mesh {where} is {extent:.4g} m across, too large for a robot part: "
            'in millimetres? add scale="0.001 0.001 0.001" to its <mesh>',
            path=str(where),
        )


def mesh_inertia(
    path: str | Path,
    mass: float,
    origin: Origin = _AT_LINK,
    scale: Vector3 | None = None,
    *,
    meshes: MeshContents | None = None,
) -> Inertial:
    """The inertia of a closed mesh file filled uniformly with ``mass`` (kg).

    About its centre of mass, placed by ``origin`` (that of its collision). Needs trimesh
    (``pip install 'fishbot-urdf[mesh]'``). The file is read by ``meshes`` (a robot's
    analysis's ``meshes``, which read each file once), or else read for this call.

    Raises:
        ShapeError: The mesh is not closed, or cannot be read as a mesh.
        InertiaUnderflowError: The mesh is so small that its volume or a moment comes out
            0 or subnormal.
        InputError: The file cannot be read.
        ToolNotFoundError: trimesh is not installed.
    """
    solid = _contents(meshes).solid(Path(path), scale)
    density = mass / solid.volume if solid.volume else math.inf
    frame = Pose.of(origin)
    unit = tuple(tuple(density * v + 0.0 for v in row) for row in solid.inertia)
    tensor = rotate_tensor(frame.rotation, unit)  # type: ignore[arg-type]
    diagonal = (tensor[0][0], tensor[1][1], tensor[2][2])
    if mass > 0 and (abs(solid.volume) < _SMALLEST or min(map(abs, diagonal)) < _SMALLEST):
        raise InertiaUnderflowError(
            "mesh", (("across", solid.extent),), mass, diagonal, path=str(path)
        )
    centre = frame.apply(solid.centre)
    return Inertial(mass=mass, inertia=_inertia(tensor), origin=Origin(xyz=centre))


def _contents(meshes: MeshContents | None) -> MeshContents:
    """``meshes``, or contents of their own for a mesh read outside a robot's analysis."""
    return meshes if meshes is not None else MeshContents()
