"""Readers for <link> and what it holds, and for <material>."""

from __future__ import annotations

from lxml import etree

from ..catalog.reading import (
    BAD_COLOR,
    COLLISION_MATERIAL,
    DUPLICATE_ELEMENT,
    MISSING_ELEMENT,
    UNKNOWN_GEOMETRY,
)
from ..diagnostics import Kind, Subject
from ..model import (
    ZERO3,
    Box,
    Collision,
    Cylinder,
    Geometry,
    Inertia,
    Inertial,
    Link,
    Location,
    Material,
    Mesh,
    Origin,
    Sphere,
    Visual,
)
from ._base import Owner, ReaderBase, xml_text
from .values import plain_numbers

_SHAPES = "<box>, <cylinder>, <sphere> or <mesh>"
_NO_ORIGIN = Origin()  # frozen: one for every element that has no <origin>


class LinkReader(ReaderBase):
    """Builds Link, Inertial, Visual, Collision, Geometry, Origin and Material."""

    def origin(self, el: etree._Element, at: Location, owner: Owner) -> Origin:
        return Origin(self.vector3(el, at, "xyz", owner), self.vector3(el, at, "rpy", owner), at)

    def material(self, el: etree._Element, at: Location, owner: Owner) -> Material:
        name = el.get("name")
        if name is None:
            # urdfdom accepts name="" (an anonymous colour, common in exported robots).
            self.missing(el, at, "name", owner, "...")
        label = Subject(Kind.MATERIAL, name or "")
        if isinstance(owner, Subject) and owner.kind is Kind.ROBOT:  # a material of its own
            self.subject = label
        color = texture = None
        for child in el:
            tag = child.tag
            if tag == "color":
                c_at = self.locator.locate(child)
                rgba = self.numbers(child, c_at, "rgba", label, 4, "red green blue alpha")
                if child.get("rgba") is None:
                    self.missing(child, c_at, "rgba", label, "red green blue alpha")
                elif rgba is not None:
                    color = (rgba[0], rgba[1], rgba[2], rgba[3])
                    if not all(0.0 <= v <= 1.0 for v in color):
                        self.error(
                            BAD_COLOR,
                            f'{label}: <color rgba="{child.get("rgba")}"> has a value outside 0..1',
                            self.locator.attribute(c_at, "rgba"),
                            "each of red, green, blue and alpha is between 0 and 1",
                        )
            elif tag == "texture":
                self.locator.skip(child)
                # An empty <texture/> is common in exported robots; urdfdom ignores it too.
                texture = child.get("filename") or None
            elif isinstance(tag, str):
                self.ignored(child, label, "material", "<material> holds <color> and <texture>")
        return Material(name or "", color, texture, at)

    def link(self, el: etree._Element, at: Location) -> Link:
        name = self.text(el, at, "name", "link") or ""
        owner = self.subject = Subject(Kind.LINK, name)
        inertial: Inertial | None = None
        visuals: list[Visual] = []
        collisions: list[Collision] = []
        extras: list[str] = []
        for child in el:
            tag = child.tag
            if tag == "visual":
                visuals.append(self.visual(child, self.locator.locate(child), owner))
            elif tag == "collision":
                collisions.append(self.collision(child, self.locator.locate(child), owner))
            elif tag == "inertial" and inertial is None:
                inertial = self.inertial(child, self.locator.locate(child), owner)
            elif tag == "inertial":
                self.passed_over(
                    child,
                    DUPLICATE_ELEMENT,
                    f"{owner}: a second <inertial> is ignored",
                    "a link has at most one <inertial>",
                    made=True,
                )
                extras.append(xml_text(child))
            elif isinstance(tag, str):
                extras.append(self.extra(child))
        return Link(name, inertial, tuple(visuals), tuple(collisions), tuple(extras), at)

    def inertial(self, el: etree._Element, at: Location, owner: Owner) -> Inertial:
        found = len(self.diagnostics)
        inertial = self._inertial(el, at, owner)
        self.about(found, "inertial")  # about the mass alone: the shape and frames stand
        return inertial

    def _inertial(self, el: etree._Element, at: Location, owner: Owner) -> Inertial:
        origin = _NO_ORIGIN
        mass = 0.0
        inertia: Inertia | None = None
        has_mass = False
        for child in el:
            tag = child.tag
            if tag == "origin":
                origin = self.origin(child, self.locator.locate(child), owner)
            elif tag == "mass":
                has_mass = True
                mass = self.number(child, self.locator.locate(child), "value", owner, required=True)
            elif tag == "inertia":
                c_at = self.locator.locate(child)
                get = child.get
                plain = plain_numbers(
                    [get("ixx"), get("ixy"), get("ixz"), get("iyy"), get("iyz"), get("izz")]
                )
                if plain is not None:
                    ixx, ixy, ixz, iyy, iyz, izz = plain
                    inertia = Inertia(ixx, ixy, ixz, iyy, iyz, izz, c_at)
                    continue
                number = self.number
                inertia = Inertia(
                    number(child, c_at, "ixx", owner, required=True),
                    number(child, c_at, "ixy", owner, required=True),
                    number(child, c_at, "ixz", owner, required=True),
                    number(child, c_at, "iyy", owner, required=True),
                    number(child, c_at, "iyz", owner, required=True),
                    number(child, c_at, "izz", owner, required=True),
                    c_at,
                )
            elif isinstance(tag, str):
                self.ignored(
                    child, owner, "inertial", "<inertial> holds <origin>, <mass> and <inertia>"
                )
        if not has_mass:
            self.error(
                MISSING_ELEMENT,
                f"{owner}: <inertial> has no <mass>",
                at,
                'write <mass value="KG"/>',
            )
        if inertia is None:
            self.error(
                MISSING_ELEMENT,
                f"{owner}: <inertial> has no <inertia>",
                at,
                'write <inertia ixx=".." ixy="0" ixz="0" iyy=".." iyz="0" izz=".."/>',
            )
        return Inertial(mass, inertia or Inertia(), origin, at)

    def _shape_parts(
        self, el: etree._Element, at: Location, owner: Owner, visual: bool
    ) -> tuple[Origin, Geometry, Material | None]:
        origin = _NO_ORIGIN
        geometry: Geometry | None = None
        material: Material | None = None
        seen_geometry = False
        for child in el:
            tag = child.tag
            if tag == "origin":
                origin = self.origin(child, self.locator.locate(child), owner)
            elif tag == "geometry" and not seen_geometry:
                seen_geometry = True
                geometry = self.geometry(child, self.locator.locate(child), owner)
            elif tag == "material" and visual:
                material = self.material(child, self.locator.locate(child), owner)
            elif tag == "material":
                self.passed_over(
                    child,
                    COLLISION_MATERIAL,
                    f"{owner}: <material> inside <collision> is ignored",
                    "colours belong in <visual>; move the <material> there",
                )
            elif tag == "geometry":
                self.passed_over(
                    child,
                    DUPLICATE_ELEMENT,
                    f"{owner}: a second <geometry> in one <{el.tag}> is ignored",
                    f"use another <{el.tag}> for another shape",
                )
            elif isinstance(tag, str):
                allowed = (
                    "<origin>, <geometry> and <material>" if visual else ("<origin> and <geometry>")
                )
                self.ignored(child, owner, el.tag, f"<{el.tag}> holds {allowed}")
        if not seen_geometry:
            self.error(
                MISSING_ELEMENT,
                f"{owner}: <{el.tag}> has no <geometry>",
                at,
                f"write <geometry> with one {_SHAPES}",
            )
        return origin, geometry or Box(ZERO3), material

    def visual(self, el: etree._Element, at: Location, owner: Owner) -> Visual:
        origin, geometry, material = self._shape_parts(el, at, owner, True)
        return Visual(geometry, origin, material, el.get("name"), at)

    def collision(self, el: etree._Element, at: Location, owner: Owner) -> Collision:
        origin, geometry, _ = self._shape_parts(el, at, owner, False)
        return Collision(geometry, origin, el.get("name"), at)

    def geometry(self, el: etree._Element, at: Location, owner: Owner) -> Geometry | None:
        shape: Geometry | None = None
        seen = False
        for child in el:
            tag = child.tag
            if not isinstance(tag, str):
                continue
            c_at = self.locator.locate(child)
            if len(child):  # a shape holds nothing, as a rule
                self.locator.skip_children(child)
            if seen:
                self.error(
                    DUPLICATE_ELEMENT,
                    f"{owner}: <geometry> holds more than one shape; <{tag}> is ignored",
                    c_at,
                    "one <geometry> has exactly one shape; use another <visual> or <collision>",
                )
                continue
            seen = True
            shape = self.shape(child, c_at, owner)
        if not seen:
            self.error(
                MISSING_ELEMENT,
                f"{owner}: <geometry> is empty",
                at,
                f"write one {_SHAPES} inside it",
            )
        return shape

    def shape(self, el: etree._Element, at: Location, owner: Owner) -> Geometry | None:
        tag = el.tag
        if tag == "box":
            return Box(self.vector3(el, at, "size", owner, required=True), at)
        if tag == "cylinder":
            radius = self.number(el, at, "radius", owner, required=True)
            return Cylinder(radius, self.number(el, at, "length", owner, required=True), at)
        if tag == "sphere":
            return Sphere(self.number(el, at, "radius", owner, required=True), at)
        if tag == "mesh":
            filename = self.text(el, at, "filename", owner) or ""
            scale = None
            if el.get("scale") is not None:
                scale = self.vector3(el, at, "scale", owner, (1.0, 1.0, 1.0))
            return Mesh(filename, scale, at)
        self.error(UNKNOWN_GEOMETRY, f"{owner}: <{tag}> is not a URDF shape", at, f"use {_SHAPES}")
        return None
