"""The rules on joints: axes, limits, angles and mimics.

Data only: the checks that report them are in `fishbot_urdf.rules`.
"""

from __future__ import annotations

from ..diagnostics import Consumer, Family, Rule, Severity

W = Severity.WARNING
_ALL = (Consumer.URDFDOM, Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
_WHEEL = """\
<robot name="fishbot">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="wheel_link">
    <collision><origin rpy="1.5708 0 0"/>
      <geometry><cylinder radius="0.03" length="0.02"/></geometry>
    </collision>
    <inertial><mass value="0.1"/>
      <inertia ixx="2.583e-5" iyy="4.5e-5" izz="2.583e-5" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="wheel_joint" type="continuous"><axis xyz="{axis}"/>
    <parent link="base_link"/><child link="wheel_link"/></joint>
</robot>
"""
_ARM = """\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="arm_link"/>
  <joint name="arm_joint" type="{type}">
    <origin xyz="0 0 0.1" rpy="{rpy}"/>
    <parent link="base_link"/><child link="arm_link"/><axis xyz="{axis}"/>
    <limit lower="{lower}" upper="{upper}" effort="{effort}" velocity="{velocity}"/>
  </joint>
</robot>
"""
_GOOD_ARM = {
    "type": "revolute",
    "rpy": "0 0 1.5708",
    "axis": "0 0 1",
    "lower": "-1.5708",
    "upper": "1.5708",
    "effort": "10",
    "velocity": "3.14",
}


def _arm(**changes: str) -> str:
    return _ARM.format(**{**_GOOD_ARM, **changes})


WHEEL_AXIS = Rule(
    "wheel-axis",
    W,
    Family.JOINTS,
    summary="A wheel's continuous joint turns about another axis than its cylinder's.",
    explanation="A continuous joint whose child collides as one flat cylinder is a wheel, and a "
    "wheel turns about its cylinder's axis. A cylinder lies along its own z axis, so a wheel "
    'turned on its side with `rpy="1.5708 0 0"` rolls about y; with the joint\'s axis left at '
    "`0 0 1` it spins like a turntable and the robot does not drive. Set the joint's `<axis>` to "
    "the cylinder's axis in the wheel link's frame.",
    bad=_WHEEL.format(axis="0 0 1"),
    good=_WHEEL.format(axis="0 1 0"),
    consumers=(Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET),
)
AXIS_LENGTH = Rule(
    "axis-length",
    W,
    Family.JOINTS,
    summary="A moving joint's axis is not of length 1.",
    explanation="URDF expects a unit axis. urdfdom and KDL keep what is written, and what each "
    "program does with a longer or shorter axis differs: some normalise it, some scale the "
    "joint's motion or its Jacobian by its length. Write the unit vector (`0 1 0`, or "
    "`0 0.7071 0.7071` for a diagonal).",
    bad=_arm(axis="0 0 2"),
    good=_arm(),
    consumers=_ALL,
)
WIDE_LIMIT = Rule(
    "wide-limit",
    W,
    Family.JOINTS,
    summary="A revolute joint's limits reach past two whole turns (4 pi), as degrees would.",
    explanation="Joint limits are in radians. A lower or upper limit beyond +-12.566 is more "
    "than two full turns each way, which means degrees were written (90 for 1.5708), or a "
    "large number stands for 'no limit'. Real joints that turn a little more than once (a "
    "wrist's +-400 degrees) stay below it. A joint that turns without end is `continuous`; "
    "otherwise convert the limits to radians.",
    bad=_arm(lower="-90", upper="90"),
    good=_arm(),
    consumers=_ALL,
)
VELOCITY_DEGREES = Rule(
    "velocity-degrees",
    W,
    Family.JOINTS,
    summary="A revolute joint's velocity limit reads as degrees per second.",
    explanation="Velocity limits are in radians per second. A revolute joint limited to a round "
    "number of degrees per second (45, 90, 180, 360: a multiple of 15 from 45 up) is beyond "
    "what robot joints do (fast legged-robot motors reach about 30 rad/s), so planners and "
    "controllers take the joint as many times faster than it is. Divide by 57.3 (180 deg/s is "
    "3.1416 rad/s).",
    bad=_arm(velocity="180"),
    good=_arm(),
    consumers=_ALL,
)
ZERO_LIMIT = Rule(
    "zero-limit",
    W,
    Family.JOINTS,
    summary="A moving joint's effort or velocity limit is 0.",
    explanation='A `<limit>` with `effort="0"` or `velocity="0"` says the joint may not push '
    "or may not move: Gazebo and ros2_control clamp every command to nothing, and MoveIt cannot "
    "plan for it. It usually comes from copying a fixed joint's template. Give the motor's real "
    "limits.",
    bad=_arm(effort="0"),
    good=_arm(),
    consumers=_ALL,
)
RPY_DEGREES = Rule(
    "rpy-degrees",
    W,
    Family.JOINTS,
    summary="An <origin>'s rpy holds an angle beyond a whole turn (2 pi), as degrees would.",
    explanation="Roll, pitch and yaw are in radians. An angle beyond +-6.2832 is more than a "
    "whole turn, which almost always means degrees were written (90 for a quarter turn, which "
    "is 1.5708). Write radians; xacro's `${radians(90)}` or `${pi/2}` help.",
    bad=_arm(rpy="0 0 90"),
    good=_arm(),
    consumers=_ALL,
)
_WHEEL_LIMIT = """\
<robot name="upkie">
  <link name="base_link"/>
  <link name="wheel_link"/>
  <joint name="wheel_joint" type="{type}">
    <parent link="base_link"/><child link="wheel_link"/><axis xyz="0 1 0"/>
    <limit effort="1.7" velocity="10"/>
  </joint>
</robot>
"""
LIMIT_UNSET = Rule(
    "limit-unset",
    W,
    Family.JOINTS,
    summary="A revolute or prismatic joint's <limit> leaves out lower or upper, which then "
    "read as 0.",
    explanation="URDF gives a bound left out the value 0, so `<limit effort velocity>` alone "
    "holds a revolute or prismatic joint at 0: urdfdom, and so robot_state_publisher, MoveIt and "
    "Gazebo (through sdformat), read 0 to 0, joint_state_publisher shows a slider that does "
    "not move, and pinocchio's limits are 0 and 0. MuJoCo and PyBullet leave such a joint free "
    "instead (with one bound given, MuJoCo still does; PyBullet reads a missing upper as -1 "
    "and limits the joint only when lower <= upper), so it moves in one program and not in "
    "another. A joint that turns without end, such as a wheel's, is `continuous`; otherwise "
    "write both bounds.",
    bad=_WHEEL_LIMIT.format(type="revolute"),
    good=_WHEEL_LIMIT.format(type="continuous"),
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.MUJOCO, Consumer.PYBULLET),
)
MIMIC_CHAIN = Rule(
    "mimic-chain",
    W,
    Family.JOINTS,
    summary="A joint mimics a joint that mimics another, or mimics with a multiplier of 0.",
    explanation="robot_state_publisher and MoveIt follow one step of mimicry: a joint that "
    "mimics a mimic joint is moved by the first joint's value in some programs and the second's "
    "in others. A multiplier of 0 holds the joint still at its offset, which a fixed joint says "
    "plainly. Point every mimic at the joint that is really driven, with a non-zero multiplier.",
    bad="""\
<robot name="gripper">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="continuous">
    <parent link="palm"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous">
    <parent link="palm"/><child link="right"/><mimic joint="left_joint" multiplier="0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="gripper">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="continuous">
    <parent link="palm"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous">
    <parent link="palm"/><child link="right"/><mimic joint="left_joint" multiplier="-1"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
MIMIC_FIXED = Rule(
    "mimic-fixed",
    W,
    Family.JOINTS,
    summary="A fixed joint has a <mimic>, or a joint mimics a fixed joint.",
    explanation="A fixed joint never moves: a `<mimic>` on it moves nothing, and a joint that "
    "mimics it follows a joint that has no position. check_urdf accepts both, and "
    "robot_state_publisher publishes a fixed joint once, as a static transform, whatever it "
    "mimics. A joint that mimics a fixed joint is where programs part: joint_state_publisher "
    "leaves fixed joints out and fails with a KeyError when it publishes the follower; "
    "pinocchio, asked to read mimics, refuses the file (the mimicked joint is not in its "
    "kinematic tree) and otherwise moves the joint on its own; fishbot's kinematics hold it at "
    "its offset. A robot reduced by turning joints fixed often keeps their mimics. Delete the "
    "`<mimic>` of a fixed joint; point a follower at the joint that really drives it, or make "
    "it fixed too.",
    bad="""\
<robot name="gripper">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="fixed">
    <parent link="palm"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous">
    <parent link="palm"/><child link="right"/><mimic joint="left_joint" multiplier="-1"/>
  </joint>
</robot>
""",
    good="""\
<robot name="gripper">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="continuous">
    <parent link="palm"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous">
    <parent link="palm"/><child link="right"/><mimic joint="left_joint" multiplier="-1"/>
  </joint>
</robot>
""",
    consumers=(Consumer.URDFDOM,),
)
