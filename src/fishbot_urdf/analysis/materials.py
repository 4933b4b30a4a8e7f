"""The material of each visual, as urdfdom resolves a name against those defined before it."""

from __future__ import annotations

from collections.abc import Mapping

from ..model import Material, Robot

__all__ = ["visual_materials"]


def visual_materials(robot: Robot) -> Mapping[int, Material | None]:
    """Each named visual material as urdfdom resolves it, by the visual's ``id``: a material
    of the same name defined at the top level, or by a visual before it, comes first; one
    with a name alone that none defined so far is none. A visual without a named material
    has no entry (its own material, if any, is its material)."""
    known: dict[str, Material] = {}
    for material in robot.materials:
        known.setdefault(material.name, material)
    found: dict[int, Material | None] = {}
    for link in robot.links:
        for visual in link.visuals:
            given = visual.material
            if given is None or not given.name:
                continue
            if given.color is None and given.texture is None:
                found[id(visual)] = known.get(given.name)
            else:
                found[id(visual)] = known.setdefault(given.name, given)
    return found
