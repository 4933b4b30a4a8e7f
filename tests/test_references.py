"""The reference rules: names that Gazebo, transmission and ros2_control elements, Gazebo's
plugins and visuals' materials give to the robot's parts."""

from __future__ import annotations

from pathlib import Path

import fishbot_urdf
from fishbot_urdf import check_file
from fishbot_urdf.extensions import Target, from_robot, plugin_target

ARM = """\
<robot name="arm">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="camera_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="camera_joint" type="fixed">
    <parent link="base_link"/><child link="camera_link"/>
  </joint>
{extra}
</robot>
"""


def _found(tmp_path: Path, extra: str, name: str = "robot.urdf") -> list[tuple[str, int, str]]:
    path = tmp_path / name
    path.write_text(ARM.format(extra=extra), encoding="utf-8")
    return [(d.rule, d.line or 0, d.format()) for d in check_file(path).diagnostics]


def test_a_gazebo_reference_is_located_at_its_attribute_and_suggests_the_name(
    tmp_path: Path,
) -> None:
    found = _found(tmp_path, '  <gazebo reference="left_wheel_lnk"><mu1>0.9</mu1></gazebo>')
    path = tmp_path / "robot.urdf"
    assert [f[2] for f in found] == [
        f"{path}:11:11: error: <gazebo reference> names link or joint 'left_wheel_lnk', which "
        "the robot does not have: Gazebo's converter drops the block without a word (did you "
        "mean 'left_wheel_link'?) [unknown-reference]"
    ]


def test_a_gazebo_reference_may_name_a_joint_and_a_gazebo_block_may_name_nothing(
    tmp_path: Path,
) -> None:
    extra = '<gazebo reference="left_wheel_joint"/><gazebo><static>false</static></gazebo>'
    assert _found(tmp_path, extra) == []


def test_transmission_and_ros2_control_joints_must_exist(tmp_path: Path) -> None:
    extra = """\
  <transmission name="t"><joint name="left_whel_joint"/></transmission>
  <ros2_control name="c" type="system">
    <joint name="rigth_wheel_joint"><command_interface name="velocity"/></joint>
  </ros2_control>"""
    found = _found(tmp_path, extra)
    assert [(rule, line) for rule, line, _ in found] == [
        ("unknown-reference", 11),
        ("unknown-reference", 13),
    ]
    assert "<transmission> joint names joint 'left_whel_joint'" in found[0][2]
    # The robot has no right wheel: its left one is no misspelling of it, but listed first.
    assert found[1][2].endswith("(joints: left_wheel_joint, camera_joint) [unknown-reference]")


def test_ros2_control_refuses_fixed_joints_and_misspelt_interfaces(tmp_path: Path) -> None:
    extra = """\
  <ros2_control name="c" type="system">
    <joint name="camera_joint"><state_interface name="position"/></joint>
    <joint name="left_wheel_joint">
      <command_interface name="velocty"/>
      <state_interface name="position"/>
      <state_interface name="temperature"/>
    </joint>
  </ros2_control>"""
    found = _found(tmp_path, extra)
    assert [(rule, line) for rule, line, _ in found] == [
        ("control-interface", 12),
        ("control-interface", 14),
    ]
    assert "'camera_joint' is a fixed joint" in found[0][2]
    assert (
        "command interface 'velocty' is not a standard one (did you mean 'velocity'?"
        in (found[1][2])
    )


def test_plugin_joints_and_frames_ros1_and_ros2_spellings(tmp_path: Path) -> None:
    extra = """\
  <gazebo><plugin name="drive" filename="libgazebo_ros_diff_drive.so">
    <left_joint>left_wheel_joint</left_joint><right_joint>right_wheel_joint</right_joint>
    <robot_base_frame>base_link</robot_base_frame><odometry_frame>odom</odometry_frame>
  </plugin></gazebo>
  <gazebo reference="camera_link"><sensor type="camera" name="c">
    <plugin name="cam" filename="libgazebo_ros_camera.so"><frameName>/camera_lnk</frameName>
    </plugin></sensor></gazebo>
  <gazebo><plugin name="p3d" filename="libgazebo_ros_p3d.so">
    <bodyName>base_link</bodyName><frameName>world</frameName>
    <jointName>left_wheel_joint, camera_joint, ghost_joint</jointName>
  </plugin></gazebo>"""
    found = _found(tmp_path, extra)
    messages = [message.split(": error: ", 1)[1] for _, _, message in found]
    assert [line for _, line, _ in found] == [12, 16, 20]
    assert messages == [
        "plugin <right_joint> names joint 'right_wheel_joint', which the robot does not have "
        "(joints: left_wheel_joint, camera_joint) [unknown-reference]",
        "plugin <frameName> names link 'camera_lnk', which the robot does not have "
        "(did you mean 'camera_link'?) [unknown-reference]",
        "plugin <jointName> names joint 'ghost_joint', which the robot does not have "
        "(joints: camera_joint, left_wheel_joint) [unknown-reference]",
    ]


def test_a_reference_written_in_a_xacro_macro_points_at_the_xacro_line(tmp_path: Path) -> None:
    (tmp_path / "robot.urdf.xacro").write_text(
        """\
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="friction" params="link">
    <gazebo reference="${link}">
      <mu1>0.9</mu1>
    </gazebo>
  </xacro:macro>
  <link name="base_link"/>
  <xacro:friction link="base_lnk"/>
</robot>
""",
        encoding="utf-8",
    )
    result = check_file(tmp_path / "robot.urdf.xacro")
    assert [(d.rule, d.path, d.line) for d in result.diagnostics] == [
        ("unknown-reference", str(tmp_path / "robot.urdf.xacro"), 3)
    ]


def test_a_robot_built_in_code_has_its_references_read_from_its_extras() -> None:
    robot = fishbot_urdf.Robot(
        "r",
        links=(fishbot_urdf.Link("a"),),
        extras=('<gazebo reference="b"/>', '<transmission><joint name="j"/></transmission>'),
    )
    assert [(r.name, r.target) for r in from_robot(robot)] == [
        ("b", Target.LINK_OR_JOINT),
        ("j", Target.JOINT),
    ]
    findings = fishbot_urdf.check(robot)
    assert [(d.rule, d.line) for d in findings] == [
        ("unknown-reference", None),
        ("unknown-reference", None),
    ]


MATERIALS = """\
<robot name="r">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="a">
    <visual><geometry><box size="1 1 1"/></geometry><material name="blu"/></visual>
    <visual><geometry><box size="1 1 1"/></geometry><material name="blue"/></visual>
    <visual><geometry><box size="1 1 1"/></geometry>
      <material name="blue"><color rgba="0 0 0.8 1"/></material></visual>
    <visual><geometry><box size="1 1 1"/></geometry>
      <material name="blue"><color rgba="0 0 1 1"/></material></visual>
  </link>
</robot>
"""


def test_materials_undefined_and_given_two_colours(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(MATERIALS, encoding="utf-8")
    found = check_file(path).diagnostics
    assert [(d.rule, d.line, d.severity.value) for d in found] == [
        ("undefined-material", 4, "warning"),
        ("material-conflict", 7, "warning"),
    ]
    assert "material 'blu' is not defined (did you mean 'blue'? " in found[0].format()
    assert (
        f"material 'blue' is given rgba 0 0 0.8 1 here, but rgba 0 0 1 1 at {path}:2 "
        "(urdfdom (RViz) uses the first" in found[1].format()
    )


def test_a_material_first_defined_in_a_visual_is_shared_by_later_ones(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(
        MATERIALS.replace('  <material name="blue"><color rgba="0 0 1 1"/></material>\n', "")
        .replace(
            '<material name="blu"/>', '<material name="blue"><color rgba="0 0 1 1"/></material>'
        )
        .replace('<color rgba="0 0 0.8 1"/>', '<color rgba="0 0 1 1"/>'),
        encoding="utf-8",
    )
    assert check_file(path).diagnostics == ()


def test_what_a_plugin_element_names() -> None:
    assert plugin_target("left_joint") is Target.JOINT
    assert plugin_target("jointName") is Target.JOINT
    assert plugin_target("robotBaseFrame") is Target.LINK
    assert plugin_target("frame_name") is Target.LINK
    assert plugin_target("update_rate") is None
