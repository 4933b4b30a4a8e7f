"""Each rule: its fixture, its rule id, the exact line and column, and the message text."""

from __future__ import annotations

import struct
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import DATA, INVALID, VALID

import fishbot_urdf
from fishbot_urdf import Config, Severity, check_file

# (fixture, rule, severity, text the finding points at, message).
# The expected line and column are where the pointed-at text first occurs in the fixture
# (at the "|" in it, if there is one), computed by the test, not written down.
CASES = [
    ("robot_name", "robot-name", "error", "<robot>", "<robot> has no name"),
    ("no_robot", "no-robot", "error", "<model", "the root element is <model>, not <robot>"),
    ("no_links", "no-links", "error", "<robot", "robot 'empty' has no links"),
    (
        "duplicate_link",
        "duplicate-link",
        "error",
        '<link name="wheel"/>\n  |<link name="wheel"/>',
        "link 'wheel' is defined twice (first defined at line 4)",
    ),
    (
        "duplicate_joint",
        "duplicate-joint",
        "error",
        '<joint name="j" type="fixed"><parent link="base_link"/><child link="b"/>',
        "joint 'j' is defined twice (first defined at line 6)",
    ),
    (
        "duplicate_material",
        "duplicate-material",
        "error",
        '<material name="white"><color rgba="0.9',
        "material 'white' is defined twice (first defined at line 3)",
    ),
    (
        "joint_type",
        "joint-type",
        "error",
        'type="rotating"',
        "joint 'wheel_joint': type 'rotating' is not a URDF joint type",
    ),
    (
        "missing_limit",
        "missing-limit",
        "error",
        '<joint name="shoulder"',
        "joint 'shoulder': a revolute joint needs <limit>",
    ),
    (
        "limit_no_effort",
        "missing-attribute",
        "error",
        "<limit",
        "joint 'shoulder': <limit> has no 'effort' attribute",
    ),
    (
        "bad_vector",
        "bad-vector",
        "error",
        'xyz="0 0.03"',
        "joint 'imu_joint': <origin xyz=\"0 0.03\"> has 2 values, 3 are needed",
    ),
    (
        "bad_number",
        "bad-number",
        "error",
        'value="1kg"',
        "link 'base_link': <mass value=\"1kg\"> is not a number",
    ),
    (
        "undefined_parent",
        "undefined-link",
        "error",
        '<parent link="base"/>',
        "joint 'left_wheel_joint': parent link 'base' is not defined",
    ),
    (
        "undefined_child",
        "undefined-link",
        "error",
        '<child link="camera_lnk"/>',
        "joint 'camera_joint': child link 'camera_lnk' is not defined",
    ),
    (
        "joint_no_child",
        "missing-element",
        "error",
        '<joint name="imu_joint"',
        "joint 'imu_joint': has no <child>",
    ),
    (
        "multiple_roots",
        "multiple-roots",
        "error",
        '<link name="laser_link"/>',
        "robot 'two_roots' has 2 root links: 'base_link', 'laser_link'",
    ),
    (
        "no_root",
        "no-root",
        "error",
        "<robot",
        "robot 'ring' has no root link: every link is some joint's child",
    ),
    (
        "cycle",
        "cycle",
        "error",
        '<joint name="a_to_b"',
        "joints 'a_to_b', 'b_to_c', 'c_to_a' form a loop: a -> b -> c -> a",
    ),
    (
        "multiple_parents",
        "multiple-parents",
        "error",
        '<parent link="right"/>|<child link="bar"/>',
        "link 'bar' is the child of 2 joints: 'bar_left', 'bar_right'",
    ),
    (
        "self_loop",
        "joint-self-loop",
        "error",
        '<child link="arm"/><axis',
        "joint 'spin': parent and child are the same link 'arm'",
    ),
    (
        "undefined_mimic",
        "undefined-mimic",
        "error",
        "<mimic",
        "joint 'right_finger': mimics joint 'left_fingr', which is not defined",
    ),
    (
        "limit_range",
        "limit-range",
        "error",
        "<limit",
        "joint 'shoulder': lower limit 1.57 is above upper limit -1.57",
    ),
    (
        "zero_axis",
        "zero-axis",
        "error",
        '<joint name="wheel_joint"',
        "joint 'wheel_joint': the axis is 0 0 0, so the joint cannot move",
    ),
    (
        "axis_without_xyz",
        "missing-attribute",
        "warning",
        "<axis/>",
        "joint 'shoulder': <axis> has no 'xyz' attribute, so urdfdom reads the axis as 0 0 0",
    ),
    (
        "negative_limit",
        "negative-limit",
        "error",
        "<limit",
        "joint 'shoulder': effort limit -10 is negative",
    ),
    (
        "negative_mass",
        "negative-mass",
        "error",
        "<inertial>",
        "link 'base_link': mass -2 kg is negative",
    ),
    (
        "collision_material",
        "collision-material",
        "warning",
        '<material name="white">',
        "link 'base_link': <material> inside <collision> is ignored",
    ),
    (
        "robot_version",
        "robot-version",
        "error",
        'version="2.0"',
        '<robot version="2.0"> is not a URDF version this tool knows',
    ),
    (
        "bad_color",
        "bad-color",
        "error",
        'rgba="255',
        "material 'orange': <color rgba=\"255 165 0 1\"> has a value outside 0..1",
    ),
    (
        "unknown_geometry",
        "unknown-geometry",
        "error",
        "<capsule",
        "link 'base_link': <capsule> is not a URDF shape",
    ),
    (
        "missing_geometry",
        "missing-element",
        "error",
        "<visual>",
        "link 'base_link': <visual> has no <geometry>",
    ),
    (
        "cylinder_no_length",
        "missing-attribute",
        "error",
        "<cylinder",
        "link 'base_link': <cylinder> has no 'length' attribute",
    ),
]


def _position(path: Path, needle: str) -> tuple[int, int]:
    text = path.read_text(encoding="utf-8")
    marker = max(needle.find("|"), 0)
    offset = text.index(needle.replace("|", "")) + marker
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return line, column


# Each fixture checked for every program its rule names: its finding at the rule's severity.
EVERY_PROGRAM = Config(targets=("all",))


@pytest.mark.parametrize(
    ("name", "rule", "severity", "needle", "message"), CASES, ids=[c[0] for c in CASES]
)
def test_rule(name: str, rule: str, severity: str, needle: str, message: str) -> None:
    path = DATA / "invalid" / f"{name}.urdf"
    result = check_file(path, config=EVERY_PROGRAM)
    matching = [d for d in result.diagnostics if d.rule == rule]
    assert len(matching) == 1, [d.format() for d in result.diagnostics]
    finding = matching[0]
    assert finding.severity is Severity(severity)
    assert (finding.line, finding.column) == _position(path, needle)
    assert finding.message == message
    assert finding.path == str(path)
    assert finding.hint, "every finding says what to do"


def test_every_invalid_fixture_has_a_case() -> None:
    named = {c[0] for c in CASES} | {"xml_syntax", "loop_from_root"}
    assert {p.stem for p in INVALID} == named


def test_each_fixture_reports_only_its_own_problem() -> None:
    # Findings that are mere consequences of another (an extra root left by a misspelt
    # link name, the second parent of a self-loop) are not reported.
    for name, rule, *_ in CASES:
        result = check_file(DATA / "invalid" / f"{name}.urdf")
        rules = {d.rule for d in result.diagnostics}
        allowed = {rule, "cycle"} if rule == "no-root" else {rule}
        assert rules == allowed, (name, [d.format() for d in result.diagnostics])


@pytest.mark.parametrize("path", VALID, ids=[p.stem for p in VALID])
def test_valid_fixtures_have_no_findings(path: Path) -> None:
    # all_elements.urdf names a mesh in package "demo"; rotations.urdf turns its frames by
    # angles past a whole turn on purpose (the rotation arithmetic must wrap), which reads
    # as degrees.
    result = check_file(path, packages={"demo": DATA / "valid" / "demo"})
    assert result.ok
    expected = {"rpy-degrees"} if path.stem == "rotations" else set()
    assert {d.rule for d in result.diagnostics} == expected


def test_check_on_a_robot_built_in_code() -> None:
    robot = fishbot_urdf.Robot(
        name="made",
        links=(fishbot_urdf.Link("a"), fishbot_urdf.Link("b")),
        joints=(fishbot_urdf.Joint("j", fishbot_urdf.JointType.REVOLUTE, "a", "b"),),
    )
    findings = fishbot_urdf.check(robot)
    assert [d.rule for d in findings] == ["missing-limit"]
    assert findings[0].path == "<robot>"


def test_unreachable_links_below_a_loop() -> None:
    text = b"""<robot name="r"><link name="root"/><link name="a"/><link name="b"/>
<link name="hanging"/>
<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint>
<joint name="bh" type="fixed"><parent link="b"/><child link="hanging"/></joint></robot>"""
    result = check_file(text, path="loop.urdf")
    assert [(d.rule, d.line) for d in result.diagnostics] == [
        ("unreachable-link", 2),
        ("cycle", 3),
    ]
    assert result.diagnostics[0].message == "link 'hanging' is not connected to the root"


def test_loop_reached_from_the_root() -> None:
    path = DATA / "invalid" / "loop_from_root.urdf"
    found = [(d.rule, d.message) for d in check_file(path).diagnostics]
    assert found == [
        ("cycle", "joints 'a_to_b', 'b_to_a' form a loop: a -> b -> a"),
        ("multiple-parents", "link 'a' is the child of 2 joints: 'base_to_a', 'b_to_a'"),
    ]


def test_an_axis_without_xyz_is_zero_as_urdfdom_reads_it(tmp_path: Path) -> None:
    # urdfdom keeps its 1 0 0 default only when <axis> is left out: <axis/> leaves 0 0 0,
    # and a moving joint cannot move about it.
    fixed = (DATA / "invalid" / "axis_without_xyz.urdf").read_text()
    path = tmp_path / "revolute.urdf"
    path.write_text(
        fixed.replace('type="fixed"', 'type="revolute"').replace(
            "<axis/>", '<axis/>\n    <limit lower="-1" upper="1" effort="1" velocity="1"/>'
        )
    )
    result = fishbot_urdf.check_file(path)
    assert result.robot is not None
    assert result.robot.joint("shoulder").axis == (0.0, 0.0, 0.0)
    assert [(d.rule, d.severity.value, d.line) for d in result.diagnostics] == [
        ("zero-axis", "error", 5),
        ("missing-attribute", "warning", 8),
    ]


def test_a_consequence_is_reported_when_its_cause_is_not() -> None:
    # A misspelt parent leaves its child as an extra root: the extra root is the misspelling's
    # consequence, reported alone only when the misspelling's rule is turned off.
    path = DATA / "invalid" / "undefined_parent.urdf"
    assert [d.rule for d in check_file(path).diagnostics] == ["undefined-link"]
    quiet = fishbot_urdf.Config(ignore=("undefined-link",))
    assert [d.rule for d in check_file(path, config=quiet).diagnostics] == ["multiple-roots"]


_COUNT_MESH_OPENS = """
import sys

opened = []


def hook(event, args):
    if event == "open" and str(args[0]).endswith(".stl"):
        opened.append(args[0])


sys.addaudithook(hook)
from fishbot_urdf.cli import main

try:
    main(sys.argv[1:])
except SystemExit:
    pass
sys.stderr.write(f"\\nopened {len(opened)}")
"""


def _mesh_files_opened(*args: str) -> int:
    out = subprocess.run(
        [sys.executable, "-c", _COUNT_MESH_OPENS, "check", *args],
        capture_output=True,
        text=True,
        check=True,
    )
    return int(out.stderr.rsplit("opened ", 1)[1])


@pytest.mark.parametrize(
    "selection",
    [("--select", "structure"), ("--ignore", "meshes"), ("--select", "joints,physics")],
)
def test_a_check_whose_rules_are_all_turned_off_opens_no_mesh_file(
    tmp_path: Path, selection: tuple[str, str]
) -> None:
    # two links drawn by an STL file beside the robot: a check of its meshes reads it
    triangle = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 0.1, 0, 0, 0, 0.1, 0, 0)
    (tmp_path / "part.stl").write_bytes(b"\0" * 80 + struct.pack("<I", 1) + triangle)
    mesh = '<visual><geometry><mesh filename="part.stl"/></geometry></visual>'
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        f'<robot name="r"><link name="a">{mesh}</link><link name="b">{mesh}</link>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>'
    )
    assert _mesh_files_opened(str(robot)) >= 1
    assert _mesh_files_opened(str(robot), *selection) == 0
