"""The rules on names and the link tree.

Data only: the checks that report them are in `fishbot_urdf.rules`.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..diagnostics import Consumer, Facts, Family, Rule, Severity

_SIMULATORS = (Consumer.GAZEBO, Consumer.MUJOCO, Consumer.DRAKE, Consumer.PYBULLET)
_ALL = (Consumer.URDFDOM, *_SIMULATORS)
E = Severity.ERROR
NO_LINKS = Rule(
    "no-links",
    E,
    Family.STRUCTURE,
    summary="The robot has no links.",
    explanation="A robot is made of links, and needs at least one. check_urdf fails on a "
    "`<robot>` with none (`No link elements found in urdf file`), and so do Gazebo and PyBullet. "
    "In a xacro file it usually means the links are in a macro that is never called, or in a file "
    "that is never included.",
    bad="""\
<robot name="fishbot">
  <material name="blue">
    <color rgba="0 0 1 1"/>
  </material>
</robot>
""",
    good="""\
<robot name="fishbot">
  <material name="blue">
    <color rgba="0 0 1 1"/>
  </material>
  <link name="base_link"/>
</robot>
""",
    # MuJoCo and Drake load an empty model.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.PYBULLET),
)
DUPLICATE_LINK = Rule(
    "duplicate-link",
    E,
    Family.STRUCTURE,
    summary="Two links have the same name.",
    explanation="Links are found by name, by joints, TF and every tool, so each name may be used "
    "once. check_urdf fails with `link 'wheel_link' is not unique`, and Gazebo, MuJoCo, Drake and "
    "PyBullet refuse the file too. It often comes from a xacro macro called twice without a "
    "prefix that makes its names differ; give each link its own name.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="wheel_link"/>
  <link name="wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
DUPLICATE_JOINT = Rule(
    "duplicate-joint",
    E,
    Family.STRUCTURE,
    summary="Two joints have the same name.",
    explanation="Joint names must be unique too: joint states and controllers name the joint they "
    "mean. check_urdf fails with `joint 'wheel_joint' is not unique`, Gazebo and Drake refuse the "
    "file, and PyBullet crashes on it. Name each joint after what it moves.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    # MuJoCo 4.0 loads two joints of one name.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.DRAKE, Consumer.PYBULLET),
)
DUPLICATE_MATERIAL = Rule(
    "duplicate-material",
    E,
    Family.STRUCTURE,
    summary="Two materials at the robot's top level have the same name.",
    explanation="A material defined directly in `<robot>` is shared, by name, with every "
    "`<visual>` that names it, so two of them with one name leave the colour in doubt. check_urdf "
    "fails with `material 'blue' is not unique`, Gazebo refuses the file, and Drake refuses two "
    "definitions that differ. Keep one, or give the other its own name.",
    bad="""\
<robot name="fishbot">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <material name="blue"><color rgba="0 0 0.8 1"/></material>
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="blue"/>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <material name="dark_blue"><color rgba="0 0 0.8 1"/></material>
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="blue"/>
    </visual>
  </link>
</robot>
""",
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.DRAKE),
)


@dataclass(frozen=True, slots=True, kw_only=True)
class UndefinedLinkFacts(Facts):
    """The facts of an `undefined-link` finding."""

    end: str
    """Which end of the joint names it: ``parent`` or ``child``."""
    link: str
    """The link name that is not defined."""


UNDEFINED_LINK = Rule(
    "undefined-link",
    E,
    Family.STRUCTURE,
    summary="A joint's parent or child names a link that is not defined.",
    explanation="A joint connects two links by name, and both must be defined in the robot. "
    "check_urdf fails (`parent link [base] of joint [laser_joint] not found`), and Gazebo, "
    "MuJoCo, Drake and PyBullet refuse the file too. The cause is usually a typo, or a prefix "
    "that a xacro macro puts on one name and not on the other, or a ROS suffix left off "
    "(`left_wheel` for `left_wheel_link`); fishbot suggests the closest link name and lists the "
    "links, those most like the name first, and how many more there are.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base"/>
    <child link="laser_link"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/>
    <child link="laser_link"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
JOINT_SELF_LOOP = Rule(
    "joint-self-loop",
    E,
    Family.STRUCTURE,
    summary="A joint's parent and child are the same link.",
    explanation="A joint connects a parent link to another link, its child. With one link at both "
    "ends, check_urdf still reports success but leaves that link out of the tree it prints, and "
    "Gazebo and PyBullet load the robot without it; MuJoCo and Drake refuse the file. Name as "
    "parent the link the child is attached to.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="laser_link"/>
    <child link="laser_link"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/>
    <child link="laser_link"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
MISSING_LIMIT = Rule(
    "missing-limit",
    E,
    Family.STRUCTURE,
    summary="A revolute or prismatic joint has no <limit>.",
    explanation="A revolute or prismatic joint moves between end stops, so it needs `<limit lower "
    "upper effort velocity>`. check_urdf fails with `is of type REVOLUTE but it does not specify "
    "limits`, and Gazebo and PyBullet refuse the joint; MuJoCo and Drake let it move without end. "
    "A joint that turns without end, such as a wheel's axle, is continuous and needs no limit.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="1.0" velocity="2.0"/>
  </joint>
</robot>
""",
    # MuJoCo and Drake read a revolute joint without <limit> as one that turns freely.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.PYBULLET),
)
LIMIT_RANGE = Rule(
    "limit-range",
    E,
    Family.STRUCTURE,
    summary="A joint's lower limit is above its upper limit.",
    explanation="`lower` must not be above `upper`. check_urdf accepts such a joint, but the "
    "simulators each read it their own way: Gazebo swaps the two with a warning, MuJoCo and "
    "PyBullet drop the limit and let the joint turn past it, and Drake refuses the joint. Swap "
    "the two values, or check the sign of each.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="1.57" upper="-1.57" effort="1.0" velocity="2.0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="1.0" velocity="2.0"/>
  </joint>
</robot>
""",
    consumers=_SIMULATORS,
)
NEGATIVE_LIMIT = Rule(
    "negative-limit",
    E,
    Family.STRUCTURE,
    summary="A joint's effort or velocity limit is negative.",
    explanation="`effort` (N or N*m) and `velocity` (m/s or rad/s) are the most a joint may push "
    "and move, in either direction, so they are zero or more. check_urdf accepts a negative one, "
    "but Gazebo reads it as no limit at all, and Drake refuses a negative velocity. Write the "
    "magnitude.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="1.0" velocity="-2.0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="camera_link"/>
  <joint name="camera_joint" type="revolute">
    <parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="1.0" velocity="2.0"/>
  </joint>
</robot>
""",
    # MuJoCo ignores the two values; PyBullet keeps them but does not apply them.
    consumers=(Consumer.GAZEBO, Consumer.DRAKE),
)
ZERO_AXIS = Rule(
    "zero-axis",
    E,
    Family.STRUCTURE,
    summary="A moving joint's axis is 0 0 0.",
    explanation="A joint turns about, or slides along, its `<axis>`, which therefore cannot be 0 "
    "0 0. check_urdf accepts it, but the KDL tree robot_state_publisher builds gives every link "
    "below the joint a NaN pose, and so does PyBullet; Gazebo reports an error and turns about 0 "
    "0 1 instead, and MuJoCo and Drake refuse the file. Give the direction, such as `0 1 0` for a "
    "wheel whose axle lies along y.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/>
    <child link="left_wheel_link"/>
    <axis xyz="0 0 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/>
    <child link="left_wheel_link"/>
    <axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
UNDEFINED_MIMIC = Rule(
    "undefined-mimic",
    E,
    Family.STRUCTURE,
    summary="A <mimic> names a joint that does not exist, its own joint, or a loop of mimics.",
    explanation='`<mimic joint="...">` makes a joint follow another one, named exactly. '
    "check_urdf accepts a name that matches no joint, but MoveIt logs an error and moves the "
    "joint on its own, MuJoCo ignores the mimic, and Drake refuses the file. Name the joint to "
    "follow. Joints that mimic each other round a loop (`a` follows `b`, `b` follows `a`) have "
    "no joint that moves of its own: let one of them lead.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
    <mimic joint="left_wheel"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
    <mimic joint="left_wheel_joint"/>
  </joint>
</robot>
""",
    # Gazebo and PyBullet read no <mimic> at all, right or wrong.
    consumers=(Consumer.URDFDOM, Consumer.MUJOCO, Consumer.DRAKE),
)
MULTIPLE_PARENTS = Rule(
    "multiple-parents",
    E,
    Family.STRUCTURE,
    summary="A link is the child of more than one joint.",
    explanation="In URDF every link but the root hangs from exactly one joint; a link that is the "
    "child of two joints closes a loop, which a tree cannot hold. check_urdf accepts it and "
    "prints the link twice, Gazebo counts the link's mass twice (with fixed joints), MuJoCo and "
    "Drake refuse the file, and PyBullet crashes. Keep one of the joints.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
  <joint name="laser_mount_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)


@dataclass(frozen=True, slots=True, kw_only=True)
class RootsFacts(Facts):
    """The facts of a `multiple-roots` finding."""

    roots: tuple[str, ...]
    """The root links, in file order."""


MULTIPLE_ROOTS = Rule(
    "multiple-roots",
    E,
    Family.STRUCTURE,
    summary="More than one link is no joint's child.",
    explanation="Every link but one must be some joint's child; the one that is not is the root "
    "the whole robot hangs from. A link that no joint reaches, usually because its joint was "
    "forgotten, is a second root: check_urdf fails with `Two root links found`, Gazebo refuses "
    "the file, PyBullet crashes, and Drake lets the extra part fall away as a body of its own. "
    "Add the joint that attaches it.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="imu_link"/>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed">
    <parent link="base_link"/><child link="imu_link"/>
  </joint>
</robot>
""",
    # MuJoCo welds every root link to the world, as it does the first.
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO, Consumer.DRAKE, Consumer.PYBULLET),
)
NO_ROOT = Rule(
    "no-root",
    E,
    Family.STRUCTURE,
    summary="Every link is some joint's child.",
    explanation="When every link is some joint's child, the joints form a loop and the robot has "
    "no root to hang from. check_urdf fails with `No root link found`, and Gazebo, MuJoCo, Drake "
    "and PyBullet refuse the file too. Look for a joint whose parent and child are swapped; the "
    "`cycle` finding names the loop.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
  <joint name="base_joint" type="fixed">
    <parent link="laser_link"/><child link="base_link"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_link"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)


@dataclass(frozen=True, slots=True, kw_only=True)
class LoopFacts(Facts):
    """The facts of a `cycle` finding."""

    joints: tuple[str, ...]
    """The joints of the loop."""


CYCLE = Rule(
    "cycle",
    E,
    Family.STRUCTURE,
    summary="Joints form a loop.",
    explanation="URDF describes a tree: following joints from parent to child never leads back to "
    "a link already passed. When a loop leaves out the root, check_urdf reports success but "
    "silently leaves the loop's links out of the robot, and Gazebo and PyBullet do the same; "
    "MuJoCo and Drake refuse the file. Break the loop by giving each link its one parent on the "
    "way out from the root.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="right_wheel_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="left_wheel_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <link name="right_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
""",
    consumers=_ALL,
)
UNREACHABLE_LINK = Rule(
    "unreachable-link",
    E,
    Family.STRUCTURE,
    summary="A link is not connected to the root (it hangs below a joint loop).",
    explanation="A link that hangs below a joint loop cannot be reached from the root, so it has "
    "no place in the robot. check_urdf reports success without it, Gazebo and PyBullet load the "
    "robot without it, and MuJoCo and Drake refuse the file. Break the loop (see `cycle`) and the "
    "link is attached again.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="arm_link"/>
  <link name="hand_link"/>
  <link name="tool_link"/>
  <joint name="arm_joint" type="fixed"><parent link="hand_link"/><child link="arm_link"/></joint>
  <joint name="hand_joint" type="fixed"><parent link="arm_link"/><child link="hand_link"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="hand_link"/><child link="tool_link"/></joint>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="arm_link"/>
  <link name="hand_link"/>
  <link name="tool_link"/>
  <joint name="arm_joint" type="fixed"><parent link="base_link"/><child link="arm_link"/></joint>
  <joint name="hand_joint" type="fixed"><parent link="arm_link"/><child link="hand_link"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="hand_link"/><child link="tool_link"/></joint>
</robot>
""",
    consumers=_ALL,
)
