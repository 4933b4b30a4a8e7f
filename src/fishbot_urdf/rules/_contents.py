"""What a mesh file's contents say against the robot: a collision mesh too flat to hull, a
mesh in millimetres (its facts are read once, by the analysis's ``meshes``)."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ..meshfile import MeshFacts
from ..model import Box, Cylinder, Link, Sphere

__all__ = ["flat_mesh", "hull_refused", "millimetres"]

_LARGEST_PART = 5.0  # metres: a robot part larger than this is implausible
_FLAT = 1e-5  # a mesh thinner than this share of its size is flat (its numbers' rounding)


def flat_mesh(facts: MeshFacts) -> str | None:
    """Why a collision mesh has no volume to make a convex hull of, or None if it has one."""
    found = _flatness(facts)
    return None if found is None else found[0]


def hull_refused(facts: MeshFacts) -> str | None:
    """Why MuJoCo cannot make a convex hull of a mesh, which it makes of every mesh that
    collides, and refuses the model for it (see `flat_mesh`), or None."""
    found = _flatness(facts)
    return None if found is None else found[1]


def _flatness(facts: MeshFacts) -> tuple[str, str | None] | None:
    """Why a mesh has no volume to make a convex hull of, and, when MuJoCo refuses it, why
    in few words."""
    if facts.spread is None:
        return None
    plane, line = facts.spread
    size = facts.extent()
    corners = max(abs(v) for v in (*facts.low, *facts.high))
    # float32 (STL) rounds a vertex by about 6e-8 of its coordinates
    rounding = max(_FLAT * size, 1e-6 * corners)
    if line is None or plane > rounding:
        return None  # (line: measured only for a mesh near flat)
    if facts.vertices is not None and facts.vertices < 4:
        return (
            f"has {facts.vertices} distinct vertices, no volume to collide with: MuJoCo "
            "refuses the robot ('at least 4 vertices required')",
            f"has {facts.vertices} distinct vertices, too few for a convex hull",
        )
    if line <= rounding:
        shape, said = "on one line", "collinear"
    else:
        shape, said = "in one plane", "coplanar"
    # MuJoCo's own test allows 1e-15 of the mesh's size: what our sums leave is as small
    if plane <= 1e-12 * max(size, corners) or line <= rounding:
        return (
            f"has every vertex {shape}, no volume to collide with: MuJoCo refuses the robot "
            f"('{said} vertices, cannot compute convex hull')",
            f"has every vertex {shape}, no volume for a convex hull",
        )
    return (
        f"has every vertex {shape} but for {plane:.2g} (the file's rounding), no volume to "
        "collide with: MuJoCo makes a convex hull of it only as thick as that",
        None,
    )


def millimetres(link: Link, extent: float) -> str | None:
    """Why a mesh ``extent`` metres across reads as millimetres, or None if it does not.

    Plain sense: no robot part is more than 5 m across, unless the link's other shapes or
    its inertia say it is that large too. Against them: a mesh 200 to 5000 times larger
    than what they say.
    """
    shrunk = extent / 1000.0
    sizes = list(_sizes(link))
    if any(size >= extent / 20 for size, _ in sizes):
        return None  # the rest of the link is as large: a big part, in metres
    if extent > _LARGEST_PART and shrunk >= 0.001:
        return (
            f"is {extent:.4g} m across, more than any robot part; in millimetres it would be "
            f"{shrunk:.4g} m"
        )
    for size, what in sizes:
        if extent > 0.3 and 200 <= extent / size <= 5000:
            return (
                f"is {extent:.4g} m across, but {what} says the link is about {size:.3g} m; "
                f"in millimetres it would be {shrunk:.4g} m"
            )
    return None


def _sizes(link: Link) -> Iterator[tuple[float, str]]:
    """How large the link's other evidence says it is (m): its shapes, its inertia."""
    shapes = [part.geometry for part in link.visuals]
    shapes += [part.geometry for part in link.collisions]
    for shape in shapes:
        if isinstance(shape, Box):
            size, what = max(shape.size), "its box"
        elif isinstance(shape, Cylinder):
            size, what = max(2 * shape.radius, shape.length), "its cylinder"
        elif isinstance(shape, Sphere):
            size, what = 2 * shape.radius, "its sphere"
        else:
            continue
        if size > 0:
            yield size, what
    inertial = link.inertial
    if inertial is not None and inertial.mass > 0:
        i = inertial.inertia
        largest = max(i.ixx, i.iyy, i.izz)
        if largest > 0:
            # A rod of length L has I = m L^2 / 12: the longest the inertia allows.
            yield math.sqrt(12.0 * largest / inertial.mass), "its inertia"
