"""`fishbot tf`: one frame in another, as tf2_echo prints it, with joint positions."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import FISHBOT

import fishbot_urdf
from fishbot_urdf.cli import cli

XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"


def _tf(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["tf", *args])
    return result.exit_code, result.stdout, result.stderr


def test_the_output_is_tf2_echos() -> None:
    code, out, err = _tf(str(XACRO), "base_link", "left_wheel_link", "-j", "left_wheel_joint=90deg")
    assert (code, err) == (0, "")
    # fishbot.urdf.xacro puts the left wheel joint at (0, wheel_y, wheel_z) = (0, 0.10,
    # -0.06) with its axis along y; 90 degrees about y takes x to -z and z to x, the
    # quaternion (0, sin 45, 0, cos 45).
    assert out == (
        "At time 0.0\n"
        "- Translation: [0.000, 0.100, -0.060]\n"
        "- Rotation: in Quaternion (xyzw) [0.000, 0.707, 0.000, 0.707]\n"
        "- Rotation: in RPY (radian) [0.000, 1.571, 0.000]\n"
        "- Rotation: in RPY (degree) [0.000, 90.000, 0.000]\n"
        "- Matrix:\n"
        "  0.000  0.000  1.000  0.000\n"
        "  0.000  1.000  0.000  0.100\n"
        " -1.000  0.000  0.000 -0.060\n"
        "  0.000  0.000  0.000  1.000\n"
    )


def test_json_has_the_numbers_of_the_plain_poses() -> None:
    code, out, _ = _tf(
        str(XACRO),
        "laser_link",
        "right_wheel_link",
        "-j",
        "right_wheel_joint=0.3",
        "--format",
        "json",
    )
    assert code == 0
    report = json.loads(out)
    robot = fishbot_urdf.load(XACRO)
    poses = fishbot_urdf.link_poses(robot, {"right_wheel_joint": 0.3})
    expected = poses["laser_link"].inverse().then(poses["right_wheel_link"])
    np.testing.assert_allclose(report["matrix"], expected.matrix(), atol=1e-15)
    assert report["from"] == "laser_link" and report["positions"] == {"right_wheel_joint": 0.3}
    x, y, z, w = report["quaternion_xyzw"]
    assert x * x + y * y + z * z + w * w == pytest.approx(1.0)
    roll, pitch, yaw = report["rpy"]
    rebuilt = fishbot_urdf.spatial.rpy_matrix((roll, pitch, yaw))
    np.testing.assert_allclose(np.array(rebuilt), np.array(report["matrix"])[:3, :3], atol=1e-12)
    assert report["rpy_degrees"] == pytest.approx([math.degrees(a) for a in report["rpy"]])


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (("base_lnk", "laser_link"), "no link 'base_lnk' (did you mean 'base_link'?"),
        (
            ("base_link", "laser_link", "-j", "left_whel_joint=1"),
            "did you mean 'left_wheel_joint'?",
        ),
        (("base_link", "laser_link", "-j", "left_wheel_joint=x"), "is not NAME=VALUE"),
    ],
)
def test_wrong_frames_and_joints_are_one_line_and_exit_2(args: tuple[str, ...], said: str) -> None:
    code, out, err = _tf(str(XACRO), *args)
    assert (code, out) == (2, "")
    assert said in err


def test_a_position_outside_the_limits_and_a_broken_robot(tmp_path: Path) -> None:
    arm = tmp_path / "arm.urdf"
    arm.write_text(
        '<robot name="arm"><link name="a"/><link name="b"/>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>'
    )
    code, _, err = _tf(str(arm), "a", "b", "-j", "j=2")
    assert code == 2
    assert "joint 'j': position 2 is outside its limits -1 .. 1" in err
    broken = tmp_path / "broken.urdf"
    broken.write_text(
        '<robot name="r"><link name="a"/><joint name="j" type="fixed">'
        '<parent link="a"/><child link="b"/></joint></robot>'
    )
    code, out, err = _tf(str(broken), "a", "b")
    assert (code, out) == (1, "")
    assert "[undefined-link]" in err


def test_a_joint_without_a_position_of_its_own_is_named_for_what_it_is(tmp_path: Path) -> None:
    # imu_joint is one of the fishbot's fixed joints: there is a joint of that name.
    code, out, err = _tf(str(XACRO), "base_link", "imu_link", "-j", "imu_joint=1")
    assert (code, out) == (2, "")
    assert (
        "joint 'imu_joint' is fixed: it takes no position "
        "(moving joints: left_wheel_joint, right_wheel_joint)"
    ) in err
    assert "no joint" not in err
    robot = tmp_path / "gripper.urdf"
    robot.write_text(
        '<robot name="g"><link name="world"/><link name="base"/><link name="a"/><link name="b"/>'
        '<joint name="slide" type="planar"><parent link="world"/><child link="base"/></joint>'
        '<joint name="left" type="prismatic"><parent link="base"/><child link="a"/>'
        '<limit lower="0" upper="0.1" effort="1" velocity="1"/></joint>'
        '<joint name="right" type="prismatic"><parent link="base"/><child link="b"/>'
        '<limit lower="0" upper="0.1" effort="1" velocity="1"/><mimic joint="left"/></joint>'
        "</robot>"
    )
    code, _, err = _tf(str(robot), "a", "b", "-j", "right=0.05")
    assert code == 2
    assert "joint 'right' mimics 'left' and follows it: set 'left' instead" in err
    code, _, err = _tf(str(robot), "a", "b", "-j", "slide=0.05")
    assert code == 2
    assert "joint 'slide' is planar: its position is slide.x, slide.y and slide.yaw" in err
    assert _tf(str(robot), "world", "b", "-j", "slide.x=1", "-j", "left=0.05")[0] == 0


WHEEL = """\
<robot name="r">
  <link name="base_link"/>
  <link name="wheel">
    <visual><geometry><cylinder radius="0.032" length="0.04"/></geometry></visual>
    <inertial>{inertial}</inertial>
  </link>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel"/><origin xyz="0 0.1 0"/><axis xyz="0 1 0"/>
  </joint>
</robot>
"""
INERTIA = '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'


@pytest.mark.parametrize(
    ("inertial", "rule"),
    [
        ('<mass value="0.1"/>', "missing-element"),  # no <inertia>
        ("<mass/>" + INERTIA, "missing-attribute"),
        ('<mass value="1kg"/>' + INERTIA, "bad-number"),
        ('<mass value="-1"/>' + INERTIA, "negative-mass"),
        ('<origin xyz="0 0"/><mass value="1"/>' + INERTIA, "bad-vector"),
    ],
)
def test_a_fault_of_the_inertial_alone_is_printed_and_tf_answers(
    tmp_path: Path, inertial: str, rule: str
) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(WHEEL.format(inertial=inertial))
    # pinocchio loads each of them (the frames do not depend on the inertial) and places
    # the wheel where the joint's origin says.
    pin = pytest.importorskip("pinocchio")
    model = pin.buildModelFromUrdf(str(robot))
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    placed = data.oMf[model.getFrameId("wheel")].translation
    code, out, err = _tf(str(robot), "base_link", "wheel", "--format", "json")
    assert code == 0, err
    assert json.loads(out)["translation"] == list(placed) == [0.0, 0.1, 0.0]
    (line,) = err.splitlines()
    # (a negative mass harms the simulators alone: for the ROS tools, a warning)
    level = "warning" if rule == "negative-mass" else "error"
    assert f": {level}: link 'wheel': " in line and line.endswith(f"[{rule}]")
    # the shape in doubt still stops it: a joint's origin
    broken = tmp_path / "broken.urdf"
    broken.write_text(robot.read_text().replace('xyz="0 0.1 0"', 'xyz="0 0.1"'))
    code, out, err = _tf(str(broken), "base_link", "wheel")
    assert (code, out) == (1, "")
    assert "[bad-vector]" in err


def test_a_xacro_argument_named_as_a_joint_says_how_to_place_the_joint() -> None:
    code, out, err = _tf(str(XACRO), "base_link", "left_wheel_link", "left_wheel_joint:=1.0")
    assert code == 0
    assert out.startswith("At time 0.0\n- Translation: [0.000, 0.100, -0.060]\n")
    assert err == (
        f"{XACRO}: warning: argument 'left_wheel_joint' is given, but no <xacro:arg> declares "
        "it and nothing reads it ('left_wheel_joint' is a joint: did you mean "
        "`-j left_wheel_joint=1.0`?) [xacro-unknown-arg]\n"
    )
    # Any other argument no file reads is the warning check and expand give.
    code, _, err = _tf(str(XACRO), "base_link", "left_wheel_link", "use_sim:=true")
    checked = CliRunner().invoke(cli, ["check", "-q", str(XACRO), "use_sim:=true"])
    assert (code, checked.exit_code) == (0, 0)
    assert err == checked.stderr != ""
    # A URDF file takes no arguments at all: each is a warning, a joint's name with a word
    # on placing joints.
    urdf = FISHBOT / "urdf" / "first_robot.urdf"
    code, _, err = _tf(str(urdf), "base_link", "imu_link", "imu_joint:=1", "use_sim:=true")
    assert code == 0
    assert err == (
        f"{urdf}: warning: argument 'imu_joint' is given, but a URDF file takes no arguments "
        "('imu_joint' is a fixed joint, which takes no position) [xacro-unknown-arg]\n"
        f"{urdf}: warning: argument 'use_sim' is given, but a URDF file takes no arguments "
        "(name:=value is for a .xacro file: it was not used) [xacro-unknown-arg]\n"
    )
