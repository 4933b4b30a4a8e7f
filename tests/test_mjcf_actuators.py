"""`fishbot mjcf`'s actuators, from the robot's own description (its drive plugin's wheels, its
<ros2_control> command interfaces), and its friction from <gazebo reference> <mu1>: what
MuJoCo compiles of them, and what they do when MuJoCo runs them."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import mujoco
import numpy as np
import pytest
from conftest import FISHBOT

import fishbot_urdf
from fishbot_urdf.export.mjcf import to_mjcf

XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"


def _model(text: str, floor: bool = False) -> tuple[mujoco.MjModel, mujoco.MjData]:
    root = ET.fromstring(text)
    if floor:
        world = root.find("worldbody")
        assert world is not None
        world.insert(0, ET.Element("geom", type="plane", size="0 0 1", friction="0 0 0"))
    model = mujoco.MjModel.from_xml_string(ET.tostring(root, encoding="unicode"))
    return model, mujoco.MjData(model)


def test_the_fishbot_s_wheels_are_its_plugin_s_velocity_servos() -> None:
    model, _ = _model(to_mjcf(fishbot_urdf.load(XACRO)))
    names = [model.actuator(i).name for i in range(model.nu)]
    assert names == ["left_wheel_joint", "right_wheel_joint"]
    for name in names:
        actuator = model.actuator(name)
        assert model.joint(int(actuator.trnid[0])).name == name
        # <max_wheel_torque>30</max_wheel_torque> in plugins/gazebo_control_plugin.xacro
        assert list(actuator.forcerange) == [-30.0, 30.0]
        # a velocity servo: force = kv * (ctrl - qvel)
        kv = actuator.gainprm[0]
        assert kv > 0 and actuator.biasprm[2] == -kv


def test_the_fishbot_s_friction_is_its_gazebo_blocks() -> None:
    model, _ = _model(to_mjcf(fishbot_urdf.load(XACRO)))
    by_body: dict[str, list[float]] = {}
    for geom in range(model.ngeom):
        if model.geom_group[geom] == 3:  # collisions
            body = model.body(int(model.geom_bodyid[geom])).name
            by_body.setdefault(body, []).append(float(model.geom_friction[geom][0]))
    # <mu1>20.0</mu1> on the wheels, <mu1>0.0</mu1> on the casters, MuJoCo's 1 elsewhere
    assert by_body["left_wheel_link"] == by_body["right_wheel_link"] == [20.0]
    assert by_body["front_caster_link"] == by_body["back_caster_link"] == [0.0]
    assert by_body["base_link"] == [1.0]


def test_wheel_servos_drive_the_fishbot_at_radius_times_speed() -> None:
    # MuJoCo alone, on the file as written: the wheels at 0.2 / 0.032 rad/s roll it at 0.2 m/s
    model, data = _model(to_mjcf(fishbot_urdf.load(XACRO)), floor=True)
    data.qpos[2] = 0.002
    mujoco.mj_step(model, data, nstep=500)  # settle for 1 s
    start = data.qpos[:2].copy()
    data.ctrl[:] = 0.2 / 0.032
    mujoco.mj_step(model, data, nstep=500)  # 1 s to reach the speed
    start = data.qpos[:2].copy()
    mujoco.mj_step(model, data, nstep=1000)  # 2 s at it
    speed = float(np.linalg.norm(data.qpos[:2] - start)) / 2.0
    assert speed == pytest.approx(0.2, rel=0.01)


CONTROLLED = """\
<robot name="controlled">
  <link name="world"/>
  <link name="a"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="b"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="c"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="by_position" type="revolute"><parent link="world"/><child link="a"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="2"/></joint>
  <joint name="by_velocity" type="continuous"><parent link="world"/><child link="b"/>
    <axis xyz="0 0 1"/><limit effort="3" velocity="4"/></joint>
  <joint name="by_effort" type="revolute"><parent link="world"/><child link="c"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="2" velocity="2"/></joint>
  <ros2_control name="arm" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="by_position"><command_interface name="position"/>
      <state_interface name="position"/></joint>
    <joint name="by_velocity"><command_interface name="velocity"/>
      <state_interface name="velocity"/></joint>
    <joint name="by_effort"><command_interface name="effort"/></joint>
  </ros2_control>
</robot>
"""


def test_ros2_control_interfaces_become_servos_and_motors() -> None:
    model, data = _model(to_mjcf(fishbot_urdf.parse(CONTROLLED)))
    position, velocity, effort = (
        model.actuator(n) for n in ("by_position", "by_velocity", "by_effort")
    )
    # each limited to its joint's <limit effort>
    assert list(position.forcerange) == [-5.0, 5.0]
    assert list(velocity.forcerange) == [-3.0, 3.0]
    assert list(effort.ctrlrange) == [-2.0, 2.0]
    assert list(position.ctrlrange) == [-1.0, 1.0]  # the joint's limits
    assert list(velocity.ctrlrange) == [-4.0, 4.0]  # its <limit velocity>
    # what they do: the position servo takes its joint to 0.5 rad, the velocity servo
    # turns its joint at 2 rad/s, the motor's 2 N*m turn a body of 0.01 kg*m^2 at 200 rad/s^2
    data.ctrl[:] = [0.5, 2.0, 2.0]
    mujoco.mj_step(model, data, nstep=1000)
    assert data.joint("by_position").qpos[0] == pytest.approx(0.5, abs=1e-3)
    assert data.joint("by_velocity").qvel[0] == pytest.approx(2.0, rel=1e-3)
    mujoco.mj_resetData(model, data)
    data.ctrl[:] = [0.0, 0.0, 2.0]
    mujoco.mj_step(model, data)
    assert data.joint("by_effort").qacc[0] == pytest.approx(2.0 / 0.01, rel=1e-6)


@pytest.mark.parametrize(
    ("plugin", "torque"),
    [
        # Gazebo Classic's plugin takes 5 N*m when <max_wheel_torque> is not written
        ('<plugin name="d" filename="libgazebo_ros_diff_drive.so">', 5.0),
        # gz-sim's DiffDrive has no torque limit
        ('<plugin name="gz::sim::systems::DiffDrive" filename="gz-sim-diff-drive-system">', None),
    ],
)
def test_a_plugin_s_default_torque(plugin: str, torque: float | None) -> None:
    robot = f"""\
<robot name="r">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="l"><inertial><mass value="0.1"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
  <link name="r"><inertial><mass value="0.1"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
  <joint name="lj" type="continuous"><parent link="base"/><child link="l"/>
    <origin xyz="0 0.1 0"/><axis xyz="0 1 0"/></joint>
  <joint name="rj" type="continuous"><parent link="base"/><child link="r"/>
    <origin xyz="0 -0.1 0"/><axis xyz="0 1 0"/></joint>
  <gazebo>{plugin}<left_joint>lj</left_joint><right_joint>rj</right_joint></plugin></gazebo>
</robot>
"""
    model, _ = _model(to_mjcf(fishbot_urdf.parse(robot)))
    assert model.nu == 2
    for index in range(2):
        limited = bool(model.actuator_forcelimited[index])
        assert limited == (torque is not None)
        if torque is not None:
            assert list(model.actuator_forcerange[index]) == [-torque, torque]
    assert not math.isnan(float(model.actuator_gainprm[0][0]))
