"""Parsing: the model, number rules (compared live with urdfdom), locations, round trips."""

from __future__ import annotations

from pathlib import Path
from unittest import mock
from xml.sax.saxutils import escape

import pytest
from conftest import (
    CORPUS,
    DATA,
    VALID,
    GoldenInput,
    check_urdf,
    golden_check_urdf,
    repo_id,
)
from hypothesis import given, settings
from hypothesis import strategies as st

import fishbot_urdf
from fishbot_urdf import (
    Box,
    Cylinder,
    JointType,
    Mesh,
    RobotError,
    Sphere,
    load,
    parse,
    to_urdf,
)
from fishbot_urdf.parsing.values import plain_numbers, to_double, to_doubles

ALL = DATA / "valid" / "all_elements.urdf"


# Vectors (signs, exponents, units, raw tabs and line breaks) and robot versions, each a
# small robot; check_urdf's verdict on each is in the golden files (and run live where the
# tool is installed).
URDFDOM = sorted((DATA / "urdfdom").glob("*.urdf"))


@pytest.mark.parametrize("path", URDFDOM, ids=[p.stem for p in URDFDOM])
def test_numbers_and_versions_like_urdfdom(path: Path) -> None:
    real = check_urdf(GoldenInput(repo_id(path), path))
    result = fishbot_urdf.check_file(path)
    assert result.ok is (real.status == 0), [d.format() for d in result.diagnostics]


def test_the_number_cases_have_both_verdicts() -> None:
    verdicts = {golden_check_urdf(GoldenInput(repo_id(p), p)).status == 0 for p in URDFDOM}
    assert verdicts == {True, False}


_PIECES = ["0", "1", "-2.5", "1e308", "1e400", "nan", "inf", "1_0", "\u0663", "\t1", "1\t", "x", ""]


@given(st.lists(st.sampled_from(_PIECES), max_size=5))
def test_numbers_checked_at_once_as_one_by_one(texts: list[str]) -> None:
    one_by_one = [to_double(text) for text in texts]
    assert to_doubles(texts) == (None if None in one_by_one else one_by_one)


_INERTIA = '<mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'


_VECTOR_PIECE = st.sampled_from([*_PIECES, "+3", ".5", "1e-3", "1e308"])


@settings(max_examples=300)
@given(
    st.one_of(  # mostly three pieces, each a number or not
        st.lists(_VECTOR_PIECE, min_size=3, max_size=3),
        st.lists(_VECTOR_PIECE, min_size=1, max_size=4),
    ),
    st.sampled_from([" ", " ", "  ", "\t"]),
)
def test_a_vector_is_read_as_its_pieces_one_by_one(pieces: list[str], gap: str) -> None:
    text = gap.join(pieces)
    written = escape(text, {'"': "&quot;", "\t": "&#9;", "\n": "&#10;"})
    data = (
        f'<robot name="r"><link name="a"><inertial><origin xyz="{written}"/>{_INERTIA}'
        "</inertial></link></robot>"
    )
    parsed = fishbot_urdf.read(data.encode())
    kept = [piece for piece in text.split(" ") if piece]  # as urdfdom splits
    numbers = to_doubles(kept) if len(kept) == 3 else None
    assert parsed.robot is not None and parsed.robot.links[0].inertial is not None
    xyz = parsed.robot.links[0].inertial.origin.xyz
    assert xyz == ((0.0, 0.0, 0.0) if numbers is None else tuple(numbers))
    assert [d.rule for d in parsed.diagnostics] == (
        [] if numbers is not None else ["bad-vector" if len(kept) != 3 else "bad-number"]
    )


def test_model_of_every_element() -> None:
    robot = load(ALL)
    assert robot.name == "everything"
    assert robot.version == "1.0"
    assert [m.name for m in robot.materials] == ["blue", "wood"]
    assert robot.materials[0].color == (0.0, 0.0, 0.8, 1.0)
    assert robot.materials[1].texture == "package://demo/textures/wood.png"
    base = robot.link("base_link")
    assert base.inertial is not None
    assert base.inertial.mass == 2.5
    assert base.inertial.origin.xyz == (0.0, 0.0, 0.05)
    assert base.inertial.inertia.izz == 0.02
    assert [v.name for v in base.visuals] == ["body", None]
    assert base.visuals[0].geometry == Box((0.3, 0.2, 0.1))
    assert base.visuals[1].geometry == Mesh("package://demo/meshes/cover.stl", (0.001,) * 3)
    assert base.collisions[1].geometry == Sphere(0.05)
    arm = robot.link("arm")
    assert arm.visuals[0].geometry == Cylinder(radius=0.02, length=0.4)
    assert arm.visuals[0].material == fishbot_urdf.Material("red", (1.0, 0.0, 0.0, 1.0))
    assert arm.extras == ('<sensor_mount type="custom">kept as XML</sensor_mount>',)
    shoulder = robot.joint("shoulder")
    assert shoulder.type is JointType.REVOLUTE
    assert shoulder.origin.rpy == (0.0, 1.5707963, 0.0)
    assert shoulder.axis == (0.0, 1.0, 0.0)
    assert shoulder.limit == fishbot_urdf.Limit(effort=30, velocity=2, lower=-1.57, upper=1.57)
    assert shoulder.dynamics == fishbot_urdf.Dynamics(damping=0.5, friction=0.1)
    assert shoulder.calibration == fishbot_urdf.Calibration(rising=0.1, falling=-0.1)
    assert shoulder.safety_controller == fishbot_urdf.SafetyController(
        k_velocity=10, k_position=100, soft_lower_limit=-1.5, soft_upper_limit=1.5
    )
    assert robot.joint("finger_b_joint").mimic == fishbot_urdf.Mimic("finger_a_joint", 1, 0)
    assert robot.joint("marker_joint").axis == (1.0, 0.0, 0.0)  # the spec's default
    assert {j.type for j in robot.joints} == set(JointType)
    assert [e.split(" ", 1)[0] for e in robot.extras] == [
        "<transmission",
        "<gazebo",
        "<ros2_control",
    ]


def test_extension_elements_are_kept_without_layout_white_space() -> None:
    parsed = fishbot_urdf.read(
        b'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        b'  <link name="a"/>\n'
        b'  <gazebo reference="a">\n'
        b"    <material>Gazebo/Grey</material>\n"
        b"    <note> two  words </note>\n"
        b"    <empty>  </empty>\n"
        b"  </gazebo>\n"
        b'  <gazebo><plugin name="p"><frameName>\n  a\n</frameName></plugin></gazebo>\n'
        b"</robot>\n"
    )
    assert parsed.robot is not None
    ns = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    assert parsed.robot.extras == (
        f'<gazebo {ns} reference="a"><material>Gazebo/Grey</material>'
        "<note> two  words </note><empty/></gazebo>",
        f'<gazebo {ns}><plugin name="p"><frameName>\n  a\n</frameName></plugin></gazebo>',
    )
    assert [(r.name, r.context) for r in parsed.references] == [
        ("a", "<gazebo reference>"),
        ("a", "plugin <frameName>"),
    ]


def test_every_element_knows_its_line_and_column() -> None:
    robot = load(ALL)
    lines = ALL.read_text().splitlines()

    def where(needle: str) -> tuple[int, int]:
        line = next(i for i, text in enumerate(lines, 1) if needle in text)
        return line, lines[line - 1].index(needle) + 1

    shoulder = robot.joint("shoulder")
    assert shoulder.source == fishbot_urdf.Location(str(ALL), *where('<joint name="shoulder"'))
    assert shoulder.limit is not None and shoulder.limit.source is not None
    assert (shoulder.limit.source.line, shoulder.limit.source.column) == where(
        '<limit lower="-1.57"'
    )
    assert shoulder.parent_source is not None
    assert shoulder.parent_source.line == where('<parent link="base_link"/>')[0]


def test_columns_count_characters_not_bytes() -> None:
    text = "<robot name='r'><!-- 机器人 --><link name='a'><inertial><mass value='x'/>"
    text += "<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial></link></robot>"
    with pytest.raises(RobotError) as info:
        parse(text)
    (finding,) = info.value.diagnostics
    assert finding.column == text.index("value='x'") + 1


def test_comments_do_not_confuse_locations() -> None:
    text = (
        "<robot name='r'>\n<!-- <link name='commented'/> -->\n<link name='a'/>\n"
        "<link name='a'/>\n</robot>"
    )
    (finding,) = fishbot_urdf.check_file(text.encode(), path="c.urdf").diagnostics
    assert (finding.rule, finding.line, finding.column) == ("duplicate-link", 4, 1)


def test_multi_line_start_tags_report_their_first_line() -> None:
    text = b'<robot name="r">\n  <link\n     name="a"/>\n  <link\n    name="a"/>\n</robot>'
    (finding,) = fishbot_urdf.check_file(text, path="m.urdf").diagnostics
    assert (finding.line, finding.column) == (4, 3)


def test_parse_raises_with_every_finding() -> None:
    text = (
        "<robot name='r'><link name='a'><inertial><mass value='1kg'/>"
        "<inertia ixx='x' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial></link></robot>"
    )
    with pytest.raises(RobotError) as info:
        parse(text)
    assert [d.rule for d in info.value.diagnostics] == ["bad-number", "bad-number"]
    assert str(info.value).startswith("<string>:1:")
    assert str(info.value).endswith("[bad-number] (and 1 more)")


# Corpus robots that load (ur3.urdf, for one, has no robot name: check_urdf rejects it too).
LOADABLE = [p for p in CORPUS if not any(d.is_error for d in fishbot_urdf.read(p).diagnostics)]


def test_nearly_all_of_the_corpus_loads() -> None:
    assert len(LOADABLE) >= len(CORPUS) - 2


@pytest.mark.parametrize("path", VALID + LOADABLE, ids=[p.name for p in VALID + LOADABLE])
def test_round_trip(path: Path) -> None:
    robot = load(path)
    text = to_urdf(robot)
    again = parse(text)
    assert again == robot
    assert to_urdf(again) == text


def test_parse_accepts_str_with_an_encoding_declaration() -> None:
    robot = parse(
        '<?xml version="1.0" encoding="UTF-8"?>\n<robot name="机器人"><link name="a"/></robot>'
    )
    assert robot.name == "机器人"


def test_robot_lookup_errors() -> None:
    robot = load(ALL)
    with pytest.raises(KeyError):
        robot.link("nope")
    with pytest.raises(KeyError):
        robot.joint("nope")


@pytest.mark.parametrize(
    ("attribute", "rule"),
    [('xyz="$(optenv LIDAR_XYZ 0 0 0.1)"', "bad-vector"), ('xyz="${x} 0 0"', "bad-number")],
)
def test_a_xacro_substitution_left_in_a_urdf_is_named(attribute: str, rule: str) -> None:
    data = (
        '<robot name="r"><link name="a"/><link name="b"/>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
        f"<origin {attribute}/></joint></robot>"
    ).encode()
    (finding,) = fishbot_urdf.check_file(data, path="r.urdf").diagnostics
    assert finding.rule == rule
    assert finding.hint == (
        "this is a xacro substitution left unexpanded: run xacro or `fishbot expand` on the "
        ".xacro file it came from, or give that file instead"
    )


_PLAIN = ["0", "1", "-2.5", "+3", ".5", "1e-3", "-0"]  # numbers as nearly every file writes them


@given(st.lists(st.one_of(st.none(), st.sampled_from([*_PIECES, *_PLAIN, " 1", "1 "])), max_size=6))
def test_plain_numbers_are_the_numbers_read_one_by_one(texts: list[str | None]) -> None:
    one_by_one = [None if text is None else to_double(text) for text in texts]
    plain = plain_numbers(texts)
    assert plain is None or plain == one_by_one
    if all(text in _PLAIN for text in texts):
        assert plain is not None


@settings(max_examples=200)
@given(
    st.lists(
        st.one_of(st.none(), st.sampled_from([*_PIECES, *_PLAIN, " 1", "1 "])),
        min_size=10,
        max_size=10,
    )
)
def test_inertia_and_limits_read_at_once_as_one_by_one(texts: list[str | None]) -> None:
    names = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz", "effort", "velocity", "lower", "upper")
    written = dict(zip(names, texts, strict=True))

    def attributes(keys: tuple[str, ...]) -> str:
        return " ".join(
            f'{k}="{escape(written[k] or "", {chr(9): "&#9;"})}"'
            for k in keys
            if written[k] is not None
        )

    data = (
        f'<robot name="r"><link name="a"><inertial><mass value="1"/>'
        f"<inertia {attributes(names[:6])}/></inertial></link><link name='b'/>"
        f'<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        f"<limit {attributes(names[6:])}/></joint></robot>"
    ).encode()
    at_once = fishbot_urdf.read(data)
    with (
        mock.patch("fishbot_urdf.parsing._links.plain_numbers", return_value=None),
        mock.patch("fishbot_urdf.parsing._joints.plain_numbers", return_value=None),
    ):
        one_by_one = fishbot_urdf.read(data)
    assert at_once == one_by_one
