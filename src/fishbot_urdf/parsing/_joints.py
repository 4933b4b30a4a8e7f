"""Readers for <joint> and what it holds."""

from __future__ import annotations

from collections.abc import Callable

from lxml import etree

from ..catalog.reading import DUPLICATE_ELEMENT, JOINT_TYPE, MISSING_ATTRIBUTE, MISSING_ELEMENT
from ..diagnostics import Kind, Severity, Subject
from ..model import (
    DEFAULT_AXIS,
    ZERO3,
    Calibration,
    Dynamics,
    Joint,
    JointType,
    Limit,
    Location,
    Mimic,
    Origin,
    SafetyController,
)
from ._base import Owner, unexpanded_hint
from ._links import LinkReader
from .values import plain_numbers

_TYPES = {t.value: t for t in JointType}
_NO_ORIGIN = Origin()


class JointReader(LinkReader):
    """Builds Joint and its parts."""

    def joint_type(self, el: etree._Element, at: Location, owner: Owner) -> JointType:
        text = el.get("type")
        found = _TYPES.get(text or "")
        if found is not None:
            return found
        if not text:
            self.error(
                JOINT_TYPE,
                f"{owner}: has no type",
                at,
                'write type="revolute|continuous|prismatic|fixed|floating|planar"',
            )
        else:
            self.error(
                JOINT_TYPE,
                f"{owner}: type {text!r} is not a URDF joint type",
                self.locator.attribute(at, "type"),
                unexpanded_hint(text)
                or "use revolute, continuous, prismatic, fixed, floating or planar",
            )
        return JointType.FIXED  # stands in so that the rest can still be checked

    def joint(self, el: etree._Element, at: Location) -> Joint:
        name = self.text(el, at, "name", "joint") or ""
        owner = self.subject = Subject(Kind.JOINT, name)
        joint_type = self.joint_type(el, at, owner)
        parts: dict[str, object] = {}  # what each child URDF defines gave, by tag
        extras: list[str] = []
        locate = self.locator.locate
        for child in el:
            tag = child.tag
            read = _PARTS.get(tag)  # (a comment's tag is a function: no part)
            if read is not None:
                c_at = locate(child)
                if tag in parts:
                    self.locator.skip_children(child)
                    self.error(
                        DUPLICATE_ELEMENT,
                        f"{owner}: a second <{tag}> is ignored",
                        c_at,
                        f"a joint has at most one <{tag}>",
                    )
                else:
                    made = len(self.diagnostics)
                    parts[tag] = read(self, child, c_at, owner)
                    if tag == "axis":  # urdfdom reads no fixed or floating joint's axis
                        self.about(made, "axis")
            elif isinstance(tag, str):
                extras.append(self.extra(child))
        ends: list[tuple[str, Location | None]] = []
        for end in ("parent", "child"):
            found = parts.get(end)
            if found is None:
                self.error(
                    MISSING_ELEMENT,
                    f"{owner}: has no <{end}>",
                    at,
                    f'write <{end} link="LINK_NAME"/>',
                )
                found = ("", None)
            ends.append(found)  # type: ignore[arg-type]
        (parent, parent_at), (child_name, child_at) = ends
        return Joint(
            name,
            joint_type,
            parent,
            child_name,
            parts.get("origin", _NO_ORIGIN),  # type: ignore[arg-type]
            parts.get("axis", DEFAULT_AXIS),  # type: ignore[arg-type]
            parts.get("limit"),  # type: ignore[arg-type]
            parts.get("dynamics"),  # type: ignore[arg-type]
            parts.get("calibration"),  # type: ignore[arg-type]
            parts.get("mimic"),  # type: ignore[arg-type]
            parts.get("safety_controller"),  # type: ignore[arg-type]
            tuple(extras),
            at,
            parent_at,
            child_at,
        )

    def end(self, el: etree._Element, at: Location, owner: Owner) -> tuple[str, Location]:
        """A <parent> or <child>: the link it names, and where it is."""
        return self.text(el, at, "link", owner) or "", at

    def axis(self, el: etree._Element, at: Location, owner: Owner) -> tuple[float, ...]:
        if el.get("xyz") is None:
            # urdfdom keeps the 1 0 0 default only when there is no <axis> at all; an <axis>
            # without xyz leaves it at 0 0 0 (KDL then computes poses of NaN).
            self.error(
                MISSING_ATTRIBUTE,
                f"{owner}: <axis> has no 'xyz' attribute, so urdfdom reads the axis as 0 0 0",
                at,
                'write <axis xyz="x y z">, or leave <axis> out for the default 1 0 0',
                Severity.WARNING,
            )
            return ZERO3
        return self.vector3(el, at, "xyz", owner, DEFAULT_AXIS)

    def limit(self, el: etree._Element, at: Location, owner: Owner) -> Limit:
        get = el.get
        plain = plain_numbers(
            [get("effort"), get("velocity"), get("lower", "0"), get("upper", "0")]
        )
        unset = tuple(bound for bound in ("lower", "upper") if get(bound) is None)
        if plain is not None:
            effort, velocity, lower, upper = plain
            return Limit(effort, velocity, lower, upper, at, unset)
        return Limit(
            self.number(el, at, "effort", owner, required=True),
            self.number(el, at, "velocity", owner, required=True),
            self.number(el, at, "lower", owner),
            self.number(el, at, "upper", owner),
            at,
            unset,
        )

    def dynamics(self, el: etree._Element, at: Location, owner: Owner) -> Dynamics:
        if el.get("damping") is None and el.get("friction") is None:
            # urdfdom refuses the joint, so the whole file
            self.error(
                MISSING_ATTRIBUTE,
                f"{owner}: <dynamics> has neither 'damping' nor 'friction'",
                at,
                'write <dynamics damping="NUMBER" friction="NUMBER"/>, or leave it out',
            )
        return Dynamics(
            self.number(el, at, "damping", owner), self.number(el, at, "friction", owner), at
        )

    def calibration(self, el: etree._Element, at: Location, owner: Owner) -> Calibration:
        return Calibration(
            self.optional_number(el, at, "rising", owner),
            self.optional_number(el, at, "falling", owner),
            at,
        )

    def mimic(self, el: etree._Element, at: Location, owner: Owner) -> Mimic:
        return Mimic(
            self.text(el, at, "joint", owner) or "",
            self.number(el, at, "multiplier", owner, 1.0),
            self.number(el, at, "offset", owner),
            at,
        )

    def safety_controller(self, el: etree._Element, at: Location, owner: Owner) -> SafetyController:
        return SafetyController(
            k_velocity=self.number(el, at, "k_velocity", owner, required=True),
            k_position=self.number(el, at, "k_position", owner),
            soft_lower_limit=self.number(el, at, "soft_lower_limit", owner),
            soft_upper_limit=self.number(el, at, "soft_upper_limit", owner),
            source=at,
        )


_PARTS: dict[object, Callable[[JointReader, etree._Element, Location, Owner], object]] = {
    "parent": JointReader.end,
    "child": JointReader.end,
    "origin": JointReader.origin,
    "axis": JointReader.axis,
    "limit": JointReader.limit,
    "dynamics": JointReader.dynamics,
    "calibration": JointReader.calibration,
    "mimic": JointReader.mimic,
    "safety_controller": JointReader.safety_controller,
}
