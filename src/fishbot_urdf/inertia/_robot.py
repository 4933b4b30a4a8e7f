"""A robot's mass properties, and inertials computed for the links that lack one."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

from ..analysis import Analysis, of
from ..analysis.meshcontents import MeshContents
from ..catalog.setup import FILL_SKIPPED, FillFacts
from ..diagnostics import Diagnostic, Kind, Subject
from ..errors import ArgumentError, FishbotUrdfError, ShapeError, UnknownNameError
from ..graph import root
from ..kinematics import link_poses
from ..model import Inertial, Link, Mesh, Origin, Robot
from ..spatial import Pose
from ._solids import MassProperties, combine, exact_sum, geometry_inertia, plausible_mesh, volume

__all__ = ["Filling", "fill_inertials", "link_inertial", "mass_properties"]


def mass_properties(
    robot: Robot | Analysis, positions: Mapping[str, float] | None = None
) -> MassProperties:
    """Total mass, centre of mass and inertia about it of a whole robot, in its root frame.

    Args:
        robot: A robot with one root link, or its analysis.
        positions: Joint positions by name (rad or m); the rest are zero.

    Raises:
        StructureError: The robot has no root or several.
        UnknownNameError: ``positions`` names a joint that does not exist.
        ArgumentError: ``positions`` names a joint that does not move.
    """
    analysis = of(robot)
    root(analysis)  # raises StructureError unless there is one root
    poses = analysis.zero_poses if not positions else link_poses(analysis, positions)
    return combine(
        (link.inertial, poses[link.name])
        for link in analysis.robot.links
        if link.inertial is not None and link.name in poses
    )


def _positive(value: float | None, what: str) -> None:
    if value is not None and not (math.isfinite(value) and value > 0):
        raise ArgumentError(f"the {what} must be a finite number > 0, not {value:g}", name=what)


def link_inertial(
    link: Link,
    *,
    density: float | None = None,
    mass: float | None = None,
    resolve: Callable[[Mesh], Path] | None = None,
    meshes: MeshContents | None = None,
) -> Inertial:
    """The inertial of a link filled uniformly, from its collision shapes.

    Give the ``density`` (kg/m^3) or the link's total ``mass`` (kg, shared among its shapes
    by volume). One box, cylinder or sphere gives the closed form about the shape's own
    origin (the numbers common_inertia.xacro gives); several shapes are added up about
    their joint centre of mass. Closed meshes count when trimesh is installed; ``resolve``
    turns one into its file (by default, as `geometry_inertia` does; for a link of a robot,
    give its analysis's ``mesh_paths.file``) and ``meshes`` reads it (for a link of a
    robot, give its analysis's ``meshes``; by default, each file is read once for the link).

    Raises:
        ArgumentError: Neither or both of density and mass are given, or one is not a
            finite number > 0.
        ShapeError: The link has no collision shape, or its shapes have no volume (an open
            mesh), or a mesh is too large to be a robot part (in millimetres, read as
            metres).
        PackageNotFoundError: A mesh's package is not found.
        MeshNotFoundError: A mesh's file is not found.
        ToolNotFoundError: A mesh needs trimesh, which is not installed.
    """
    if density is None and mass is None:
        raise ArgumentError("give the density or the mass", name="density")
    if density is not None and mass is not None:
        raise ArgumentError("give the density or the mass, not both", name="density")
    _positive(density, "density")
    _positive(mass, "mass")
    meshes = meshes if meshes is not None else MeshContents()
    for collision in link.collisions:
        if isinstance(collision.geometry, Mesh):
            plausible_mesh(collision.geometry, resolve, meshes=meshes)
    shapes = [(c, volume(c.geometry, resolve, meshes=meshes)) for c in link.collisions]
    if not shapes:
        raise ShapeError(f"link {link.name!r} has no collision shape")
    total = exact_sum([v for _, v in shapes])
    if not total > 0.0 or not math.isfinite(total):
        raise ShapeError(f"link {link.name!r}: its collision shapes have no finite volume")
    if density is not None:
        masses = [density * v for _, v in shapes]
    else:
        assert mass is not None
        masses = [mass * v / total for _, v in shapes]
    parts = [
        geometry_inertia(collision.geometry, part, collision.origin, resolve, meshes=meshes)
        for (collision, _), part in zip(shapes, masses, strict=True)
    ]
    if len(parts) == 1:
        return _finite(link, parts[0])
    together = combine((made, Pose()) for made in parts)
    # The mass asked for, exactly (the sum of the shares may differ in the last digit).
    whole = mass if mass is not None else together.mass
    return _finite(
        link, Inertial(mass=whole, inertia=together.inertia, origin=Origin(xyz=together.com))
    )


def _finite(link: Link, inertial: Inertial) -> Inertial:
    """``inertial``, if every number of it can be written; a number beyond the largest
    float (a huge shape, a dense one) is refused rather than written as inf or nan."""
    i = inertial.inertia
    numbers = (inertial.mass, i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz, *inertial.origin.xyz)
    if not all(math.isfinite(n) for n in numbers):
        raise ShapeError(
            f"link {link.name!r}: its collision shapes are too large for a finite mass and "
            f"inertia (mass {inertial.mass:g} kg)"
        )
    return inertial


@dataclass(frozen=True, slots=True)
class Filling:
    """Inertials computed for the links that have collision shapes and no <inertial>.

    Attributes:
        inertials: Link name -> its new inertial, in file order.
        skipped: One ``fill-skipped`` finding per link that could not be filled (no mass
            or density for it, an open mesh, a package not found, trimesh missing). Its
            data's ``reason`` is ``no-mass``, ``shape``, or the error's rule id.
    """

    inertials: Mapping[str, Inertial]
    skipped: tuple[Diagnostic, ...]


def fill_inertials(
    robot: Robot | Analysis,
    *,
    density: float | None = None,
    masses: Mapping[str, float] | None = None,
    resolve: Callable[[Mesh], Path] | None = None,
) -> Filling:
    """Compute an inertial for every link that has collision shapes and no <inertial>.

    Args:
        robot: The robot, or its analysis.
        density: The density of every filled link (kg/m^3).
        masses: The mass of some links (kg), by name; a link given here ignores
            ``density``.
        resolve: Finds a mesh's file (default: the analysis's ``mesh_paths``, as every
            command finds it); the analysis's ``meshes`` read it.

    Raises:
        ArgumentError: Neither density nor masses are given; a mass or the density is not
            a finite number > 0; a link of ``masses`` already has an inertial or has no
            collision shape.
        UnknownNameError: ``masses`` names a link the robot does not have.
    """
    analysis = of(robot)
    resolve = resolve or analysis.mesh_paths.file
    wanted = dict(masses or {})
    if density is None and not wanted:
        raise ArgumentError("give a density or the mass of some links", name="density")
    _positive(density, "density")
    for name, mass in wanted.items():
        link = analysis.links.get(name)
        if link is None:
            raise UnknownNameError("link", name, analysis.links)
        _positive(mass, "mass")
        if link.inertial is not None:
            raise ArgumentError(f"link {name!r} already has an <inertial>", name=name)
        if not link.collisions:
            raise ArgumentError(
                f"link {name!r} has no <collision> shape to compute an inertia from", name=name
            )
    computed: dict[str, Inertial] = {}
    skipped: list[Diagnostic] = []
    for link in analysis.robot.links:
        if not link.collisions or link.inertial is not None:
            continue
        given = wanted.get(link.name)
        if given is None and density is None:
            skipped.append(_skip(link, analysis.path, "no mass was given for it", "no-mass"))
            continue
        try:
            computed[link.name] = link_inertial(
                link,
                mass=given,
                density=None if given is not None else density,
                resolve=resolve,
                meshes=analysis.meshes,
            )
        except FishbotUrdfError as exc:  # an open mesh, a package not found, no trimesh
            hint = getattr(exc, "hint", None)
            why = exc.message + (f"; {hint}" if hint else "")
            skipped.append(_skip(link, analysis.path, why, exc.rule))
    return Filling(computed, tuple(skipped))


def _skip(link: Link, path: str, why: str, reason: str) -> Diagnostic:
    owner = Subject(Kind.LINK, link.name)
    return FILL_SKIPPED.report(
        f"{owner}: no <inertial> added ({why})",
        link.source,
        path=path,
        subject=owner,
        data=FillFacts(reason=reason),
    )
