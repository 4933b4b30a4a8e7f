"""The rules on the names that extensions and materials give.

Data only: the checks that report them are in `fishbot_urdf.rules`.
"""

from __future__ import annotations

from ..diagnostics import Consumer, Family, Rule, Severity

E, W = Severity.ERROR, Severity.WARNING
UNKNOWN_REFERENCE = Rule(
    "unknown-reference",
    E,
    Family.REFERENCES,
    summary="A <gazebo reference>, <transmission>, <ros2_control> or Gazebo plugin names a link "
    "or joint the robot does not have.",
    explanation="These elements name the robot's parts, and no URDF reader looks at them: a typo "
    "passes check_urdf and RViz, then the simulation quietly goes wrong. Gazebo drops a "
    "`<gazebo reference>` block that names nothing (the friction or colour never applies), the "
    "controller manager refuses a `<ros2_control>` joint it cannot find, and a differential drive "
    "plugin with a wrong joint never moves the wheels. Use the exact link or joint name.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <gazebo reference="left_wheel_lnk"><mu1>0.9</mu1></gazebo>
  <ros2_control name="fishbot" type="system">
    <joint name="left_whel_joint"><command_interface name="velocity"/></joint>
  </ros2_control>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <gazebo reference="left_wheel_link"><mu1>0.9</mu1></gazebo>
  <ros2_control name="fishbot" type="system">
    <joint name="left_wheel_joint"><command_interface name="velocity"/></joint>
  </ros2_control>
</robot>
""",
    consumers=(Consumer.GAZEBO, Consumer.ROS2_CONTROL),
)
CONTROL_INTERFACE = Rule(
    "control-interface",
    E,
    Family.REFERENCES,
    summary="A <ros2_control> joint is fixed or has more than one axis, or names an interface "
    "that looks like a misspelt standard one.",
    explanation="ros2_control drives joints of one degree of freedom through the standard "
    "interfaces `position`, `velocity`, `acceleration` and `effort`. A fixed joint has nothing to "
    "command, planar and floating joints are not supported by the Gazebo hardware plugins, and an "
    "interface such as `postion` is taken as a custom one no controller claims, so the controller "
    "fails to start. Control moving joints, and spell the interfaces as ros2_control does.",
    bad="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <ros2_control name="fishbot" type="system">
    <joint name="left_wheel_joint"><command_interface name="velocty"/></joint>
  </ros2_control>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link"/>
  <link name="left_wheel_link"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel_link"/><axis xyz="0 1 0"/>
  </joint>
  <ros2_control name="fishbot" type="system">
    <joint name="left_wheel_joint"><command_interface name="velocity"/></joint>
  </ros2_control>
</robot>
""",
    consumers=(Consumer.GAZEBO, Consumer.ROS2_CONTROL),
)
UNDEFINED_MATERIAL = Rule(
    "undefined-material",
    W,
    Family.REFERENCES,
    summary="A visual names a material that has no colour or texture anywhere.",
    explanation='`<material name="blue"/>` with no `<color>` inside borrows the colour of a '
    "material of that name defined at the robot's top level (or in an earlier visual). When "
    "there is none, check_urdf only warns `material 'blue' undefined` and RViz draws the part in "
    "its default colour. Define the material once at the top level, or give the visual its "
    "`<color>`.",
    bad="""\
<robot name="fishbot">
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
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="blue"/>
    </visual>
  </link>
</robot>
""",
)
MATERIAL_CONFLICT = Rule(
    "material-conflict",
    W,
    Family.REFERENCES,
    summary="One material name is given different colours in different places.",
    explanation="urdfdom keeps one material per name: the top-level definition, or else the "
    "first visual that defines it. Every later visual that uses the name with another "
    "`<color>` is drawn in the first colour by RViz, while Gazebo and other readers use the "
    "visual's own, so the robot looks different in each. Give each colour its own material "
    "name.",
    bad="""\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="paint"><color rgba="0 0 1 1"/></material>
    </visual>
    <visual>
      <geometry><sphere radius="0.05"/></geometry>
      <material name="paint"><color rgba="1 0 0 1"/></material>
    </visual>
  </link>
</robot>
""",
    good="""\
<robot name="fishbot">
  <link name="base_link">
    <visual>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
      <material name="blue"><color rgba="0 0 1 1"/></material>
    </visual>
    <visual>
      <geometry><sphere radius="0.05"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material>
    </visual>
  </link>
</robot>
""",
    consumers=(Consumer.URDFDOM, Consumer.GAZEBO),
)
