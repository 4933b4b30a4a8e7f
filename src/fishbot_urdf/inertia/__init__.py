"""Inertia: the closed forms of uniform solids (the fishbot's common_inertia.xacro), closed
meshes, a robot's mass properties and mass table, and inertials filled in from collision
shapes."""

from __future__ import annotations

from ._robot import Filling, fill_inertials, link_inertial, mass_properties
from ._solids import (
    MassProperties,
    box_inertia,
    combine,
    cylinder_inertia,
    geometry_inertia,
    mesh_inertia,
    principal_moments,
    sphere_inertia,
    volume,
)
from ._table import LinkMass, MassTable, inertial_dict, mass_table

__all__ = [
    "Filling",
    "LinkMass",
    "MassProperties",
    "MassTable",
    "box_inertia",
    "combine",
    "cylinder_inertia",
    "fill_inertials",
    "geometry_inertia",
    "inertial_dict",
    "link_inertial",
    "mass_properties",
    "mass_table",
    "mesh_inertia",
    "principal_moments",
    "sphere_inertia",
    "volume",
]
