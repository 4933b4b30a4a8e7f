"""Inertia of uniform solids: the closed forms of the fishbot's common_inertia.xacro.

Every function returns an ``Inertial`` whose numbers are the very floats the xacro macros
produce (the same operations in the same order), about the solid's centre, in its own
frame: pass the ``origin`` of the visual or collision it belongs to.
"""

from __future__ import annotations

from .model import Box, Cylinder, Geometry, Inertia, Inertial, Origin, Sphere

__all__ = ["box_inertia", "cylinder_inertia", "geometry_inertia", "sphere_inertia"]

_AT_LINK = Origin()


def box_inertia(m: float, w: float, h: float, d: float, origin: Origin = _AT_LINK) -> Inertial:
    """A solid box of mass ``m`` (kg) with sides ``w`` along x, ``h`` along y and ``d``
    along z (m), as ``<box size="w h d"/>``: ixx = m/12 (h^2 + d^2), iyy = m/12 (w^2 + d^2),
    izz = m/12 (w^2 + h^2) (kg*m^2)."""
    return Inertial(
        mass=m,
        inertia=Inertia(
            ixx=m / 12.0 * (h * h + d * d),
            iyy=m / 12.0 * (w * w + d * d),
            izz=m / 12.0 * (w * w + h * h),
        ),
        origin=origin,
    )


def cylinder_inertia(m: float, r: float, h: float, origin: Origin = _AT_LINK) -> Inertial:
    """A solid cylinder of mass ``m`` (kg), radius ``r`` and height ``h`` (m) along its z
    axis, as ``<cylinder radius="r" length="h"/>``: ixx = iyy = m/12 (3 r^2 + h^2),
    izz = m/2 r^2 (kg*m^2)."""
    across = m / 12.0 * (3 * r * r + h * h)
    return Inertial(
        mass=m, inertia=Inertia(ixx=across, iyy=across, izz=m / 2.0 * r * r), origin=origin
    )


def sphere_inertia(m: float, r: float, origin: Origin = _AT_LINK) -> Inertial:
    """A solid sphere of mass ``m`` (kg) and radius ``r`` (m): 2/5 m r^2 about every axis."""
    moment = 2.0 / 5.0 * m * r * r
    return Inertial(mass=m, inertia=Inertia(ixx=moment, iyy=moment, izz=moment), origin=origin)


def geometry_inertia(geometry: Geometry, mass: float, origin: Origin = _AT_LINK) -> Inertial:
    """The inertia of a URDF box, cylinder or sphere filled uniformly with ``mass`` (kg).

    Raises:
        TypeError: The geometry is a mesh (or anything but a box, cylinder or sphere).
    """
    if isinstance(geometry, Box):
        x, y, z = geometry.size
        return box_inertia(mass, x, y, z, origin)
    if isinstance(geometry, Cylinder):
        return cylinder_inertia(mass, geometry.radius, geometry.length, origin)
    if isinstance(geometry, Sphere):
        return sphere_inertia(mass, geometry.radius, origin)
    raise TypeError(f"no closed form for {type(geometry).__name__} (box, cylinder, sphere)")
