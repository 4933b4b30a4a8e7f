"""Inertia: the closed forms of uniform solids (the fishbot's common_inertia.xacro), closed
meshes, a robot's mass properties and mass table, inertials filled in from collision
shapes, and the mass sphere and inertia box RViz draws for an inertial."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ._marks import (
    LEAD_DENSITY,
    EquivalentBox,
    NoBox,
    equivalent_box,
    mass_sphere_diameter,
    why_no_box,
)
from ._robot import Filling, fill_inertials, link_inertial, mass_properties
from ._solids import (
    MassProperties,
    box_inertia,
    combine,
    cylinder_inertia,
    geometry_inertia,
    mesh_inertia,
    principal_moments,
    solid_moments,
    sphere_inertia,
    volume,
)

if TYPE_CHECKING:
    from ._macros import InertiaMacro, inertia_macros
    from ._shared import SharedInertial, shared_inertials
    from ._suggestions import InertialSuggestion, suggest_inertials, xacro_suggestions
    from ._table import LinkMass, MassTable, inertial_dict, mass_table

__all__ = [
    "LEAD_DENSITY",
    "EquivalentBox",
    "Filling",
    "InertiaMacro",
    "InertialSuggestion",
    "LinkMass",
    "MassProperties",
    "MassTable",
    "NoBox",
    "SharedInertial",
    "box_inertia",
    "combine",
    "cylinder_inertia",
    "equivalent_box",
    "fill_inertials",
    "geometry_inertia",
    "inertia_macros",
    "inertial_dict",
    "link_inertial",
    "mass_properties",
    "mass_sphere_diameter",
    "mass_table",
    "mesh_inertia",
    "principal_moments",
    "shared_inertials",
    "solid_moments",
    "sphere_inertia",
    "suggest_inertials",
    "volume",
    "why_no_box",
    "xacro_suggestions",
]


_MACROS = ("InertiaMacro", "inertia_macros")
_SUGGESTIONS = ("InertialSuggestion", "suggest_inertials", "xacro_suggestions")


def __getattr__(name: str) -> Any:
    # The mass table loads when first used: `check` needs only the formulas.
    if name in ("LinkMass", "MassTable", "inertial_dict", "mass_table"):
        from . import _table  # (~4 ms, and `check` never needs it)

        return getattr(_table, name)
    if name in _MACROS:
        from . import _macros  # (the expansion's probe: only --fill needs it)

        return getattr(_macros, name)
    if name in ("SharedInertial", "shared_inertials"):
        from . import _shared  # (as the suggestions: only --fill needs them)

        return getattr(_shared, name)
    if name in _SUGGESTIONS:
        from . import _suggestions  # (the writer too: only --fill needs them)

        return getattr(_suggestions, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
