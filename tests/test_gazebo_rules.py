"""The gazebo rules on a fishbot with Gazebo blocks, as the ROS 2 and ROS 1 notes write it:
right as it is, and with each fault set by one of its xacro arguments."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import DATA

from fishbot_urdf import check_file
from fishbot_urdf.catalog import get
from fishbot_urdf.cli import cli
from fishbot_urdf.diagnostics import shown_path
from fishbot_urdf.packages import ros_version

ROS2 = DATA / "gazebo" / "fishbot_description"
ROS1 = DATA / "gazebo" / "fishbot_ros1"
ROBOT = ROS2 / "urdf" / "fishbot.urdf.xacro"
ROBOT1 = ROS1 / "urdf" / "fishbot.urdf.xacro"
TREE = """\
robot name is: fishbot
---------- Successfully Parsed XML ---------------
root Link: base_footprint has 1 child(ren)
    child(1):  base_link
        child(1):  camera_link
        child(2):  laser_link
        child(3):  left_wheel_link
        child(4):  right_wheel_link
"""


def _check(path: Path, *args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["check", "--isolated", str(path), *args])
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize("robot", [ROBOT, ROBOT1], ids=["ros2", "ros1"])
def test_the_right_robot_has_no_finding(robot: Path) -> None:
    assert _check(robot) == (0, TREE, "")


FAULTS = [
    (
        ["separation:=0.34"],
        "86:9: error: plugin 'diff_drive' (libgazebo_ros_diff_drive.so): <wheel_separation> is "
        "0.34 m, but joints 'left_wheel_joint' and 'right_wheel_joint' are 0.2 m apart along "
        "the axle (write <wheel_separation>0.2</wheel_separation>) [diff-drive-size]",
    ),
    (
        ["diameter:=0.032"],
        "87:9: error: plugin 'diff_drive' (libgazebo_ros_diff_drive.so): <wheel_diameter> is "
        "0.032 m, the radius of wheel 'left_wheel_link''s collision cylinder (radius 0.032 m) "
        "(write <wheel_diameter>0.064</wheel_diameter>) [diff-drive-size]",
    ),
    (
        ["diameter:=0.07"],
        "87:9: error: plugin 'diff_drive' (libgazebo_ros_diff_drive.so): <wheel_diameter> is "
        "0.07 m, but wheel 'left_wheel_link''s collision cylinder has radius 0.032 m (write "
        "<wheel_diameter>0.064</wheel_diameter>) [diff-drive-size]",
    ),
    (
        ["left_joint:=right_wheel_joint", "right_joint:=left_wheel_joint"],
        "84:9: error: plugin 'diff_drive' (libgazebo_ros_diff_drive.so): left wheel joint "
        "'right_wheel_joint' is on the robot's right (y -0.1 m in the base frame) and right wheel "
        "joint 'left_wheel_joint' on its left (y 0.1 m): left and right are swapped, so the robot "
        "turns the other way from what it is told, and so does its odometry (name the wheels' "
        "continuous joints, turning about the axle, left as the wheel on +y) "
        "[diff-drive-wheels]",
    ),
    (
        ["left_joint:=base_joint"],
        "84:9: error: plugin 'diff_drive' (libgazebo_ros_diff_drive.so): wheel joint 'base_joint' "
        "is a fixed joint, which does not turn (name the wheels' continuous joints, turning about "
        "the axle, left as the wheel on +y) [diff-drive-wheels]",
    ),
    (
        ["laser_plugin:=libgazebo_ros_laser.so"],
        "119:7: error: plugin 'libgazebo_ros_laser.so' is ROS 1's; this robot is for ROS 2, which "
        "has no such file (use libgazebo_ros_ray_sensor.so) [plugin-ros-version]",
    ),
    (
        ["depth_plugin:=libgazebo_ros_openni_kinect.so"],
        "145:7: error: plugin 'libgazebo_ros_openni_kinect.so' is ROS 1's; this robot is for ROS "
        "2, which has no such file (use libgazebo_ros_camera.so on a depth sensor) "
        "[plugin-ros-version]",
    ),
    (
        ["laser_z:=0.03"],
        "108:3: warning: sensor 'laser' (ray) on 'laser_link' starts inside link 'base_link''s "
        "collision shape, and its rays leave it only after 0.15 m, but its minimum range is "
        "0.12 m: rays that start inside hit the shape, and the scan sees the robot itself (raise "
        "the sensor out of the shape, or set <min> to 0.15 or more) "
        "[sensor-self-hit]",
    ),
    (
        ["range_min:=9"],
        "108:3: error: sensor 'laser' (ray): <range> minimum 9 m is not below its maximum 8 m "
        "(write the minimum below the maximum (metres)) [sensor-settings]",
    ),
    (
        ["samples:=0"],
        "108:3: error: sensor 'laser' (ray): scan <samples> is 0 (a scan has at least 1 sample) "
        "[sensor-settings]",
    ),
    (
        ["fov:=80"],
        "126:3: error: sensor 'camera' (camera): <horizontal_fov> is 80, outside (0, pi) radians "
        "(write it in radians (80 degrees is 1.3963)) [sensor-settings]\n"
        # past 2 pi, sdformat's reader (ign sdf -p) refuses the whole robot
        f"{shown_path(str(ROBOT))}:130:9: error: <gazebo reference='camera_link'>: "
        "<horizontal_fov> '80' is more than 6.283186, its most: sdformat's reader refuses the "
        "robot, so Gazebo cannot load it (write a number from 0.1 to 6.283186) [gazebo-setting]",
    ),
    (
        ["width:=0"],
        "126:3: error: sensor 'camera' (camera): image <width> is 0 (an image is at least 1 "
        "pixel each way) [sensor-settings]",
    ),
    (
        ["sim:=gz", "--select", "diff-drive-size"],
        "101:9: error: plugin 'gz::sim::systems::DiffDrive' (gz-sim-diff-drive-system): "
        "<wheel_radius> is 0.064 m, the diameter of wheel 'left_wheel_link''s collision cylinder "
        "(radius 0.032 m) (write <wheel_radius>0.032</wheel_radius>) [diff-drive-size]",
    ),
    (
        ["sim:=gz", "diameter:=0.032", "--select", "plugin-simulator"],
        "97:7: error: plugin 'gz-sim-diff-drive-system' is the new Gazebo (gz-sim)'s, but this "
        "robot's other plugins (libgazebo_ros_camera.so, libgazebo_ros_ray_sensor.so) are for "
        "Gazebo Classic (use Gazebo Classic's plugin for it, or move the whole robot to the new "
        "Gazebo (gz-sim)) [plugin-simulator]",
    ),
]


@pytest.mark.parametrize(("args", "line"), FAULTS, ids=[" ".join(a) for a, _ in FAULTS])
def test_each_fault_is_one_finding_on_stderr_and_the_tree_stays(args: list[str], line: str) -> None:
    status = 0 if "warning:" in line else 1
    assert _check(ROBOT, *args) == (status, TREE, f"{shown_path(str(ROBOT))}:{line}\n")


def test_a_sensor_on_a_joint_is_found_once_for_each_sensor() -> None:
    status, out, err = _check(ROBOT, "camera_reference:=camera_joint")
    assert (status, out) == (1, TREE)
    assert [line.split(" [")[-1] for line in err.splitlines()] == ["sensor-reference]"] * 2
    assert "which names a joint, not a link (write <gazebo reference='camera_link'>)" in err


def test_a_sensor_on_nothing_is_unknown_reference_s_alone() -> None:
    status, _, err = _check(ROBOT, "camera_reference:=camera_lnk")
    assert status == 1
    assert [line.rsplit(" ", 1)[-1] for line in err.splitlines()] == ["[unknown-reference]"]


def test_ros1_plugins_in_a_catkin_package_are_right() -> None:
    assert ros_version(ROS1 / "package.xml") == 1
    assert ros_version(ROS2 / "package.xml") == 2
    assert _check(ROBOT1, "diameter:=0.032")[2] == (
        f"{shown_path(str(ROBOT1))}:87:7: error: plugin 'differential_drive_controller' "
        "(libgazebo_ros_diff_drive.so): <wheelDiameter> is 0.032 m, the radius of wheel "
        "'left_wheel_link''s collision cylinder (radius 0.032 m) (write "
        "<wheelDiameter>0.064</wheelDiameter>) [diff-drive-size]\n"
    )


def test_the_ros1_robot_in_an_ament_package_is_told_each_ros1_plugin(tmp_path: Path) -> None:
    (tmp_path / "urdf").mkdir()
    shutil.copy(ROS2 / "package.xml", tmp_path / "package.xml")
    shutil.copy(ROBOT1, tmp_path / "urdf" / "fishbot.urdf.xacro")
    result = check_file(tmp_path / "urdf" / "fishbot.urdf.xacro")
    found = [(d.rule, d.line) for d in result.diagnostics]
    assert found == [("plugin-ros-version", line) for line in (80, 106, 120)]
    messages = [d.message for d in result.diagnostics]
    assert "<leftJoint>" in messages[0] and "libgazebo_ros_ray_sensor.so" in (
        result.diagnostics[1].hint or ""
    )


WHEELS = """\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel"/>
  <link name="right_wheel"/>
  <joint name="left_wheel_joint" type="continuous"><origin xyz="0 0.1 0"/><axis xyz="{axis}"/>
    <parent link="base_link"/><child link="left_wheel"/></joint>
  <joint name="right_wheel_joint" type="continuous"><origin xyz="0 -0.1 0"/><axis xyz="0 1 0"/>
    <parent link="base_link"/><child link="right_wheel"/></joint>
  <gazebo><plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
    <left_joint>left_wheel_joint</left_joint><right_joint>right_wheel_joint</right_joint>
    <wheel_separation>0.2</wheel_separation>{extra}
  </plugin></gazebo>
</robot>
"""


def test_a_wheel_that_turns_about_another_axis_than_the_axle(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(WHEELS.format(axis="0 0 1", extra=""), encoding="utf-8")
    found = [(d.rule, d.message) for d in check_file(path).diagnostics]
    assert found == [
        (
            "diff-drive-wheels",
            "plugin 'diff_drive' (libgazebo_ros_diff_drive.so): wheel joint 'left_wheel_joint' "
            "turns about 0 0 1 in the base frame, not about the axle between the wheels",
        )
    ]


def test_a_left_out_wheel_diameter_is_the_default_held_to_the_robot(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    text = WHEELS.format(axis="0 1 0", extra="").replace("0.2</wheel_sep", "0.3</wheel_sep")
    path.write_text(text.replace("<wheel_separation>0.3</wheel_separation>", ""), "utf-8")
    found = [d.message for d in check_file(path).diagnostics]
    assert found == [
        "plugin 'diff_drive' (libgazebo_ros_diff_drive.so): <wheel_separation> is not written "
        "(the default is 0.34 m), but joints 'left_wheel_joint' and 'right_wheel_joint' are "
        "0.2 m apart along the axle"
    ]


def test_the_rules_can_be_turned_off() -> None:
    assert _check(ROBOT, "separation:=0.34", "--ignore", "gazebo") == (0, TREE, "")


@pytest.mark.parametrize(
    ("manifest", "version"),
    [
        (
            "<package format='3'><name>a</name><export><build_type>ament_python</build_type>"
            "</export></package>",
            2,
        ),
        (
            "<package format='2'><name>a</name><buildtool_depend>catkin</buildtool_depend>"
            "</package>",
            1,
        ),
        ("<package format='3'><name>a</name></package>", None),
        ("<package", None),
    ],
)
def test_the_ros_a_package_xml_builds_with(
    tmp_path: Path, manifest: str, version: int | None
) -> None:
    (tmp_path / "package.xml").write_text(manifest, encoding="utf-8")
    assert ros_version(tmp_path / "package.xml") == version


def test_a_gpu_lidar_inside_the_robot_is_not_judged(tmp_path: Path) -> None:
    # it renders the visuals: the collision shapes it starts in are not in its way
    bad = get("sensor-self-hit").bad
    path = tmp_path / "robot.urdf"
    path.write_text(bad.replace('type="ray">', 'type="gpu_ray">'), encoding="utf-8")
    assert check_file(path).diagnostics == ()
    path.write_text(bad, encoding="utf-8")
    assert [d.rule for d in check_file(path).diagnostics] == ["sensor-self-hit"]


MIXED = """\
<robot name="fishbot">
  <link name="base_link"/>
  <ros2_control name="fishbot" type="system">
    <hardware><plugin>{hardware}</plugin></hardware>
  </ros2_control>
  <gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/></gazebo>
</robot>
"""


@pytest.mark.parametrize(
    ("hardware", "found"),
    [
        ("gazebo_ros2_control/GazeboSystem", []),
        ("gz_ros2_control/GazeboSimSystem", ["libgazebo_ros2_control.so"]),
    ],
)
def test_ros2_control_s_hardware_plugin_says_which_gazebo(
    tmp_path: Path, hardware: str, found: list[str]
) -> None:
    # one of each kind: the one that comes second is the odd one out
    path = tmp_path / "robot.urdf"
    path.write_text(MIXED.format(hardware=hardware), encoding="utf-8")
    result = check_file(path).diagnostics
    assert [d.rule for d in result] == ["plugin-simulator"] * len(found)
    assert [d.message.split("'")[1] for d in result] == found
