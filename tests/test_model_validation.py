"""A robot built in Python is held to what the reader gives: check() reports bad values as the
reader's findings, to_urdf() refuses them, and fields of the wrong type raise FieldTypeError."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import fields, is_dataclass, replace
from itertools import pairwise
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fishbot_urdf
from fishbot_urdf import (
    Box,
    Calibration,
    Collision,
    Cylinder,
    Dynamics,
    FieldTypeError,
    FishbotUrdfError,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Material,
    Mesh,
    Mimic,
    Origin,
    Robot,
    RobotError,
    SafetyController,
    Sphere,
    Visual,
    check,
    parse,
    to_urdf,
)
from fishbot_urdf import validation as values_module
from fishbot_urdf.validation import values

NAN, INF = math.nan, math.inf
INERTIAL = Inertial(1.0, Inertia(0.1, 0.0, 0.0, 0.1, 0.0, 0.1))
WHEEL = Visual(Cylinder(0.1, 0.05), material=Material("blue", (0.0, 0.0, 1.0, 1.0)))


def _robot(
    link: Link | None = None, joint: Joint | None = None, name: Any = "bot", **fields: Any
) -> Robot:
    """A two-link robot that passes check(), with ``link`` as its base and ``joint`` joining
    the two (each replaced when given)."""
    base = link or Link("base_link", INERTIAL, (WHEEL,))
    arm = Link("arm", INERTIAL)
    join = joint or Joint("arm_joint", JointType.REVOLUTE, "base_link", "arm", limit=Limit(1, 1))
    return Robot(name, (base, arm), (join,), **fields)


def _shape(geometry: Any, **fields: Any) -> Link:
    return Link("base_link", INERTIAL, (Visual(geometry, **fields),))


def test_the_robot_built_here_is_clean_and_round_trips() -> None:
    robot = _robot()
    assert check(robot) == ()
    assert parse(to_urdf(robot)) == robot


# -- numbers that are not finite -----------------------------------------------------------
NOT_FINITE: list[tuple[str, Robot, str]] = [
    ("box", _robot(_shape(Box((NAN, 1, 1)))), "link 'base_link': visual box size is nan 1 1"),
    ("cylinder radius", _robot(_shape(Cylinder(INF, 1))), "visual cylinder radius is inf"),
    ("cylinder length", _robot(_shape(Cylinder(1, -INF))), "visual cylinder length is -inf"),
    ("sphere", _robot(_shape(Sphere(NAN))), "link 'base_link': visual sphere radius is nan"),
    ("mesh scale", _robot(_shape(Mesh("a.stl", (1, INF, 1)))), "visual mesh scale is 1 inf 1"),
    (
        "visual origin",
        _robot(_shape(Box((1, 1, 1)), origin=Origin((0, 0, 0), (NAN, 0, 0)))),
        "link 'base_link': visual origin rpy is nan 0 0",
    ),
    (
        "colour",
        _robot(_shape(Box((1, 1, 1)), material=Material("m", (NAN, 0, 0, 1)))),
        "link 'base_link': visual material 'm' color is nan 0 0 1",
    ),
    (
        "mass",
        _robot(Link("base_link", Inertial(INF, INERTIAL.inertia))),
        "link 'base_link': inertial mass is inf",
    ),
    (
        "inertia",
        _robot(Link("base_link", Inertial(1.0, Inertia(izz=NAN)))),
        "link 'base_link': inertial izz is nan",
    ),
    (
        "inertial origin",
        _robot(Link("base_link", replace(INERTIAL, origin=Origin((0, NAN, 0))))),
        "link 'base_link': inertial origin xyz is 0 nan 0",
    ),
]
_JOINT = Joint("arm_joint", JointType.REVOLUTE, "base_link", "arm", limit=Limit(1, 1))
NOT_FINITE += [
    (
        part,
        _robot(joint=replace(_JOINT, **{part.split()[0]: value})),
        f"joint 'arm_joint': {message}",
    )
    for part, value, message in [
        ("origin", Origin((NAN, 0, 0)), "origin xyz is nan 0 0"),
        ("axis", (0, 0, INF), "axis is 0 0 inf"),
        ("limit", Limit(1, NAN, -1, 1), "limit velocity is nan"),
        ("dynamics", Dynamics(INF), "dynamics damping is inf"),
        ("calibration", Calibration(rising=NAN), "calibration rising is nan"),
        ("mimic", Mimic("other", NAN), "mimic multiplier is nan"),
        ("safety_controller", SafetyController(-INF), "safety_controller k_velocity is -inf"),
    ]
]


@pytest.mark.parametrize(
    ("robot", "message"), [c[1:] for c in NOT_FINITE], ids=[c[0] for c in NOT_FINITE]
)
def test_a_number_that_is_not_finite_is_a_bad_number(robot: Robot, message: str) -> None:
    found = [(d.rule, d.severity.value, d.message) for d in check(robot) if d.rule == "bad-number"]
    assert len(found) == 1
    assert found[0][:2] == ("bad-number", "error")
    assert found[0][2].endswith(message)
    with pytest.raises(RobotError) as info:
        to_urdf(robot)
    assert [d.message for d in info.value.diagnostics] == [found[0][2]]


def test_a_bad_number_says_where_it_is_and_silences_what_follows_from_it() -> None:
    robot = _robot(joint=replace(_JOINT, axis=(NAN, 0.0, 0.0)))
    (finding,) = check(robot)
    assert finding.subject == fishbot_urdf.Subject(fishbot_urdf.Kind.JOINT, "arm_joint")
    assert finding.data["field"] == "robot.joints[0].axis"
    assert finding.format() == (
        "<robot>: error: joint 'arm_joint': axis is nan 0 0 (write finite numbers) [bad-number]"
    )


def test_every_bad_number_is_listed() -> None:
    link = Link("base_link", Inertial(NAN, Inertia(ixx=INF)), (Visual(Box((NAN, NAN, 1))),))
    robot = _robot(link)
    messages = [d.message for d in check(robot)]
    assert messages == [
        "link 'base_link': inertial mass is nan",
        "link 'base_link': inertial ixx is inf",
        "link 'base_link': visual box size is nan nan 1",
    ]
    with pytest.raises(RobotError) as info:
        to_urdf(robot)
    assert [d.message for d in info.value.diagnostics] == messages
    assert str(info.value) == f"<robot>: {messages[0]} [bad-number] (and 2 more)"


# -- names ---------------------------------------------------------------------------------
NAMES: list[tuple[str, Callable[[Any], Robot], str, str]] = [
    ("robot", lambda n: _robot(name=n), "robot-name", "<robot> has no name"),
    (
        "link",
        lambda n: _robot(Link(n, INERTIAL)),
        "missing-attribute",
        "link at robot.links[0]: <link> has no 'name' attribute",
    ),
    (
        "joint",
        lambda n: _robot(joint=replace(_JOINT, name=n)),
        "missing-attribute",
        "joint at robot.joints[0]: <joint> has no 'name' attribute",
    ),
    (
        "parent",
        lambda n: _robot(joint=replace(_JOINT, parent=n)),
        "missing-attribute",
        "joint 'arm_joint': <parent> has no 'link' attribute",
    ),
    (
        "mimic",
        lambda n: _robot(joint=replace(_JOINT, mimic=Mimic(n))),
        "missing-attribute",
        "joint 'arm_joint': <mimic> has no 'joint' attribute",
    ),
    (
        "mesh",
        lambda n: _robot(_shape(Mesh(n))),
        "missing-attribute",
        "link 'base_link': visual <mesh> has no 'filename' attribute",
    ),
]


@pytest.mark.parametrize("empty", [None, ""])
@pytest.mark.parametrize(
    ("build", "rule", "message"), [n[1:] for n in NAMES], ids=[n[0] for n in NAMES]
)
def test_a_missing_name_is_the_readers_finding(
    build: Callable[[Any], Robot], rule: str, message: str, empty: str | None
) -> None:
    robot = build(empty)
    errors = [(d.rule, d.message) for d in check(robot) if d.is_error]
    if message.startswith("link at"):  # and the joint's parent is undefined, as in a file
        assert errors[1][0] == "undefined-link"
        del errors[1]
    assert errors == [(rule, message)]
    with pytest.raises(RobotError) as info:
        to_urdf(robot)
    assert [d.rule for d in info.value.diagnostics] == [rule]


def test_a_material_may_have_an_empty_name_but_not_none() -> None:
    robot = _robot(_shape(Box((1, 1, 1)), material=Material("")), materials=(Material(""),))
    assert check(robot) == ()
    assert parse(to_urdf(robot)) == robot
    robot = _robot(materials=(Material(None),))  # type: ignore[arg-type]
    assert [d.message for d in check(robot)] == [
        "material at robot.materials[0]: <material> has no 'name' attribute"
    ]


CONTROL = [
    ("a\x00b", "control character 0x00"),
    ("a\x1bb", "control character 0x1B"),
    ("a\ud800", "a lone surrogate U+D800"),
    ("a\uffff", "U+FFFF, not a character"),
]


@pytest.mark.parametrize(("name", "what"), CONTROL)
def test_a_character_xml_cannot_hold_is_an_error(name: str, what: str) -> None:
    robot = _robot(Link(name, INERTIAL), joint=replace(_JOINT, parent=name))
    found = [(d.rule, d.severity.value, d.message) for d in check(robot)]
    assert found == [
        (
            "xml-control-char",
            "error",
            f"link {name!r}: its name holds {what}, which XML cannot hold",
        ),
        (
            "xml-control-char",
            "error",
            f"joint 'arm_joint': <parent> link {name!r} holds {what}, which XML cannot hold",
        ),
    ]
    with pytest.raises(RobotError):
        to_urdf(robot)


@pytest.mark.parametrize(
    "where",
    ["robot", "material", "visual material", "texture", "visual name", "filename", "version"],
)
def test_every_text_is_looked_at(where: str) -> None:
    bad = "x\x07"
    robot = {
        "robot": _robot(name=bad),
        "material": _robot(materials=(Material(bad),)),
        "visual material": _robot(_shape(Box((1, 1, 1)), material=Material(bad))),
        "texture": _robot(_shape(Box((1, 1, 1)), material=Material("m", texture=bad))),
        "visual name": _robot(_shape(Box((1, 1, 1)), name=bad)),
        "filename": _robot(_shape(Mesh(bad))),
        "version": _robot(version=bad),
    }[where]
    rules = [d.rule for d in check(robot) if d.is_error]
    assert "xml-control-char" in rules
    with pytest.raises(RobotError):
        to_urdf(robot)


@pytest.mark.parametrize("name", ["a\nb", "tab\there", "r\r", "\x7f\x85", "grün", " "])
def test_names_a_file_can_give_stay_fine(name: str) -> None:
    robot = _robot(Link(name, INERTIAL), joint=replace(_JOINT, parent=name))
    assert check(robot) == ()
    assert parse(to_urdf(robot)) == robot


def test_a_name_read_from_a_file_stays_fine() -> None:
    robot = parse('<robot name="r&#10;1"><link name="a&#9;b&#13;"/><link name="é"/></robot>')
    assert [link.name for link in robot.links] == ["a\tb\r", "é"]
    assert [d.rule for d in check(robot) if d.is_error] == ["multiple-roots"]
    assert parse(to_urdf(robot)) == robot


def test_a_version_other_than_1_0_is_refused() -> None:
    assert check(_robot(version="1.0")) == ()
    (finding,) = check(_robot(version="2.0"))
    assert (finding.rule, finding.message) == (
        "robot-version",
        '<robot version="2.0"> is not a URDF version this tool knows',
    )
    with pytest.raises(RobotError):
        to_urdf(_robot(version="2.0"))


def test_a_colour_outside_0_1_is_a_bad_color() -> None:
    robot = _robot(_shape(Box((1, 1, 1)), material=Material("m", (255, 0, 0, 1))))
    (finding,) = check(robot)
    assert (finding.rule, finding.message) == (
        "bad-color",
        "link 'base_link': visual material 'm' color 255 0 0 1 has a value outside 0..1",
    )


# -- types ---------------------------------------------------------------------------------
TYPES: list[tuple[str, Callable[[], Robot], str, str]] = [
    ("robot", lambda: "robot", "robot", "a Robot"),  # type: ignore[list-item,return-value]
    ("links", lambda: Robot("r", [Link("a")]), "robot.links", "a tuple of Link"),  # type: ignore[arg-type]
    ("link", lambda: Robot("r", ("a",)), "robot.links[0]", "a Link"),  # type: ignore[arg-type]
    ("name", lambda: _robot(Link(5)), "robot.links[0].name", "a str"),  # type: ignore[arg-type]
    (
        "str for a float",
        lambda: _robot(Link("base_link", Inertial("1", INERTIAL.inertia))),  # type: ignore[arg-type]
        "robot.links[0].inertial.mass",
        "a number (int or float)",
    ),
    (
        "None for a float",
        lambda: _robot(_shape(Sphere(None))),  # type: ignore[arg-type]
        "robot.links[0].visuals[0].geometry.radius",
        "a number (int or float)",
    ),
    (
        "list for a tuple",
        lambda: _robot(_shape(Box([1, 1, 1]))),  # type: ignore[arg-type]
        "robot.links[0].visuals[0].geometry.size",
        "a tuple of 3 numbers",
    ),
    (
        "None for a tuple",
        lambda: _robot(joint=replace(_JOINT, axis=None)),
        "robot.joints[0].axis",
        "a tuple of 3 numbers",
    ),
    (
        "two numbers for three",
        lambda: _robot(joint=replace(_JOINT, origin=Origin((1.0, 2.0)))),  # type: ignore[arg-type]
        "robot.joints[0].origin.xyz",
        "a tuple of 3 numbers",
    ),
    (
        "int for an Enum",
        lambda: _robot(joint=replace(_JOINT, type=3)),
        "robot.joints[0].type",
        "a JointType",
    ),
    (
        "str for an Enum",
        lambda: _robot(joint=replace(_JOINT, type="fixed")),
        "robot.joints[0].type",
        "a JointType",
    ),
    (
        "str in a vector",
        lambda: _robot(joint=replace(_JOINT, axis=(0, 0, "1"))),
        "robot.joints[0].axis[2]",
        "a number (int or float)",
    ),
    (
        "complex",
        lambda: _robot(joint=replace(_JOINT, limit=Limit(1j, 1))),  # type: ignore[arg-type]
        "robot.joints[0].limit.effort",
        "a number (int or float)",
    ),
    (
        "an int past the floats",
        lambda: _robot(Link("base_link", Inertial(10**400, INERTIAL.inertia))),
        "robot.links[0].inertial.mass",
        "a number a float can hold",
    ),
    (
        "geometry",
        lambda: _robot(_shape("box")),
        "robot.links[0].visuals[0].geometry",
        "a Box, Cylinder, Sphere or Mesh",
    ),
    (
        "a visual among collisions",
        lambda: _robot(Link("base_link", collisions=(WHEEL,))),
        "robot.links[0].collisions[0]",
        "a Collision",
    ),
    (
        "source",
        lambda: _robot(Link("base_link", source="x.urdf")),
        "robot.links[0].source",
        "a Location or None",
    ),  # type: ignore[arg-type]
    ("extras", lambda: _robot(extras="<gazebo/>"), "robot.extras", "a tuple of str"),  # type: ignore[arg-type]
    (
        "limit",
        lambda: _robot(joint=replace(_JOINT, limit=Dynamics())),
        "robot.joints[0].limit",
        "a Limit or None",
    ),
]


@pytest.mark.parametrize(
    ("build", "field", "expected"), [t[1:] for t in TYPES], ids=[t[0] for t in TYPES]
)
def test_a_field_of_the_wrong_type_raises_field_type_error(
    build: Callable[[], Robot], field: str, expected: str
) -> None:
    robot = build()
    for call in (check, to_urdf):
        with pytest.raises(FieldTypeError) as info:
            call(robot)
        assert (info.value.field, info.value.expected) == (field, expected)
        assert info.value.message.startswith(f"{field} is ")


def test_field_type_error() -> None:
    robot = _robot(Link("base_link", Inertial("1", INERTIAL.inertia)))  # type: ignore[arg-type]
    with pytest.raises(FieldTypeError) as info:
        check(robot)
    error = info.value
    assert isinstance(error, FishbotUrdfError)
    assert isinstance(error, TypeError)
    assert error.rule == "field-type"
    assert (error.field, error.expected, error.value) == (
        "robot.links[0].inertial.mass",
        "a number (int or float)",
        "1",
    )
    assert str(error) == "robot.links[0].inertial.mass is str '1', not a number (int or float)"
    long = FieldTypeError("robot.name", "a str", list(range(100)))
    assert str(long) == "robot.name is list [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11..., not a str"


def test_numbers_of_other_kinds_are_numbers() -> None:
    from fractions import Fraction

    import numpy as np

    box = Box((np.float32(0.5), np.float64(0.5), Fraction(1, 2)))  # type: ignore[arg-type]
    robot = _robot(_shape(box), joint=replace(_JOINT, limit=Limit(True, 1)))
    assert check(robot) == ()
    assert parse(to_urdf(robot)) == robot
    assert [d.message for d in check(_robot(_shape(Sphere(np.float32("nan")))))] == [
        "link 'base_link': visual sphere radius is nan"
    ]


# -- at random -----------------------------------------------------------------------------
# What a file can give a name: no control character but tab, line feed and carriage return
# (and DEL and the C1 controls, which XML allows), no U+FFFE or U+FFFF.
_NAMES = st.text(
    st.characters(
        codec="utf-8",
        exclude_categories=("Cs", "Cc"),
        exclude_characters="\ufffe\uffff",
        include_characters="\t\n\r\x7f\x85",
    ),
    min_size=1,
)
# Sizes of robot parts in metres: up to 2 m (a robot of 10 m parts, metres apart and
# lighter than air, reads as millimetres: robot-units, an error)
_SIZE = st.floats(0.01, 2.0)
_ANY = st.floats(-10.0, 10.0)
_VECTOR = st.tuples(_ANY, _ANY, _ANY)
_ORIGINS = st.builds(Origin, _VECTOR, _VECTOR)
_GEOMETRY = st.one_of(
    st.builds(Box, st.tuples(_SIZE, _SIZE, _SIZE)),
    st.builds(Cylinder, _SIZE, _SIZE),
    st.builds(Sphere, _SIZE),
    st.builds(Mesh, st.just("package://bot/a.stl"), st.none() | st.tuples(_SIZE, _SIZE, _SIZE)),
)
_COLOR = st.floats(0.0, 1.0)
_MATERIAL = st.builds(Material, _NAMES, st.none() | st.tuples(_COLOR, _COLOR, _COLOR, _COLOR))


@st.composite
def robots(draw: st.DrawFn) -> Robot:
    """A chain of links that passes check()."""
    count = draw(st.integers(1, 4))
    names = draw(st.lists(_NAMES, min_size=count, max_size=count, unique=True))
    links = []
    for name in names:
        mass = draw(st.floats(0.5, 5.0))
        inertial = Inertial(mass, Inertia(1.0, 0.0, 0.0, 1.0, 0.0, 1.0), draw(_ORIGINS))
        visuals = draw(
            st.lists(st.builds(Visual, _GEOMETRY, _ORIGINS, st.none() | _MATERIAL), max_size=2)
        )
        collisions = draw(st.lists(st.builds(Collision, _GEOMETRY, _ORIGINS), max_size=2))
        links.append(Link(name, inertial, tuple(visuals), tuple(collisions)))
    joints = []
    for index, (parent, child) in enumerate(pairwise(names)):
        kind = draw(st.sampled_from([JointType.REVOLUTE, JointType.CONTINUOUS, JointType.FIXED]))
        axis = draw(st.sampled_from([(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]))
        limit = Limit(1.0, 1.0, -1.0, 1.0) if kind is JointType.REVOLUTE else None
        dynamics = draw(st.none() | st.builds(Dynamics, st.floats(0, 1), st.floats(0, 1)))
        joints.append(
            Joint(f"joint_{index}", kind, parent, child, draw(_ORIGINS), axis, limit, dynamics)
        )
    return Robot(draw(_NAMES), tuple(links), tuple(joints))


BAD_NUMBERS = [NAN, INF, -INF, 10**400]
BAD_NAMES = [None, "", "a\x00", "\ud800", "\ufffe"]
WRONG = ["1", None, [1.0, 2.0, 3.0], 3, b"x", 1j]


def _leaves(item: object, path: tuple[Any, ...] = ()) -> list[tuple[tuple[Any, ...], object]]:
    """Every field below ``item`` that is no dataclass, with the path to it."""
    found: list[tuple[tuple[Any, ...], object]] = []
    if is_dataclass(item):
        for f in fields(item):
            if f.name.endswith("source"):
                continue
            value = getattr(item, f.name)
            found.append(((*path, f.name), value))
            found.extend(_leaves(value, (*path, f.name)))
    elif isinstance(item, tuple):
        for index, value in enumerate(item):
            if is_dataclass(value):
                found.extend(_leaves(value, (*path, index)))
    return found


def _put(item: Any, path: tuple[Any, ...], value: object) -> Any:
    """``item`` with the field at ``path`` set to ``value``."""
    if not path:
        return value
    head, rest = path[0], path[1:]
    if isinstance(head, int):
        return (*item[:head], _put(item[head], rest, value), *item[head + 1 :])
    return replace(item, **{head: _put(getattr(item, head), rest, value)})


@st.composite
def spoiled(draw: st.DrawFn) -> Robot:
    """A robot with a few of its fields set to values the reader would never give."""
    robot = draw(robots())
    for _ in range(draw(st.integers(1, 3))):
        path, value = draw(st.sampled_from(_leaves(robot)))
        if isinstance(value, float):
            bad = draw(st.sampled_from([*BAD_NUMBERS, *WRONG]))
        elif isinstance(value, str) or value is None:
            bad = draw(st.sampled_from([*BAD_NAMES, *WRONG, "a\nb"]))
        elif isinstance(value, tuple) and value and isinstance(value[0], float):
            index = draw(st.integers(0, len(value) - 1))
            bad = (
                *value[:index],
                draw(st.sampled_from([*BAD_NUMBERS, *WRONG])),
                *value[index + 1 :],
            )
        else:
            bad = draw(st.sampled_from([*WRONG, value]))
        robot = _put(robot, path, bad)
    return robot


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(robots())
def test_a_robot_that_passes_check_round_trips(robot: Robot) -> None:
    assert [d for d in check(robot) if d.is_error] == []
    assert parse(to_urdf(robot)) == robot


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(spoiled())
def test_check_only_finds_and_to_urdf_only_refuses(robot: Robot) -> None:
    try:
        found = check(robot)
    except FieldTypeError:
        with pytest.raises(FieldTypeError):
            to_urdf(robot)
        return
    try:
        text = to_urdf(robot)
    except RobotError as error:
        assert all(d.is_error for d in error.diagnostics)
        assert {d.rule for d in error.diagnostics} <= {d.rule for d in found}
        return
    if not any(d.is_error for d in found):
        assert parse(text) == _as_read(robot)


def _as_read(robot: Robot) -> Robot:
    """``robot`` as a reader gives it back: an empty texture file name is none (urdfdom
    ignores ``<texture filename=""/>``, and so does the reader)."""
    from dataclasses import replace

    def material(m: Material | None) -> Material | None:
        return m if m is None or m.texture != "" else replace(m, texture=None)

    links = tuple(
        replace(
            link, visuals=tuple(replace(v, material=material(v.material)) for v in link.visuals)
        )
        for link in robot.links
    )
    return replace(robot, links=links, materials=tuple(map(material, robot.materials)))


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(robots(), spoiled()))
def test_the_quick_test_agrees_with_the_walk(robot: Robot) -> None:
    outcomes = []
    plain = values_module.plain
    for quick in (plain, lambda robot: False):
        values_module.plain = quick
        try:
            outcomes.append([d.message for d in values(robot)])
        except FieldTypeError as error:
            outcomes.append([error.field])
        finally:
            values_module.plain = plain
    assert outcomes[0] == outcomes[1]


def _turned(robot: fishbot_urdf.Robot, where: str, value: float) -> fishbot_urdf.Robot:
    """``robot`` (one link with a cylinder collision, a revolute joint to a second link)
    with one number made ``value``."""
    from dataclasses import replace

    link, joint = robot.links[0], robot.joints[0]
    if where == "collision rpy":
        shape = link.collisions[0]
        turned = replace(shape, origin=replace(shape.origin, rpy=(0.0, value, 0.0)))
        return replace(robot, links=(replace(link, collisions=(turned,)), *robot.links[1:]))
    if where == "joint xyz":
        joint = replace(joint, origin=replace(joint.origin, xyz=(value, 0.0, 0.0)))
    elif where == "joint axis":
        joint = replace(joint, axis=(value, 0.0, 0.0))
    return replace(robot, joints=(joint,))


@pytest.mark.parametrize("where", ["collision rpy", "joint xyz", "joint axis"])
@pytest.mark.parametrize("value", [math.inf, -math.inf, math.nan])
def test_the_other_rules_read_a_number_that_is_not_finite_as_0(where: str, value: float) -> None:
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="a"><inertial><mass value="1"/>'
        '<inertia ixx="0.00333333" ixy="0" ixz="0" iyy="0.00333333" iyz="0" izz="0.005"/>'
        "</inertial>"
        '<collision><geometry><cylinder radius="0.1" length="0.1"/></geometry></collision>'
        '</link><link name="b"/><joint name="j" type="revolute"><parent link="a"/>'
        '<child link="b"/><axis xyz="1 0 0"/>'
        '<limit effort="1" velocity="1" lower="-1" upper="1"/></joint></robot>'
    )
    assert fishbot_urdf.check(robot) == ()
    found = fishbot_urdf.check(_turned(robot, where, value))
    assert [d.rule for d in found] == ["bad-number"], found
    said = {
        "collision rpy": "collision origin rpy",
        "joint xyz": "origin xyz",
        "joint axis": "axis",
    }
    assert said[where] in found[0].message
