"""A quick first pass for fault-free files: the same Robot as the full reader, built faster.

The full reader explains every fault it meets, and pays for that on every element. Most files
have no fault, so ``read`` first tries this pass, which accepts only fault-free input and
gives up (returns None) at the first thing that would need a finding or that it does not
handle; the full reader then reads the file from the start. Its result, locations included,
is tested to equal the full reader's.
"""

from __future__ import annotations

from lxml import etree

from ..model import (
    DEFAULT_AXIS,
    ZERO3,
    Box,
    Calibration,
    Collision,
    Cylinder,
    Dynamics,
    Geometry,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Location,
    Material,
    Mesh,
    Mimic,
    Origin,
    Robot,
    SafetyController,
    Sphere,
    Vector3,
    Visual,
    builder,
)
from ..xmlsource import Locator
from ._base import xml_text

_TYPES = {t.value: t for t in JointType}
_NO_ORIGIN = Origin()
_ONES = (1.0, 1.0, 1.0)

_origin = builder(Origin)
_box = builder(Box)
_cylinder = builder(Cylinder)
_sphere = builder(Sphere)
_mesh = builder(Mesh)
_material = builder(Material)
_inertia = builder(Inertia)
_inertial = builder(Inertial)
_visual = builder(Visual)
_collision = builder(Collision)
_link = builder(Link)
_limit = builder(Limit)
_joint = builder(Joint)


class _GiveUp(Exception):
    """Raised where the full reader would make a finding, or meets a case this pass skips."""


def fast_robot(root: etree._Element, locator: Locator, data: bytes) -> Robot | None:
    """The robot in ``root`` if the file is free of faults, else None (read it fully then)."""
    if locator.raw_whitespace or b"&#" in data or root.tag != "robot":
        # With no character references and no raw tabs or line breaks, no attribute value
        # holds white space other than spaces: the number rules below rely on it.
        return None
    count = root.xpath("count(//*)")
    if not isinstance(count, float) or locator.element_count != count:
        return None  # a processing instruction holds a "<tag": let the full reader resync
    try:
        return _Pass(locator).robot(root)
    except (_GiveUp, ValueError, TypeError):  # float() of a malformed or missing value
        return None


def _numbers(*texts: str | None) -> list[float]:
    """Numbers by values.to_double's rules, all checked at once; give up on any other."""
    values = list(map(float, texts))  # type: ignore[arg-type]  # None: TypeError, caught
    total = sum(values)  # not finite if any value is inf or nan
    joined = "".join(texts)  # type: ignore[arg-type]
    # A space would be leading (allowed) or trailing (refused): give up on both.
    if total - total or " " in joined or "_" in joined or not joined.isascii():
        raise _GiveUp
    return values


def _vector(text: str | None, count: int) -> list[float]:
    if text is None:
        raise _GiveUp
    pieces = text.split(" ")
    if len(pieces) != count:
        pieces = [p for p in pieces if p]  # urdfdom drops empty pieces
    if len(pieces) != count:
        raise _GiveUp
    return _numbers(*pieces)


def _vector3(text: str | None, default: Vector3) -> Vector3:
    if text is None:
        return default
    x, y, z = _vector(text, 3)
    return (x, y, z)


def _required(el: etree._Element, name: str) -> str:
    value = el.get(name)
    if not value:
        raise _GiveUp
    return value


def _optional(el: etree._Element, name: str, default: float = 0.0) -> float:
    value = el.get(name)
    return default if value is None else _numbers(value)[0]


class _Pass:
    """One walk over the elements in document order, taking each one's location in turn."""

    __slots__ = ("at",)

    def __init__(self, locator: Locator) -> None:
        self.at = iter(locator.locations()).__next__

    def skip_inside(self, el: etree._Element) -> None:
        for _ in el.iterdescendants(etree.Element):
            self.at()

    def leaf(self, el: etree._Element) -> Location:
        # The full reader re-finds its place by tag name after an element holding elements it
        # does not read; this pass counts elements, so it leaves those cases to it.
        if len(el):
            raise _GiveUp
        return self.at()

    def robot(self, el: etree._Element) -> Robot:
        at = self.at()
        name = _required(el, "name")
        version = el.get("version")
        if version is not None and version != "1.0":
            raise _GiveUp
        links: list[Link] = []
        joints: list[Joint] = []
        materials: list[Material] = []
        extras: list[str] = []
        for child in el:
            tag = child.tag
            if tag == "link":
                links.append(self.link(child))
            elif tag == "joint":
                joints.append(self.joint(child))
            elif tag == "material":
                materials.append(self.material(child))
            elif isinstance(tag, str):
                extras.append(self.extra(child))
        return Robot(
            name, tuple(links), tuple(joints), tuple(materials), version, tuple(extras), at
        )

    def extra(self, el: etree._Element) -> str:
        self.at()
        self.skip_inside(el)
        return xml_text(el)

    def origin(self, el: etree._Element) -> Origin:
        at = self.leaf(el)
        return _origin(_vector3(el.get("xyz"), ZERO3), _vector3(el.get("rpy"), ZERO3), at)

    # -- links ------------------------------------------------------------------------------
    def link(self, el: etree._Element) -> Link:
        at = self.at()
        name = _required(el, "name")
        inertial: Inertial | None = None
        visuals: list[Visual] = []
        collisions: list[Collision] = []
        extras: list[str] = []
        for child in el:
            tag = child.tag
            if tag == "visual":
                visuals.append(self.visual(child))
            elif tag == "collision":
                collisions.append(self.collision(child))
            elif tag == "inertial" and inertial is None:
                inertial = self.inertial(child)
            elif tag == "inertial":
                raise _GiveUp
            elif isinstance(tag, str):
                extras.append(self.extra(child))
        return _link(name, inertial, tuple(visuals), tuple(collisions), tuple(extras), at)

    def inertial(self, el: etree._Element) -> Inertial:
        at = self.at()
        origin = _NO_ORIGIN
        mass: float | None = None
        inertia: Inertia | None = None
        for child in el:
            tag = child.tag
            if tag == "origin":
                origin = self.origin(child)
            elif tag == "mass":
                self.leaf(child)
                (mass,) = _numbers(child.get("value"))
            elif tag == "inertia":
                c_at = self.leaf(child)
                get = child.get
                ixx, ixy, ixz, iyy, iyz, izz = _numbers(
                    get("ixx"), get("ixy"), get("ixz"), get("iyy"), get("iyz"), get("izz")
                )
                inertia = _inertia(ixx, ixy, ixz, iyy, iyz, izz, c_at)
            elif isinstance(tag, str):
                raise _GiveUp
        if mass is None or inertia is None:
            raise _GiveUp
        return _inertial(mass, inertia, origin, at)

    def visual(self, el: etree._Element) -> Visual:
        at = self.at()
        geometry, origin, material = self.shape_parts(el, with_material=True)
        return _visual(geometry, origin, material, el.get("name"), at)

    def collision(self, el: etree._Element) -> Collision:
        at = self.at()
        geometry, origin, _ = self.shape_parts(el, with_material=False)
        return _collision(geometry, origin, el.get("name"), at)

    def shape_parts(
        self, el: etree._Element, *, with_material: bool
    ) -> tuple[Geometry, Origin, Material | None]:
        """The geometry, origin and (in a visual) material of a visual or collision."""
        origin = _NO_ORIGIN
        geometry: Geometry | None = None
        material: Material | None = None
        for child in el:
            tag = child.tag
            if tag == "geometry" and geometry is None:
                geometry = self.geometry(child)
            elif tag == "origin":
                origin = self.origin(child)
            elif tag == "material" and with_material:
                material = self.material(child)
            elif isinstance(tag, str):
                raise _GiveUp  # a second geometry, a material in a collision, an unknown tag
        if geometry is None:
            raise _GiveUp
        return geometry, origin, material

    def geometry(self, el: etree._Element) -> Geometry:
        self.at()
        shape = el[0] if len(el) == 1 else None
        if shape is None or not isinstance(shape.tag, str):
            shapes = [child for child in el if isinstance(child.tag, str)]
            if len(shapes) != 1:
                raise _GiveUp
            shape = shapes[0]
        at = self.at()
        self.skip_inside(shape)  # as the full reader does
        tag = shape.tag
        if tag == "box":
            return _box(_vector3(_given(shape.get("size")), ZERO3), at)
        if tag == "cylinder":
            radius, length = _numbers(shape.get("radius"), shape.get("length"))
            return _cylinder(radius, length, at)
        if tag == "sphere":
            return _sphere(_numbers(shape.get("radius"))[0], at)
        if tag == "mesh":
            scale = shape.get("scale")
            return _mesh(
                _required(shape, "filename"), None if scale is None else _vector3(scale, _ONES), at
            )
        raise _GiveUp

    def material(self, el: etree._Element) -> Material:
        at = self.at()
        name = el.get("name")
        if name is None:
            raise _GiveUp
        color = texture = None
        for child in el:
            tag = child.tag
            if tag == "color":
                self.leaf(child)
                r, g, b, a = _vector(child.get("rgba"), 4)
                if not (
                    0.0 <= r <= 1.0 and 0.0 <= g <= 1.0 and 0.0 <= b <= 1.0 and 0.0 <= a <= 1.0
                ):
                    raise _GiveUp
                color = (r, g, b, a)
            elif tag == "texture":
                self.at()
                self.skip_inside(child)
                texture = child.get("filename") or None
            elif isinstance(tag, str):
                raise _GiveUp
        return _material(name, color, texture, at)

    # -- joints -----------------------------------------------------------------------------
    def joint(self, el: etree._Element) -> Joint:
        at = self.at()
        name = _required(el, "name")
        joint_type = _TYPES.get(el.get("type") or "")
        if joint_type is None:
            raise _GiveUp
        parent = child_name = None
        parent_at = child_at = None
        origin = _NO_ORIGIN
        axis = DEFAULT_AXIS
        limit = dynamics = calibration = mimic = safety = None
        seen: set[str] = set()
        extras: list[str] = []
        for child in el:
            tag = child.tag
            if not isinstance(tag, str):
                continue
            if tag not in _JOINT_PARTS:
                extras.append(self.extra(child))
                continue
            if tag in seen:
                raise _GiveUp
            seen.add(tag)
            if tag == "origin":
                origin = self.origin(child)
                continue
            c_at = self.leaf(child)
            if tag == "parent":
                parent, parent_at = _required(child, "link"), c_at
            elif tag == "child":
                child_name, child_at = _required(child, "link"), c_at
            elif tag == "axis":
                axis = _vector3(_given(child.get("xyz")), DEFAULT_AXIS)
            elif tag == "limit":
                effort, velocity = _numbers(child.get("effort"), child.get("velocity"))
                lower, upper = _optional(child, "lower"), _optional(child, "upper")
                limit = _limit(effort, velocity, lower, upper, c_at)
            elif tag == "dynamics":
                dynamics = Dynamics(_optional(child, "damping"), _optional(child, "friction"), c_at)
            elif tag == "calibration":
                calibration = Calibration(
                    _maybe(child.get("rising")), _maybe(child.get("falling")), c_at
                )
            elif tag == "mimic":
                mimic = Mimic(
                    _required(child, "joint"),
                    _optional(child, "multiplier", 1.0),
                    _optional(child, "offset"),
                    c_at,
                )
            else:
                safety = SafetyController(
                    _numbers(child.get("k_velocity"))[0],
                    _optional(child, "k_position"),
                    _optional(child, "soft_lower_limit"),
                    _optional(child, "soft_upper_limit"),
                    c_at,
                )
        if parent is None or child_name is None:
            raise _GiveUp
        return _joint(
            name,
            joint_type,
            parent,
            child_name,
            origin,
            axis,
            limit,
            dynamics,
            calibration,
            mimic,
            safety,
            tuple(extras),
            at,
            parent_at,
            child_at,
        )


def _given(text: str | None) -> str:
    # A required vector: the full reader reports a missing one.
    if text is None:
        raise _GiveUp
    return text


def _maybe(text: str | None) -> float | None:
    return None if text is None else _numbers(text)[0]


_JOINT_PARTS = frozenset(
    (
        "parent",
        "child",
        "origin",
        "axis",
        "limit",
        "dynamics",
        "calibration",
        "mimic",
        "safety_controller",
    )
)
