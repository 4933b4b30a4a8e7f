"""gazebo-setting: each value in a ``<gazebo>`` block that sdformat 12's URDF converter
crashes on or its reader refuses is a finding at its element, which the real converter
(`ign sdf -p`), where it is installed, refuses or crashes on."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import live_tool

from fishbot_urdf import check_file
from fishbot_urdf.catalog.gazebo import GAZEBO_SETTING
from fishbot_urdf.cli import cli
from fishbot_urdf.diagnostics import Severity

ROBOT = """\
<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="1 1 1"/></geometry></collision>
  </link>
  <gazebo reference="a">
    {setting}
  </gazebo>
</robot>
"""
CRASH = "sdformat's URDF converter crashes on it (std::invalid_argument), so Gazebo cannot load it"
REFUSED = "sdformat's reader refuses the robot, so Gazebo cannot load it"
BAD = [
    ("<mu1>abc</mu1>", f"<mu1> is 'abc', not a number: {CRASH} (write a number)"),
    (
        "<mu1>-1</mu1>",
        f"<mu1> '-1' is less than 0.0, its least: {REFUSED} (write a number >= 0.0)",
    ),
    (
        "<kinematic>yes</kinematic>",
        f"<kinematic> 'yes' is no bool: {REFUSED} (write true, false, 1 or 0)",
    ),
    ("<mu1>${mu}</mu1>", f"<mu1> is '${{mu}}', not a number: {CRASH} (write a number)"),
]
FIXED = "<mu1>0.8</mu1><kinematic>false</kinematic>"


def _check(path: Path, *args: str) -> tuple[int, str]:
    result = CliRunner().invoke(cli, ["check", "--isolated", "--quiet", str(path), *args])
    return result.exit_code, result.stderr


def _robot(tmp_path: Path, setting: str, name: str = "r.urdf") -> Path:
    path = tmp_path / name
    path.write_text(ROBOT.format(setting=setting), encoding="utf-8")
    return path


def _findings(path: Path) -> list[str]:
    return [
        f"{d.line}:{d.column}: {d.severity.value}: {d.message}"
        for d in check_file(path).diagnostics
        if d.rule == GAZEBO_SETTING.id
    ]


@pytest.mark.parametrize(("setting", "message"), BAD, ids=[s for s, _ in BAD])
def test_each_refused_value_is_an_error_at_its_element(
    tmp_path: Path, setting: str, message: str
) -> None:
    path = _robot(tmp_path, setting)
    assert _findings(path) == [f"7:5: error: <gazebo reference='a'>: {message}"]
    status, stderr = _check(path, "--select", "gazebo-setting")
    assert (status, stderr) == (
        1,
        f"{path}:7:5: error: <gazebo reference='a'>: {message} [gazebo-setting]\n",
    )


def test_every_refused_value_is_reported_at_once(tmp_path: Path) -> None:
    path = _robot(tmp_path, "<mu1>abc</mu1>\n    <mu2>-1</mu2>\n    <kinematic>yes</kinematic>")
    lines = [
        line.split(": ")[0] + " " + line.split("<")[2].split(">")[0] for line in _findings(path)
    ]
    assert lines == ["7:5 mu1", "8:5 mu2", "9:5 kinematic"]


def test_the_fixed_robot_is_clean(tmp_path: Path) -> None:
    assert _findings(_robot(tmp_path, FIXED)) == []
    assert _check(_robot(tmp_path, FIXED), "--select", "gazebo-setting") == (0, "")


def test_it_is_a_warning_when_gazebo_is_not_targeted(tmp_path: Path) -> None:
    path = _robot(tmp_path, "<mu1>abc</mu1>")
    status, stderr = _check(path, "--select", "gazebo-setting", "--target", "ros")
    assert status == 0
    assert stderr.startswith(f"{path}:7:5: warning: ")


def test_a_bound_is_held_only_where_the_converter_writes_the_value(tmp_path: Path) -> None:
    # with no collision, the converter writes <mu1> nowhere: ign takes the robot
    path = tmp_path / "r.urdf"
    path.write_text(
        ROBOT.format(setting="<mu1>-1</mu1>").replace(
            '    <collision><geometry><box size="1 1 1"/></geometry></collision>\n', ""
        ),
        encoding="utf-8",
    )
    assert _findings(path) == []


def test_a_value_in_an_included_file_is_placed_there(tmp_path: Path) -> None:
    (tmp_path / "friction.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <gazebo reference="a">\n'
        "    <kp>1e6</kp>\n"
        "      <mu1>abc</mu1>\n"
        "  </gazebo>\n"
        "</robot>\n",
        encoding="utf-8",
    )
    main = tmp_path / "robot.urdf.xacro"
    main.write_text(
        ROBOT.format(setting="<kinematic>yes</kinematic>")
        .replace(
            "</robot>",
            '  <xacro:include filename="friction.xacro"/>\n</robot>',
        )
        .replace(
            '<robot name="r">', '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        ),
        encoding="utf-8",
    )
    found = [
        (Path(d.path).name, d.line, d.column, d.severity)
        for d in check_file(main).diagnostics
        if d.rule == GAZEBO_SETTING.id
    ]
    assert found == [
        ("friction.xacro", 4, 7, Severity.ERROR),
        ("robot.urdf.xacro", 7, 5, Severity.ERROR),
    ]


@pytest.mark.parametrize(("setting", "message"), BAD, ids=[s for s, _ in BAD])
def test_ign_refuses_what_is_reported(tmp_path: Path, setting: str, message: str) -> None:
    ign = live_tool("ign", "ignition-tools libsdformat-dev")
    if ign is None:
        pytest.skip("ign is not installed")
    path = _robot(tmp_path, setting)
    run = subprocess.run(
        [ign, "sdf", "-p", str(path)], capture_output=True, timeout=120, check=False
    )
    assert run.returncode != 0
    said = run.stderr.decode("utf-8", "replace")
    if "crashes" in message:
        assert "std::invalid_argument" in said
    else:
        assert "Error reading element" in said
    fixed = subprocess.run(
        [ign, "sdf", "-p", str(_robot(tmp_path, FIXED, "fixed.urdf"))],
        capture_output=True,
        timeout=120,
        check=False,
    )
    assert fixed.returncode == 0, fixed.stderr


SDF_REFUSALS = [
    (
        "<mu1>abc</mu1>",
        "<gazebo reference='a'>: <mu1> is 'abc', not a number: sdformat's converter stops on it",
    ),
    ("<mu1>-1</mu1>", "<mu> '-1' is less than 0.0, its least: sdformat's reader refuses it"),
    ("<kinematic>yes</kinematic>", "<kinematic> 'yes' is no bool: sdformat's reader refuses it"),
]


@pytest.mark.parametrize(("setting", "message"), SDF_REFUSALS, ids=[s for s, _ in SDF_REFUSALS])
def test_fishbot_sdf_refuses_at_the_same_place(tmp_path: Path, setting: str, message: str) -> None:
    path = _robot(tmp_path, setting)
    result = CliRunner().invoke(cli, ["sdf", str(path), "-o", str(tmp_path / "r.sdf")])
    assert (result.exit_code, result.stderr) == (1, f"{path}:7:5: error: {message} [conversion]\n")
    assert not (tmp_path / "r.sdf").exists()


ARM = """\
<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="1 1 1"/></geometry></collision>
    <visual><geometry><box size="1 1 1"/></geometry></visual>
  </link>
  <link name="b">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  {block}
</robot>
"""
# (block, refused): what ign sdf -p crashes on or refuses, and what it takes
BLOCKS = [
    (
        '<gazebo reference="a"><collision><surface><friction><ode><mu>-2</mu></ode></friction>'
        "</surface></collision></gazebo>",
        True,
    ),
    ('<gazebo reference="a"><maxContacts>x</maxContacts></gazebo>', True),
    ('<gazebo reference="a"><fdir1>a b</fdir1></gazebo>', True),
    ('<gazebo reference="j"><stopErp>abc</stopErp></gazebo>', True),
    ("<gazebo><self_collide>yes</self_collide></gazebo>", True),
    (
        '<gazebo reference="a"><visual><material><ambient>2 0 0 1</ambient></material></visual>'
        "</gazebo>",
        True,
    ),
    (
        '<gazebo reference="a"><sensor name="s" type="camera"><pose>1 2 3</pose></sensor></gazebo>',
        True,
    ),
    ('<gazebo reference="a"><maxContacts>-3</maxContacts><kp>-3</kp></gazebo>', False),
    ('<gazebo reference="j"><stopErp>-1</stopErp><fudgeFactor>2</fudgeFactor></gazebo>', False),
    ("<gazebo><static>maybe</static></gazebo>", False),
    (
        '<gazebo reference="a"><material>x</material><turnGravityOff>maybe</turnGravityOff>'
        "<selfCollide>yes</selfCollide></gazebo>",
        False,
    ),
    ('<gazebo reference="nothing"><mu1>-1</mu1></gazebo>', False),
    (
        '<gazebo reference="a"><plugin name="p" filename="x.so"><foo>yes</foo></plugin></gazebo>',
        False,
    ),
]


@pytest.mark.parametrize(("block", "refused"), BLOCKS, ids=[b for b, _ in BLOCKS])
def test_a_finding_exactly_where_ign_refuses(tmp_path: Path, block: str, refused: bool) -> None:
    path = tmp_path / "arm.urdf"
    path.write_text(ARM.format(block=block), encoding="utf-8")
    assert len(_findings(path)) == refused
    ign = live_tool("ign", "ignition-tools libsdformat-dev")
    if ign is None:
        return
    run = subprocess.run(
        [ign, "sdf", "-p", str(path)], capture_output=True, timeout=120, check=False
    )
    assert (run.returncode != 0) == refused, run.stderr


def test_a_robot_without_one_root_is_left_to_the_structure_rules(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(
        '<robot name="r"><link name="a"/><link name="b"/>'
        '<gazebo reference="a"><mu1>abc</mu1></gazebo></robot>',
        encoding="utf-8",
    )
    rules = {d.rule for d in check_file(path).diagnostics}
    assert rules == {"multiple-roots"}
